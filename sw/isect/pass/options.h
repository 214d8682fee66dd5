// The options and counters of the intersection kernels (docs/intersection.md): which
// mapping, multiplier and origin handling a call uses, its number formats and culling,
// and what a call reports (KernelStats). The entry point is intersect_fmpp (kernels.h).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

class PassShare;  // pass.h
class FormCache;  // form_cache.h

enum class Mapping { kRay, kObject };
enum class MulMode { kGeneric, kConst };
// How rays with different origins are handled in the ray-parallel mapping:
//   group:   one set of inverse matrices per distinct origin (the paper's method);
//   general: every ray through the arbitrary-origin (Pluecker) formulation;
//   auto:    the paper's method for origins shared by many rays, general for the rest,
//            and general for rays with tmin > 0 or an excluded triangle.
enum class Origins { kAuto, kGroup, kGeneral };

Mapping parse_mapping(const std::string& s);    // "ray" | "object"
MulMode parse_mul_mode(const std::string& s);   // "generic" | "const"
Origins parse_origins(const std::string& s);    // "auto" | "group" | "general"
const char* to_string(Mapping m);
const char* to_string(MulMode m);
const char* to_string(Origins o);

// The kernel options, declared once: every field of KernelOptions is a row of this list,
// from which the struct, the forms' equality (form_cache.cpp), the plan's cache key
// (plan/plan_cache.cpp), the agreement between MPI ranks (mpi/render_chips.cpp), the
// reports' JSON (stats_json.h: options_json) and the command-line flags of fmpp-intersect
// (all of them) and fmpp-render (those with a render role; sw/tools/kernel_flags.h) are
// derived. tests/isect/kernel_options_test.cpp checks every row in every derived use.
//
// X(type, field, default, kind, lo, hi, roles, flag, report name, help, fmpp-render's help,
//   why a role is missing)
//   kind:  OptValue (--flag V, V in [lo, hi]), OptSet (a bool, true with --flag), OptClear
//          (a bool, false with --flag), OptNamed<Names> (one of Names::kAll, by name)
//   roles: OptionRole below; fmpp-intersect declares every flag
//   fmpp-render's help: "" for the same as fmpp-intersect's
//   why: required when a role of kFormIdentity, kPlanKey, kAgreed, kReported is missing
#define FMPP_KERNEL_OPTIONS(X)                                                                                        \
  X(Mapping, mapping, Mapping::kRay, OptNamed<MappingNames>, 0, 0,                                                      \
    kFormIdentity | kPlanKey | kAgreed | kReported | kRenderPlanned, "--mapping", "mapping", "ray | object",         \
    "ray | object: every batch of rays sharing an origin in that mapping (default: ray-parallel, and "             \
    "object-parallel for a kind of batch, primary or shadow, where the precision plan's cost model finds "          \
    "it cheaper; secondary rays always ray-parallel)",                                                              \
    "")                                                                                                             \
  X(MulMode, mul, MulMode::kConst, OptNamed<MulModeNames>, 0, 0,                                                        \
    kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag, "--mul", "multiply",                             \
    "multiply: const (CSD, specialised to the broadcast constant) | generic", "const | generic", "")               \
  /* multiplier bits: matrix mantissas (ray-parallel), ray components (object-parallel) */                         \
  X(unsigned, n, 24, OptValue, 2, 32, kFormIdentity | kAgreed | kReported | kRenderPlanned, "--bits", "bits",         \
    "multiplier bits n", "multiplier bits n (default: chosen by the precision plan)",                             \
    "plan key: the plan chooses n; the user's --bits is in the key as PlanRequest::bits")                           \
  /* ray-parallel: |V| components quantized to at most 2^vbits */                                                   \
  X(unsigned, vbits, 28, OptValue, 2, 28, kFormIdentity | kPlanKey | kAgreed, "--vbits", "vbits",                      \
    "ray-parallel: bits of the ray components (the multiplicand)", "",                                             \
    "reported: fmpp-render has no flag for it (always the default), and its report keeps the fields its readers " \
    "know")                                                                                                         \
  /* object-parallel: matrix mantissas below 2^mbits */                                                             \
  X(unsigned, mbits, 28, OptValue, 2, 28, kFormIdentity | kPlanKey | kAgreed, "--mbits", "mbits",                      \
    "object-parallel: bits of the matrix mantissas (the multiplicand)", "",                                        \
    "reported: as vbits")                                                                                           \
  /* Triangles whose condition number (|P| |P^-1|, max norms) exceeds 2^cond_bits are                               \
     intersected on the host instead. Negative: min(n, vbits) - 3 (ray-parallel),                                   \
     min(n, mbits) - 3 (object-parallel). The arbitrary-origin kernel compares its own                              \
     edge-test condition (docs/intersection.md) with 2^cond_bits, by default 2^(n - 4). */                          \
  X(int, cond_bits, -1, OptValue, -1, 60, kPlanKey | kAgreed, "--cond-bits", "cond_bits",                              \
    "triangles with condition number above 2^this go to the host (-1: chosen from the bits)", "",                  \
    "form identity: a prepared form compares it itself (RayForm::serves); reported: as vbits")                     \
  /* Certified forms: the relative accuracy a returned t must have (its certified bound); a                         \
     hit whose bound is looser gets its t computed exactly on the host. 0: the default                              \
     policy::t_accuracy = 2^-12. */                                                                                 \
  X(double, t_accuracy, 0, OptValue, 0.0, 0.5, kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag,          \
    "--t-accuracy", "t_accuracy",                                                                                   \
    "relative accuracy of a certified t; a hit whose bound is looser gets its t on the host "                      \
    "(0: the default, docs/intersection.md)",                                                                       \
    "", "")                                                                                                         \
  /* How rays with different origins are handled in the ray-parallel mapping (Origins). */                         \
  X(Origins, origins, Origins::kAuto, OptNamed<OriginsNames>, 0, 0, kFormIdentity | kPlanKey | kAgreed, "--origins",   \
    "origins",                                                                                                      \
    "ray mapping, rays with different origins: auto (paper's method for large shared-origin groups, "              \
    "general formulation for the rest) | group | general",                                                         \
    "", "reported: as vbits")                                                                                       \
  /* With origins auto and several origins in a call: an origin shared by fewer rays than                           \
     this goes, with its rays, into the call's arbitrary-origin batch, whose passes it then                         \
     shares with the other such rays (merged batches: fuller passes, each broadcast dearer).                        \
     0: max(16, blocks / 8); 1: no origin's rays are merged. The precision plan chooses it                          \
     from its cost model (docs/raytracer.md). The same answers for any value. */                                    \
  X(unsigned, merge_below, 0, OptValue, 0, 1 << 24, kAgreed | kReported | kRenderPlanned, "--merge-below",             \
    "merge_below",                                                                                                  \
    "with --origins auto: the rays of an origin shared by fewer rays than this take the arbitrary-origin "         \
    "kernel (1: none; 0: max(16, blocks / 8))",                                                                     \
    "rays of an origin shared by fewer rays than this join the arbitrary-origin batch (1: none; 0: "              \
    "max(16, blocks / 8)); default: the plan's choice, from its cost model",                                       \
    "form identity: it steers a call, not a form; plan key: the plan chooses it, the user's --merge-below is in "  \
    "the key as PlanRequest::merge_below")                                                                          \
  /* Watertight test for rays sharing an origin (ray-parallel): edge functions                                      \
     ((P_j - O) x (P_k - O)) . V on the scene's own vertices, certified: a ray whose                                \
     decision is not certain (a ray through a shared edge included) is redone exactly,                              \
     so no ray slips between two triangles and no vertex moves. */                                                  \
  X(bool, watertight, false, OptSet, 0, 0, kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag,              \
    "--watertight", "watertight",                                                                                   \
    "certified edge functions for rays sharing an origin (no cracks, no vertex moved)",                            \
    "certified edge functions for primary and shadow rays (no cracks, no vertex moved)", "")                       \
  /* general formulation: bits of the depth quotient t / u */                                                       \
  X(unsigned, qbits, 20, OptValue, 4, 28, kFormIdentity | kPlanKey | kAgreed, "--qbits", "qbits",                      \
    "general formulation: bits of the distance quotient", "", "reported: as vbits")                                \
  /* Gates (pass.h, ProgramMarks): a broadcast whose program has one sends its tail (the                            \
     distance, the comparison with the best) only when the ANY responder says some block                            \
     may be inside the triangle. Results are the same either way; off: every tail is sent. */                       \
  X(bool, gates, true, OptClear, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--no-gates", "gates",           \
    "send every broadcast whole, without asking the ANY responder whether some block may be inside its "           \
    "triangle before its distance part (the same answers, more clocks)",                                           \
    "", "form identity: it steers a call, not a form")                                                             \
  /* Ray-parallel: per pass, skip the broadcast of triangles no ray of the pass can reach                           \
     (cull.h: a hierarchy over the triangles against packets of cull_packet consecutive                             \
     rays, padded by the fixed point's error). Culling can only drop triangles for which                            \
     the FMPP would report no hit, so results are the same with and without it. */                                  \
  X(bool, cull, true, OptClear, 0, 0, kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag, "--no-cull",       \
    "cull", "broadcast every triangle in every pass", "", "")                                                      \
  /* Culling, front to back: each pass first broadcasts the nearest leaves of every ray                             \
     (a probe), reads the distances found, and then broadcasts, from a fresh start, only                            \
     the triangles that may lie as near as those (ray_parallel_pick.cpp). */                                        \
  X(bool, cull_probe, true, OptClear, 0, 0, kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag,             \
    "--no-probe", "cull_probe", "culling without the front-to-back probe",                                         \
    "culling without the front-to-back probe of rays with their own origins", "")                                  \
  /* Culling on the FMPP (box_test.h): for rays sharing an origin (the paper's form), the                           \
     host walks its hierarchy front to back per pass, tests each node against the pass's                            \
     packets itself and then on the FMPP (every block its own ray, against its current                              \
     best; the ANY responder answers), and broadcasts the leaves reached as it goes. In                             \
     place of the per-ray walk and the probe for those rays. */                                                     \
  X(bool, fmpp_boxes, true, OptClear, 0, 0, kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag,             \
    "--no-fmpp-boxes", "fmpp_boxes",                                                                                \
    "culling of rays sharing an origin by the host's per-ray walk and probe, not by the FMPP's box tests", "", "") \
  /* Diagonals in the FMPP's leaf tests (box_test.h, set_slope_compares): where the blocks hold                        \
     the constant multiply's pair words, a leaf's test also compares V_j + V_k and                                  \
     V_j - V_k with the triangle's range of slopes, where the host's guess says it pays.                            \
     Results are the same either way; off: the rectangle of the slopes alone. */                                    \
  X(bool, box_diagonals, true, OptClear, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--no-box-diagonals",    \
    "box_diagonals",                                                                                                \
    "FMPP box tests of leaves against the rectangle of the triangle's slopes only, without its diagonals (the "    \
    "same answers, more clocks)",                                                                                   \
    "", "form identity: it steers a call, not a form")                                                             \
  /* Edges in the FMPP's leaf tests (box_slopes.h): for each edge of the triangle in the                            \
     slope plane, a word the blocks form with one ADD or SUB, compared with the                                     \
     triangle's extreme along it, where the host's guess says it pays. Results are the                              \
     same either way. */                                                                                             \
  X(bool, box_edges, true, OptClear, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--no-box-edges",            \
    "box_edges",                                                                                                    \
    "FMPP box tests of leaves without the compares along the triangle's edges (the same answers, more clocks)",    \
    "", "form identity: it steers a call, not a form")                                                             \
  /* Reads in the FMPP's leaf tests (box_test.h): where the few rays that could need a                                \
     leaf are known to the host and their reach words are not, it reads those words                                 \
     (kReadLimit) instead of testing the leaf on the FMPP. Results are the same either                               \
     way. */                                                                                                          \
  X(bool, box_reads, true, OptClear, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--no-box-reads",            \
    "box_reads",                                                                                                    \
    "FMPP box tests of leaves always on the FMPP, never decided by reading the reach words of the few rays that "  \
    "could need the leaf (the same answers, more clocks)",                                                          \
    "", "form identity: it steers a call, not a form")                                                             \
  /* The host's run of the broadcasts' heads (docs/certification.md, "The host's run of                            \
     the leaf tests and the gates"): where the form gives its gate as a function of the                              \
     words the host loads (GateRows, RayForm::may_affect), a broadcast that would affect                             \
     no ray of the pass is left out, and the gate's read where the host knows some ray                               \
     passes. Results are the same either way. */                                                                     \
  X(bool, host_gates, true, OptClear, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--no-host-gates",          \
    "host_gates",                                                                                                   \
    "never run the broadcasts' gates on the host: leave out only what culling's boxes leave out, and ask each "    \
    "gate on the FMPP (the same answers, more clocks)",                                                             \
    "", "form identity: it steers a call, not a form")                                                             \
  /* Read-back (best_cache.h): a pass reads only the bests that changed since the host                              \
     last knew them (one flag plane per 64 blocks tells which); off: every block's. The                              \
     same answers either way. */                                                                                     \
  X(bool, changed_reads, true, OptClear, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--no-changed-reads",   \
    "changed_reads", "read back every block's best, not only the changed ones (the same answers, more clocks)", "", \
    "form identity: it steers the read-back, not a form")                                                           \
  X(unsigned, cull_packet, 1, OptValue, 1, 65536, kFormIdentity | kPlanKey | kAgreed | kReported | kRenderFlag,       \
    "--cull-packet", "cull_packet", "rays per culling packet", "", "")                                             \
  /* Rays of their own origins: the rounds the front-to-back probe may take in a pass,                              \
     its first included (cull/tuning.h, ray_parallel_pick.cpp: each round sends the next leaves                      \
     of each ray's front, reads back the probing rays' bests and cuts their reach). */                               \
  X(unsigned, max_probe_rounds, 8, OptValue, 1, 64, kPlanKey | kAgreed | kReported | kRenderFlag, "--probe-rounds", \
    "max_probe_rounds", "probe rounds in a pass for rays of their own origins, the first included (1: no more)",   \
    "",                                                                                                             \
    "form identity: it steers the passes, not a form")                                                               \
  /* Ray-parallel: load each batch's rays into passes in a coherent order (order.h:                                 \
     square image tiles for primary rays, octant and origin for the others) rather than                             \
     in the caller's order. Results come back in the caller's order either way. */                                  \
  X(bool, coherent, true, OptNamed<PassOrderNames>, 0, 0, kPlanKey | kAgreed | kReported | kRenderFlag, "--pass-order", \
    "pass_order", "coherent (image tiles, octant and origin) | batch (the rays' own order)", "",                   \
    "form identity: it steers a call, not a form")                                                                  \
  /* Occlusion queries (shadow rays): for a ray with a finite tmax whose hint is -1 or                              \
     proven beyond its reach (Ray::hint, plane_beyond_reach), any certified hit certainly                           \
     before tmax may come back instead of the nearest, so that the FMPP's box tests stop                            \
     sending a ray further boxes once it has one (box_test.h). Every other ray, and one                             \
     without such a hit, gets the nearest as always. So whether the nearest hit before                              \
     tmax is a triangle other than the hint reads the same from either answer. */                                   \
  X(bool, occlusion, false, OptSet, 0, 0, kAgreed, "--occlusion", "occlusion",                                         \
    "occlusion queries: a ray with a finite tmax may get any certified hit certainly before its tmax "             \
    "instead of the nearest",                                                                                       \
    "",                                                                                                             \
    "form identity: it steers a call; plan key and report: fmpp-render sets it per call from "                     \
    "--no-shadow-stop, which its key and report hold as shadow_stop")                                               \
  /* Count, per pass, the broadcasts the any-hit and nearest-hit oracles would make                                 \
     (oracle.h; KernelStats::oracle_*): host work with the exact reference, for reports. */                         \
  X(bool, oracle, false, OptSet, 0, 0, kAgreed | kRenderFlag, "--oracle", "oracle",                                    \
    "also count, per pass, what the any-hit, nearest-hit and box oracles would send",                              \
    "also count, per pass, the triangles some ray hits and the nearest hits (the bound of culling; slow)",         \
    "form identity, plan key: it only counts (fmpp-render's plan never counts); reported: its counts are the "     \
    "report's \"oracle\" object")

// What a row of FMPP_KERNEL_OPTIONS takes part in.
enum OptionRole : unsigned {
  kFormIdentity = 1u << 0,   // a prepared form is reused only under the same value (form_cache.cpp)
  kPlanKey = 1u << 1,        // part of the precision plan's cache key (plan/plan_cache.cpp)
  kAgreed = 1u << 2,         // the same on every MPI rank, checked before the frame (mpi/render_chips.cpp)
  kReported = 1u << 3,       // in the reports: fmpp-render's "fmpp" object, fmpp-intersect's top level
  kRenderFlag = 1u << 4,     // a flag of fmpp-render too, its default shown
  kRenderPlanned = 1u << 5,  // a flag of fmpp-render too, no default shown: the plan chooses it unless given
};

// The kinds of a row (how its flag reads a value and how a report writes it).
struct OptValue {};
struct OptSet {};
struct OptClear {};
template <class N>
struct OptNamed {
  using Names = N;
  using Type = typename N::Type;
};
struct MappingNames {
  using Type = Mapping;
  static constexpr std::pair<const char*, Mapping> kAll[] = {{"ray", Mapping::kRay}, {"object", Mapping::kObject}};
};
struct MulModeNames {
  using Type = MulMode;
  static constexpr std::pair<const char*, MulMode> kAll[] = {{"const", MulMode::kConst},
                                                             {"generic", MulMode::kGeneric}};
};
struct OriginsNames {
  using Type = Origins;
  static constexpr std::pair<const char*, Origins> kAll[] = {
      {"auto", Origins::kAuto}, {"group", Origins::kGroup}, {"general", Origins::kGeneral}};
};
struct PassOrderNames {  // KernelOptions::coherent
  using Type = bool;
  static constexpr std::pair<const char*, bool> kAll[] = {{"coherent", true}, {"batch", false}};
};

struct KernelOptions {
#define FMPP_KERNEL_OPTION_FIELD(type, field, init, ...) type field = init;
  FMPP_KERNEL_OPTIONS(FMPP_KERNEL_OPTION_FIELD)
#undef FMPP_KERNEL_OPTION_FIELD
  // The hooks of a call, not options: never compared, keyed, agreed or reported.
  // Called after each pass with (passes done, passes planned in this call).
  std::function<void(uint64_t, uint64_t)> progress;
  // Several FMPPs: the passes of each call handed out among them (pass.h; nullptr: all here).
  PassShare* share = nullptr;
  // Shared-origin forms prepared by earlier calls, kept for later ones (form_cache.h;
  // nullptr: every call prepares its own). The same answers and clocks either way.
  FormCache* forms = nullptr;
  // Checks every option and, with the words the forms need (form_table.cpp, where it is
  // defined: the registry knows them), the device; throws std::invalid_argument naming it.
  void validate(const Config& cfg) const;
};

// A row of FMPP_KERNEL_OPTIONS without its type.
struct OptionInfo {
  const char* field;
  double lo, hi;
  unsigned roles;
  const char* flag;
  const char* report;
  const char* help;
  const char* render_help;
  const char* why;
  bool has(unsigned role) const { return (roles & role) != 0; }
};

// Calls fn(info, member pointer, kind) for every row, in the list's order.
template <class Fn>
void for_each_kernel_option(Fn&& fn) {
#define FMPP_KERNEL_OPTION_VISIT(type, field, init, kind, lo, hi, roles, flag, report, help, render_help, why) \
  fn(OptionInfo{#field, static_cast<double>(lo), static_cast<double>(hi), roles, flag, report, help, render_help, \
                why},                                                                                          \
     &KernelOptions::field, kind{});
  FMPP_KERNEL_OPTIONS(FMPP_KERNEL_OPTION_VISIT)
#undef FMPP_KERNEL_OPTION_VISIT
}

// Whether forms prepared under a and b are the same: every kFormIdentity option equal.
bool same_form_options(const KernelOptions& a, const KernelOptions& b);

struct KernelStats {
  uint64_t cycles = 0;           // FMPP bus clocks for the whole call
  uint64_t load_cycles = 0;      // writing rays or triangles into blocks, selecting blocks
  uint64_t compute_cycles = 0;   // broadcasts
  uint64_t readback_cycles = 0;  // reading results, flags and responders
  uint64_t instructions = 0;
  uint64_t broadcasts = 0;       // triangles (ray-parallel) or rays (object-parallel) sent
  uint64_t passes = 0;
  uint64_t groups = 0;           // distinct ray origins run with the paper's method
  uint64_t general_rays = 0;     // rays run with the arbitrary-origin formulation
  uint64_t broadcast_steps = 0;  // instructions in all broadcasts (for steps per broadcast)
  uint64_t test_steps = 0;       // of those, the ones up to the T >= 0 test (the paper's count)
  uint64_t overflow_rays = 0;    // rays redone on the host after an overflow
  uint64_t overflow_triangles = 0;
  uint64_t host_triangles = 0;   // triangles intersected on the host (ill-conditioned, singular as rounded)
  uint64_t degenerate_triangles = 0;  // exactly degenerate (collinear vertices): no ray meets them, skipped
  uint64_t host_tests = 0;       // ray-triangle tests the host did instead of the FMPP
  uint64_t culled = 0;           // broadcasts skipped by culling
  uint64_t box_tests = 0;        // culling: node-packet box tests on the host
  uint64_t fmpp_box_tests = 0;   // culling: box tests run on the FMPP (box_test.h)
  uint64_t read_box_tests = 0;   // culling: box tests decided by reading reach words instead
  uint64_t box_reads = 0;        // the reach words those read
  uint64_t fmpp_node_tests = 0;  // of which of inner nodes (ray_parallel_pick.cpp, tuning.h)
  uint64_t diagonal_tests = 0;   // of which with diagonal compares (box_test.h, set_slope_compares)
  uint64_t edge_tests = 0;       // of which with edge compares (box_slopes.h)
  uint64_t edge_compares = 0;    // the edge compares of those
  uint64_t box_cycles = 0;       // their clocks (program, ANY read, SEL restored)
  uint64_t gated = 0;            // broadcasts whose tail a gate skipped (no block could use it)
  uint64_t object_searches = 0;  // object-parallel: rays whose broadcast needed the maximum search (two or more possible hits)
  uint64_t unread_rays = 0;      // rays not read back: their best certainly beyond their tmax
  uint64_t probe_rounds = 0;     // probe rounds after a pass's first (rays of their own origins: tuning.h)
  // With KernelOptions::oracle: per pass, the broadcasts of triangles some ray of the pass
  // hits (any) or that are some ray's nearest hit (nearest), and their instructions.
  // (box: the triangles whose box some ray crosses before its nearest hit, oracle.h).
  uint64_t oracle_any = 0, oracle_nearest = 0, oracle_box = 0;
  uint64_t oracle_any_steps = 0, oracle_nearest_steps = 0, oracle_box_steps = 0;
  // Certification (docs/intersection.md, "Certified results"), per form: index
  // the form's FormId in the registry (forms/forms.h, which checks that it has kForms).
  static constexpr int kForms = 4;
  uint64_t form_rays[kForms] = {};       // rays each form answered
  uint64_t flagged_rays[kForms] = {};    // rays the kernel marked uncertain: redone exactly on the host
  uint64_t t_bound_rays[kForms] = {};    // certified hits whose t bound exceeded t_accuracy: t computed exactly
  uint64_t certify_tests[kForms] = {};   // host ray-triangle tests of those redos (also in host_tests)
  // Ray-parallel, per form: its broadcasts, their clocks (box tests included) and the
  // clocks of loading and reading back its rays (also in the totals above): what the
  // precision plan prices a pass with (sw/plan/pass_cost.h).
  uint64_t form_broadcasts[kForms] = {};
  uint64_t form_broadcast_cycles[kForms] = {};
  uint64_t form_io_cycles[kForms] = {};
  uint64_t uncertified_rays = 0;         // rays answered by a form that does not certify its results
  uint64_t flagged_total() const {
    uint64_t n = 0;
    for (uint64_t f : flagged_rays) n += f;
    return n;
  }
  double steps_per_broadcast() const {
    return broadcasts ? static_cast<double>(broadcast_steps) / static_cast<double>(broadcasts) : 0;
  }
  // The clocks the oracle's broadcasts would take in the same passes: load and read back
  // as measured, broadcasts at the measured clocks per instruction, no box tests.
  double oracle_cycles(uint64_t steps) const {
    const double per_step = broadcast_steps ? static_cast<double>(compute_cycles) / static_cast<double>(broadcast_steps) : 1;
    return static_cast<double>(cycles - compute_cycles - box_cycles) + per_step * static_cast<double>(steps);
  }
  double test_steps_per_broadcast() const {
    return broadcasts ? static_cast<double>(test_steps) / static_cast<double>(broadcasts) : 0;
  }
  void add(const KernelStats& o);
};


// Words per block (from the form table, sw/isect/form_table.cpp, where they are defined): of
// the form for rays sharing an origin under `opt`, and of the form for rays with their
// own origins.
unsigned words_needed(const KernelOptions& opt);
unsigned own_origin_words(const KernelOptions& opt);

}  // namespace fmpp::isect
