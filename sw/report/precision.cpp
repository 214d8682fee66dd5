// fmpp-report precision: what the FMPP's fixed-point format costs in accuracy and what
// accuracy costs in clocks, measured on the project's scenes with the golden model
// (clock-exact with the RTL), for each multiplier width n, both multiplies (generic and
// constant, bit-identical by construction) and the watertight form; plus the leak rate
// of the paper's form and the watertight one on a closed mesh around the eye.
//
// Errors are against the double-precision reference: per primary ray (intersect_fmpp
// on the camera's rays, once as the raw machine with cond_bits = 60 and once with the
// default host fallback), and per image (PSNR of the full Whitted render). The tables,
// the hard-case list and the plots (tools/plot_precision.py) make docs/precision.md.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <sstream>

#include "tb/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/isect/meshes.h"
#include "sw/isect/policy.h"
#include "sw/isect/reference.h"
#include "sw/report/output.h"
#include "sw/report/report.h"
#include "sw/rt/render.h"

#ifndef FMPP_SOURCE_DIR
#define FMPP_SOURCE_DIR "."
#endif

namespace fmpp::report {
namespace {

using namespace fmpp::isect;
using json = nlohmann::json;

struct Options : ReportOutput {
  Options() : ReportOutput("docs/precision.md", "precision-quick", "precision_data.json", "plot_precision.py") {}
  std::string scenes_dir = FMPP_SOURCE_DIR "/scenes";
  int size = 32;
};

// The machine every figure is measured on: the RTL's medium configuration (a 32 x 32
// image is one pass of primary rays), simulated by the golden model. The quick smoke
// run uses the small one (64 blocks), whose instructions simulate 16 times faster.
const Config kMachine{1024, 32};
const Config kQuickMachine{64, 32};
const char* const kScenes[] = {"cornell", "spheres_1k", "spheres_10k", "one_triangle"};

// The ways of running the kernel compared here (all ray-parallel, the renderer's mapping).
struct Form {
  const char* name;
  MulMode mul;
  bool watertight;
};
const Form kForms[] = {{"generic", MulMode::kGeneric, false},
                       {"const", MulMode::kConst, false},
                       {"watertight", MulMode::kConst, true}};

KernelOptions kernel_options(const Form& f, unsigned n, int cond_bits) {
  KernelOptions o;
  o.mul = f.mul;
  o.n = n;
  o.watertight = f.watertight;
  o.cond_bits = cond_bits;
  return o;
}

// Errors of one set of hits against the reference's, per ray.
struct Errors {
  double wrong = 0;    // both hit, different triangles
  double hitmiss = 0;  // one hits, the other does not
  double depth_median = 0, depth_max = 0;  // |t - t_ref| / t_ref where both hit the same triangle
};

Errors errors(const std::vector<Hit>& got, const std::vector<Hit>& ref) {
  Errors e;
  std::vector<double> depth;
  size_t wrong = 0, hitmiss = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    if (got[i].hit() != ref[i].hit()) {
      ++hitmiss;
    } else if (got[i].tri != ref[i].tri) {
      ++wrong;
    } else if (ref[i].hit()) {
      depth.push_back(std::abs(got[i].t - ref[i].t) / ref[i].t);
    }
  }
  const double rays = static_cast<double>(std::max<size_t>(got.size(), 1));
  e.wrong = static_cast<double>(wrong) / rays;
  e.hitmiss = static_cast<double>(hitmiss) / rays;
  if (!depth.empty()) {
    std::sort(depth.begin(), depth.end());
    e.depth_median = depth[depth.size() / 2];
    e.depth_max = depth.back();
  }
  return e;
}

struct Run {
  std::vector<Hit> hits;
  KernelStats st;
};

Run run_kernel(const Config& machine, const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
               const KernelOptions& o) {
  auto be = make_backend("cmodel", machine);
  Device dev(be->bus());
  Run r;
  r.hits = intersect_fmpp(dev, rays, tris, o, &r.st);
  return r;
}

struct RenderRun {
  rt::Image image{1, 1};
  KernelStats st;
};

RenderRun run_render(const Config& machine, const rt::Scene& s, int size, const KernelOptions& o) {
  auto be = make_backend("cmodel", machine);
  Device dev(be->bus());
  rt::FmppIntersector fi(dev, s.triangles, o);
  rt::RenderOptions ro;
  ro.width = ro.height = size;
  RenderRun r;
  r.image = rt::render(s, fi, ro, nullptr);
  r.st = fi.stats();
  return r;
}

// PSNR of the 8-bit images (all channels), in dB; +inf for identical images.
double psnr(const rt::Image& a, const rt::Image& b) {
  const std::vector<uint8_t> x = a.to_rgb8(), y = b.to_rgb8();
  double se = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double d = static_cast<double>(x[i]) - static_cast<double>(y[i]);
    se += d * d;
  }
  if (se == 0) return std::numeric_limits<double>::infinity();
  return 10 * std::log10(255.0 * 255.0 / (se / static_cast<double>(x.size())));
}

bool same_hits(const std::vector<Hit>& a, const std::vector<Hit>& b) {
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].tri != b[i].tri || (a[i].hit() && a[i].t != b[i].t)) return false;
  }
  return a.size() == b.size();
}

// One row of a scene table.
struct Row {
  unsigned n = 0;
  std::string form;
  double steps = 0;  // per broadcast, primary rays, raw
  uint64_t broadcasts = 0;
  uint64_t raw_cycles = 0;  // primary frame, cond_bits = 60
  Errors raw;
  uint64_t cycles = 0;  // primary frame, default fallback
  Errors fallback;
  uint64_t host_triangles = 0, host_tests = 0, overflow_rays = 0, snapped = 0;
  uint64_t render_cycles = 0, render_host_tests = 0;
  double psnr = 0;
  uint64_t pixels_off = 0;  // pixels more than 8 levels off the reference render
};

json to_json(const Row& r) {
  return {{"n", r.n},
          {"form", r.form},
          {"steps", r.steps},
          {"broadcasts", r.broadcasts},
          {"raw_cycles", r.raw_cycles},
          {"raw_wrong", r.raw.wrong},
          {"raw_hitmiss", r.raw.hitmiss},
          {"raw_depth_median", r.raw.depth_median},
          {"raw_depth_max", r.raw.depth_max},
          {"cycles", r.cycles},
          {"wrong", r.fallback.wrong},
          {"hitmiss", r.fallback.hitmiss},
          {"depth_median", r.fallback.depth_median},
          {"depth_max", r.fallback.depth_max},
          {"host_triangles", r.host_triangles},
          {"host_tests", r.host_tests},
          {"overflow_rays", r.overflow_rays},
          {"snapped", r.snapped},
          {"render_cycles", r.render_cycles},
          {"render_host_tests", r.render_host_tests},
          {"psnr", std::isfinite(r.psnr) ? json(r.psnr) : json(nullptr)},
          {"pixels_off", r.pixels_off}};
}

// A rate in percent, "0" when exactly zero.
std::string pct(double v) {
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, v >= 0.01 ? "%.2f" : "%.3f", 100 * v);
  return buf;
}

std::string sci(double v) {
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

std::string big(uint64_t v) {
  char buf[64];
  if (v >= 1000000) {
    std::snprintf(buf, sizeof buf, "%.3gM", static_cast<double>(v) / 1e6);
  } else if (v >= 10000) {
    std::snprintf(buf, sizeof buf, "%.1fk", static_cast<double>(v) / 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(v));
  }
  return buf;
}

std::string db(double v) { return std::isfinite(v) ? fmt(v, 1) : "identical"; }

// One row of the leak table.
struct LeakRow {
  unsigned n = 0;
  std::string form;
  double steps = 0;
  size_t edge_leaks = 0, edge_rays = 0, uniform_leaks = 0, uniform_rays = 0;
  uint64_t host_triangles = 0;
};

// How to read the tables (written for the full run's numbers).
const char* kReading = R"(**What the numbers mean for choosing n** (read from the tables above):

- **The paper's form needs n = 20 for the machine alone, n = 24 for images.** At
  n = 20 the raw machine gets every primary ray of every scene right and the fallback
  sends at most 21 triangles to the host; the full renders reach 35.2 (spheres_10k) to
  73 dB. At n = 24, the default, every render is within one level of the reference on
  at most a few pixels (77 to 83 dB, or identical). Below 16 the raw error grows about
  4x per 2 bits (spheres_10k: 0.6 % of the rays wrong at n = 16, 3.5 % at 12, 17 % at
  10), as the error analysis predicts (cond 2^-n).
- **The fallback keeps results right, but below n = 16 it is the host doing the work.**
  Its condition limit (2^(n-3): 32 at n = 8, 128 at 10) is below the condition number
  of ordinary triangles seen from the eye (tens to hundreds), so at n = 8 all but two
  triangles of each sphere scene are host triangles: their primary rays come out right, for 10.5
  million host tests per frame on spheres_10k, as many as the brute-force reference
  does, and the secondary rays' arbitrary-origin kernel (limit 2^(n-4)) sends most
  triangles to the host too; the sphere images come out at 31 to 33 dB (4 pixels more
  than 8 levels off). The Cornell box keeps 6 of its triangles on the FMPP, whose
  cracks at n = 8 cost 5 % of the primary rays (17 dB).
  At n = 10 and 12 the fallback takes most or half of the triangles and still leaves
  errors (spheres_1k: 5 % of the rays at n = 10). From n = 16 the cost of correctness is
  small (at most 4 % of the triangles), from 24 nil.
- **Clocks grow linearly with n.** The constant (CSD) multiply costs about 6n + 16
  steps per broadcast (64 at n = 8, 159 at 24, 209 at 32) and the generic one 22n + 31,
  3.2 to 3.6 times more on the larger scenes, for bit-identical results (checked on
  every ray and image here). From n = 16 to 24 a broadcast costs 43 % more, from 24 to
  32 another 30 %. Whole renders gain less from the constant multiply (1.8 to 2.3
  times from n = 16 on the three larger scenes, near 1 below, where the host does most
  of the work) because loads, readback and the arbitrary-origin kernel of the secondary
  rays weigh the same in both. Use the constant multiply at every n.
- **n = 32 buys depth, not hits.** The ray components have 28 bits, so past 28 the
  triangle test hardly improves (no primary ray changes between n = 24 and 32 here),
  while the depth error falls about 3 times (median 1.3e-6 to 4.1e-7 on spheres_10k).
- **The watertight form never leaks, but its grid is coarse.** On the closed sphere it
  lets no ray through at any n (0 of 23,456), where the paper's form loses 18 to 24 %
  of the rays aimed exactly at edges for n = 8..28 (the sign of a rounded T decides
  them; 5 % at 32) and, of rays in all directions, 1.7 % at n = 8, falling about 4x per
  2 bits to none of 20,000 from n = 16. But it snaps vertices to a grid of (n-3)/2 bits
  of the scene's extent, moving them by up to 2^-(n-1)/2 of it: on the sphere scenes it
  needs n = 32 to get as few rays wrong as the paper's form at n = 16 to 20, and even
  there its sphere images are 45 to 68 dB (its depth comes from one n-bit row). Its clocks per
  broadcast are close to the paper's form's at equal n (fewer at small n, up to 22 %
  more at 24-32). So: the paper's form at n = 24 for the most accurate image per clock;
  the watertight form at n = 32 where a closed surface must never leak (shadow rays
  toward closed objects, inside tests).)";

const char* kHardCases = R"(## Hard cases

`tests/hardcases_test.cpp` runs every case below on the reference, on the golden model
(`Model/HardCases.*`, ctest label `unit`) and on the Verilated RTL in lockstep with the
model (`Rtl/HardCases.*`, label `rtl`, configuration `small`), in the ray-parallel and
object-parallel paper forms and the watertight form (n = 24, some also n = 16), and
checks after every run that an overflow left in the machine was counted. "Equals the
reference" means: the same triangle for every ray, and the distance within the form's
depth bound (below).

| case | behaviour asserted | bound, where the exact behaviour cannot hold |
| --- | --- | --- |
| rays exactly through the shared vertex and the shared edges of a closed fan of 7 triangles | reference and watertight: every ray hits (no crack), and reports one triangle, one of those sharing the edge or vertex (either is right: the ray meets both at one point); paper forms: any hit is such a triangle, at the right depth | the paper's form decides an exact edge by the sign of a rounded T, so it may crack there (counted, not bounded); rays 8 cond 2^-min(n,28) of the triangle's height inside a triangle hit exactly that triangle, as the reference does |
| closed perturbed sphere (288 triangles) around the eye, rays aimed exactly at its edges and vertices | every ray hits in the reference; the watertight form never leaks (n = 12, 16, 24) | the paper's form leaks on exact edges at a rate that does not fall with n (table above): asserted below 35 %; rays a margin (as above) inside every triangle never leak and hit that triangle, in both mappings |
| the same sphere, 12,000 uniformly random directions | the watertight form never leaks | the paper's form leaks only within the crack width of an edge (about cond 2^-n of a triangle's height): asserted at most 16 x 2^-n (measured 4.3-5.5 x 2^-n for n = 8..12, none from 16) |
| eye exactly in a triangle's plane, inside a triangle, and 1e-12, 1e-6, 1e-3 off the plane, with a wall behind | every form equals the reference (n = 16, 24), never a garbage hit; the singular triangle (det = 0) is a host triangle even with cond_bits = 60; nearly singular ones are counted host triangles | - |
| degenerate triangles: collinear vertices (exact integers and dyadic), a repeated vertex, three equal vertices; rays aimed exactly at them | never hit: the rays hit the wall behind, in the reference and both paper forms (default and cond_bits = 60); the four are host triangles | watertight: its grid moves collinear vertices off their line, making a sliver at most one grid step wide, which rays through the old segment may hit (that sliver keeps a closed mesh closed once snapped); a repeated vertex or a point is never hit, and rays 3 grid steps beside a collinear triangle never hit it |
| needles and a sliver of aspect ratio 1e4 (cond 2e4 to 2e5) before a wall; rays inside them and one width outside | paper forms equal the reference at n = 16 (all three are host triangles: cond > 2^13) and n = 24 (on the FMPP); host_triangles counts exactly the triangles above 2^(min(n,28)-3) in both mappings | watertight: the needles snap to nothing (host triangles); the sliver snaps to a triangle a grid step away, which the rays miss: the form equals the reference on its snapped mesh |
| a tiny triangle (1e-6) at distance 1, a tiny one 1e-7 in front of the eye, a huge one (1e6 wide) at 1e5 behind a wall | every form equals the reference; ray-parallel redoes the rays of the near one after an overflow (overflow_rays > 0) and tests the far one on the host; object-parallel tests both tiny ones on the host (the near one's column sums are above its cap), the watertight form both and the wall (the huge triangle sets a grid step of ~1400); host_triangles exact | depth: the compared sum keeps at least 9 bits (ray-parallel) or 10 bits (object-parallel) for the farthest hit, so a scene spanning 1e-7 to 1e6 has depth errors up to ~2^-9 there |
| ray directions of lengths 5 to 1e5 in one call | every form equals the reference; t is in units of each ray's own direction | - |
| triangles behind the eye and straddling its plane, rays forward and backward | hits only in front, equal to the reference, every form | - |
| one triangle listed six times with its vertices in every order | a tie: the first copy (lowest index) wins, in the reference and every form (watertight: on its snapped mesh) | - |
| coplanar overlapping triangles (plane z = 4) | reference, object-parallel and watertight: exact tie, lowest index | ray-parallel sums three separately rounded rows per triangle, so two different triangles of one plane differ in the last unit of S: it reports one of them, at the right depth |
| z-fighting: parallel overlapping planes 1e-2, 1e-3, 1e-9 apart, the farther one first | where the gap exceeds twice the form's depth bound, the nearer triangle, as the reference | below that, either of the two, at the right depth |
| interpenetrating triangles crossing along a line | rays away from the crossing: the nearer one, as the reference | on the crossing line, either |
| a floor of 128 triangles 1 below the eye, rays down to 1e-3 elevation (hits ~1900 away), above the horizon, beyond the floor | paper forms equal the reference at n = 16 (many far tiles are host triangles) and n = 24 | watertight: the grid step (~2) exceeds the eye's height, so its floor moves: it equals the reference on its snapped floor |
| directions with zero components (along the axes, in the axis planes) in a box around the eye | every form equals the reference | - |
| a scene and eye translated by (1e5, -1e5, 1e5), also rays with their own origins, tmin and an excluded triangle | primary rays equal the reference in the paper forms, the watertight form on its snapped mesh; arbitrary-origin rays equal it within that kernel's bound 2^-(n-10) | - |
| tiny triangles (0.02 across) 70 from the scene's centre, rays with their own origins aimed inside them (arbitrary-origin kernel) | n = 16: the 16 tiny triangles are host triangles (edge-test condition above 2^(n-4)) and every ray equals the reference; with cond_bits = 60 some rays are wrong; n = 24: on the FMPP, every ray equals the reference | - |
| rays that miss everything, an empty scene, an empty batch | all misses, no host work, no overflow | - |

**Depth bounds used by the tests** (`allowed` in the test file): the paper's forms make
a relative error of about cond 2^-min(n,28) in T and hence in S = 1/t (8 cond 2^-bits
allowed), plus the resolution of the compared sum: ray-parallel brings S to one
exponent chosen so that the nearest possible hit (at dmin, the nearest triangle but at
least 2^-20 of the farthest vertex) is ~2^29, so a hit at d keeps S_c >= 2^28 dmin / d
(8 / S_c allowed); object-parallel keeps S_c >= 2^(mbits-2) / (s_max d) (same
allowance). The watertight form intersects the snapped mesh (surfaces up to sqrt(3)/2
grid steps away: 2 steps / |cos| along a ray allowed) and takes S from one n-bit row
(2^-(n-12) relative allowed).

**Bugs these cases found** (each fixed with its test, see the git log): the reference
broke ties between copies of a triangle by rounding (vertex order) and hit degenerate
triangles through their segment; the kernels quantized all ray directions of a call
with one scale (a short ray lost its bits), let object-parallel keep triangles up to
cond 2^25 at any n, let one near-plane triangle take every bit of the object-parallel
S from all others, dropped triangles the watertight grid flattened (the reference
still hits them), and derived scales from an empty scene (undefined behaviour).
)";

}  // namespace

Command add_precision(CLI::App& app) {
  auto opt = std::make_shared<Options>();
  Command c;
  c.sub = app.add_subcommand("precision", "accuracy against cycles for each multiplier width, on the scenes (golden model)");
  add_output_options(c.sub, *opt);
  c.sub->add_option("--scenes", opt->scenes_dir, "directory holding the scene JSON files")->capture_default_str();
  CLI::Option* size_opt = c.sub->add_option("--size", opt->size, "image width and height in pixels")
                              ->capture_default_str()
                              ->check(CLI::Range(2, 256));
  c.sub->add_flag("--quick", opt->quick, "8 x 8 pixels, n = 8 and 24 only, fewer leak rays (for tests)")
      ->excludes(size_opt);
  c.run = [opt]() -> int {
    prepare_outputs(*opt);
    const Options& o = *opt;
    const auto t_start = std::chrono::steady_clock::now();
    const int size = o.quick ? 8 : o.size;
    const Config machine = o.quick ? kQuickMachine : kMachine;
    const std::vector<unsigned> bits =
        o.quick ? std::vector<unsigned>{8, 24} : std::vector<unsigned>{8, 10, 12, 16, 20, 24, 32};
    json data;
    data["size"] = size;
    data["machine"] = {{"blocks", machine.blocks}, {"words", machine.words}};
    std::ostringstream md;
    const std::string date = today();
    bool consistent = true;  // generic and const gave bit-identical results everywhere

    // ------------------------------------------------------------- the scenes
    std::map<std::string, std::vector<Row>> tables;
    std::map<std::string, size_t> scene_tris;
    for (const char* name : kScenes) {
      const rt::Scene scene = rt::load_scene(o.scenes_dir + "/" + name + ".json");
      scene_tris[name] = scene.triangles.size();
      std::fprintf(stderr, "[precision] %s: %zu triangles, %d x %d pixels\n", name, scene.triangles.size(), size, size);
      const std::vector<Ray> rays = rt::primary_rays(scene.camera, size, size);
      const std::vector<Hit> ref = nearest_reference(rays, scene.triangles);
      rt::ReferenceIntersector ri(scene.triangles);
      rt::RenderOptions ro;
      ro.width = ro.height = size;
      const rt::Image ref_image = rt::render(scene, ri, ro, nullptr);
      std::vector<Row> rows;
      for (unsigned n : bits) {
        std::vector<Hit> generic_hits;
        rt::Image generic_image(1, 1);
        for (const Form& f : kForms) {
          Row r;
          r.n = n;
          r.form = f.name;
          const Run raw = run_kernel(machine, rays, scene.triangles, kernel_options(f, n, policy::kRawCondBits));
          r.steps = raw.st.steps_per_broadcast();
          r.broadcasts = raw.st.broadcasts;
          r.raw_cycles = raw.st.cycles;
          r.raw = errors(raw.hits, ref);
          const Run fb = run_kernel(machine, rays, scene.triangles, kernel_options(f, n, -1));
          r.cycles = fb.st.cycles;
          r.fallback = errors(fb.hits, ref);
          r.host_triangles = fb.st.host_triangles;
          r.host_tests = fb.st.host_tests;
          r.overflow_rays = fb.st.overflow_rays;
          r.snapped = fb.st.snapped_degenerate;
          const RenderRun rr = run_render(machine, scene, size, kernel_options(f, n, -1));
          r.render_cycles = rr.st.cycles;
          r.render_host_tests = rr.st.host_tests;
          r.psnr = psnr(rr.image, ref_image);
          r.pixels_off = rt::compare(rr.image, ref_image).pixels_over;
          // Generic and const must agree bit for bit (docs/intersection.md).
          if (f.mul == MulMode::kGeneric) {
            generic_hits = raw.hits;
            generic_image = rr.image;
          } else if (!f.watertight &&
                     (!same_hits(generic_hits, raw.hits) || generic_image.to_rgb8() != rr.image.to_rgb8())) {
            std::fprintf(stderr, "[precision] %s n=%u: generic and const results differ\n", name, n);
            consistent = false;
          }
          rows.push_back(r);
        }
        std::fprintf(stderr, "[precision]   n=%u done (%.0f s so far)\n", n,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count());
      }
      tables[name] = rows;
      json js = json::array();
      for (const Row& r : rows) js.push_back(to_json(r));
      data["scenes"][name] = js;
    }

    // ------------------------------------------------------ the leak rate
    std::fprintf(stderr, "[precision] leak rate on the closed sphere\n");
    const std::vector<Triangle> sphere = closed_sphere(SphereMeshOptions{});
    const std::vector<Ray> edge_rays = edge_and_vertex_rays(sphere, glm::dvec3(0));
    const std::vector<Ray> uniform = uniform_rays(glm::dvec3(0), o.quick ? 2000 : 20000, 3);
    const std::vector<unsigned> leak_bits =
        o.quick ? bits : std::vector<unsigned>{8, 10, 12, 16, 20, 24, 28, 32};
    std::vector<LeakRow> leaks;
    json jl = json::array();
    struct LeakForm {
      const char* name;
      bool watertight;
      int cond_bits;
    };
    for (unsigned n : leak_bits) {
      for (const LeakForm& lf : {LeakForm{"paper, raw", false, policy::kRawCondBits}, LeakForm{"paper, fallback", false, -1},
                                 LeakForm{"watertight", true, -1}}) {
        KernelOptions ko;
        ko.n = n;
        ko.watertight = lf.watertight;
        ko.cond_bits = lf.cond_bits;
        const Run e = run_kernel(machine, edge_rays, sphere, ko);
        const Run u = run_kernel(machine, uniform, sphere, ko);
        LeakRow l;
        l.n = n;
        l.form = lf.name;
        l.steps = e.st.steps_per_broadcast();
        l.edge_rays = edge_rays.size();
        l.uniform_rays = uniform.size();
        for (const Hit& h : e.hits) l.edge_leaks += !h.hit();
        for (const Hit& h : u.hits) l.uniform_leaks += !h.hit();
        l.host_triangles = e.st.host_triangles;
        leaks.push_back(l);
        jl.push_back({{"n", n}, {"form", l.form}, {"steps", l.steps}, {"edge_leaks", l.edge_leaks},
                      {"edge_rays", l.edge_rays}, {"uniform_leaks", l.uniform_leaks}, {"uniform_rays", l.uniform_rays},
                      {"host_triangles", l.host_triangles}});
      }
    }
    data["leaks"] = jl;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

    // ------------------------------------------------------------ markdown
    md << "# Precision: accuracy against cycles\n\n";
    md << "Generated by `build/fmpp-report precision" << (o.quick ? " --quick" : "")
       << (o.size != 32 && !o.quick ? " --size " + std::to_string(o.size) : std::string()) << "` on " << date << " ("
       << machine_description() << "; " << fmt(seconds) << " s). Every figure is measured on the golden model "
       << "(clock-exact with the RTL: the lockstep tests check it) as an FMPP of " << machine.blocks << " blocks x "
       << machine.words << " words (the RTL's `" << (o.quick ? "small" : "medium")
       << "` configuration), ray-parallel, at " << size << " x " << size
       << " pixels. The data behind the tables and plots is in `" << o.img_dir << "/precision_data.json`.\n\n";
    if (!consistent) {
      md << "**Generic and constant multiplies gave different results somewhere: see the tool's output. "
            "They must not (docs/intersection.md).**\n\n";
    }
    md << R"(## What is measured

- **n**: the multiplier width (`KernelOptions::n`): the mantissas of P^-1 in the paper's
  form, the edge constants (from a grid of (n - 3) / 2 bits) in the watertight form. The
  other operand (ray components) has vbits = 28 bits, so beyond n = 28 the triangle
  test gains little.
- **Forms**: `generic` and `const` are the paper's form with the generic shift-and-add
  multiply and the constant-specialised (CSD) one: bit-identical results by
  construction (checked here on every image and every primary ray), different cycles.
  `watertight` is the exact-integer edge-function form (always constant multiplies).
- **steps/bcast**: instructions (= clocks) per triangle broadcast, primary rays.
- **frame clocks**: FMPP clocks for all primary rays of the image (load, broadcasts,
  readback), counted by the golden model; **render clocks**: for the whole Whitted
  render (primary, shadow, reflection and refraction rays; the secondary rays of mirrors
  and glass use the arbitrary-origin kernel).
- **Raw machine** (`cond_bits = 60`): every triangle on the FMPP, so the error is the
  fixed-point format's. **Fallback** (the default): ill-conditioned triangles (cond >
  2^(min(n,28)-3)) and, in the watertight form, triangles the grid flattens are
  intersected on the host (**host tris**, **host tests** = ray-triangle tests the host
  did instead), and overflowed rays are redone there: the cost of correctness.
- Per primary ray, against the double-precision reference: **wrong** = both hit,
  different triangles; **hit/miss** = one hits and the other does not (both in % of the
  rays); **depth** = |t - t_ref| / t_ref over the rays hitting the same triangle (median
  and maximum).
- **PSNR**: of the 8-bit image of the full render against the reference render (all
  channels; "identical" when every pixel is equal); **px > 8** = pixels more than 8
  levels off in some channel.

)";
    for (const char* name : kScenes) {
      const std::vector<Row>& rows = tables[name];
      md << "## " << name << " (" << scene_tris[name] << " triangles)\n\n";
      md << "| n | form | steps/bcast | raw: frame clocks | wrong % | hit/miss % | depth median | depth max | "
            "fallback: frame clocks | host tris | host tests | wrong % | hit/miss % | render clocks | PSNR dB | px > 8 |\n";
      md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
      for (const Row& r : rows) {
        md << "| " << r.n << " | " << r.form << " | " << fmt(r.steps, 1) << " | " << big(r.raw_cycles) << " | "
           << pct(r.raw.wrong) << " | " << pct(r.raw.hitmiss) << " | " << sci(r.raw.depth_median) << " | "
           << sci(r.raw.depth_max) << " | " << big(r.cycles) << " | " << r.host_triangles << " | " << big(r.host_tests)
           << " | " << pct(r.fallback.wrong) << " | " << pct(r.fallback.hitmiss) << " | " << big(r.render_cycles) << " | "
           << db(r.psnr) << " | " << r.pixels_off << " |\n";
      }
      md << "\n";
    }

    md << "## Leak rate on a closed mesh around the eye\n\n";
    md << "The closed, perturbed sphere of `sw/isect/meshes.h` (" << sphere.size()
       << " triangles, every edge shared by two) around the eye: **edge rays** are aimed exactly at its "
       << edge_rays.size() << " vertex and edge points (`edge_and_vertex_rays`), **uniform rays** are "
       << uniform.size()
       << " random directions. Every ray must hit; a miss is a leak. `paper, raw` is the const form with "
          "cond_bits = 60, `paper, fallback` the default, `watertight` the exact-integer form. "
          "(`tests/hardcases_test.cpp` asserts the bounds.)\n\n";
    md << "| n | form | steps/bcast | edge rays leaking | % | uniform rays leaking | % | host tris |\n"
          "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const LeakRow& l : leaks) {
      md << "| " << l.n << " | " << l.form << " | " << fmt(l.steps, 1) << " | " << l.edge_leaks << " of " << l.edge_rays
         << " | " << pct(static_cast<double>(l.edge_leaks) / static_cast<double>(l.edge_rays)) << " | " << l.uniform_leaks
         << " of " << l.uniform_rays << " | "
         << pct(static_cast<double>(l.uniform_leaks) / static_cast<double>(l.uniform_rays)) << " | " << l.host_triangles
         << " |\n";
    }
    md << "\n";

    // ------------------------------------------------------ choosing n
    // Per scene, the smallest n meeting each criterion (const form unless named).
    md << "## Choosing n\n\n";
    md << "Smallest n (of those measured) at which, per scene: the raw machine gets at most 0.1 % of the primary "
          "rays wrong (wrong + hit/miss); the fallback sends at most 1 % of the triangles to the host; the full "
          "render reaches 40 dB PSNR; all three, with the const form's steps per broadcast there; and the "
          "watertight form's raw error is at most 0.1 %.\n\n";
    md << "| scene | raw error <= 0.1 % | host triangles <= 1 % | render PSNR >= 40 dB | all three | steps/bcast there "
          "| watertight raw error <= 0.1 % | its steps/bcast |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n";
    json choose = json::object();
    for (const char* name : kScenes) {
      auto first = [&](const char* form, auto pred) -> const Row* {
        for (const Row& r : tables[name]) {
          if (r.form == form && pred(r)) return &r;
        }
        return nullptr;
      };
      const double ntris = static_cast<double>(scene_tris[name]);
      const Row* raw = first("const", [](const Row& r) { return r.raw.wrong + r.raw.hitmiss <= 1e-3; });
      const Row* host = first("const", [&](const Row& r) { return static_cast<double>(r.host_triangles) <= 0.01 * ntris; });
      const Row* image = first("const", [](const Row& r) { return !(r.psnr < 40); });
      const Row* all = first("const", [&](const Row& r) {
        return r.raw.wrong + r.raw.hitmiss <= 1e-3 && static_cast<double>(r.host_triangles) <= 0.01 * ntris &&
               !(r.psnr < 40);
      });
      const Row* wt = first("watertight", [](const Row& r) { return r.raw.wrong + r.raw.hitmiss <= 1e-3; });
      auto n_of = [](const Row* r) { return r ? std::to_string(r->n) : std::string("-"); };
      auto steps_of = [](const Row* r) { return r ? fmt(r->steps, 1) : std::string("-"); };
      md << "| " << name << " | " << n_of(raw) << " | " << n_of(host) << " | " << n_of(image) << " | " << n_of(all)
         << " | " << steps_of(all) << " | " << n_of(wt) << " | " << steps_of(wt) << " |\n";
      choose[name] = {{"raw", n_of(raw)}, {"host", n_of(host)}, {"image", n_of(image)}, {"all", n_of(all)},
                      {"watertight", n_of(wt)}};
    }
    data["choose"] = choose;
    md << "\n" << "@CHOOSING@" << "\n\n";

    md << "## Plots\n\n![accuracy against cycles](img/precision_scenes.png)\n\n"
          "![leak rate and steps per broadcast against n](img/precision_leaks.png)\n\n";
    md << kHardCases << "\n";
    md << "Reproduce: `make build && build/fmpp-report precision` (writes this file, " << o.img_dir
       << "/precision_{scenes,leaks}.png and " << o.img_dir << "/precision_data.json; about "
       << fmt(std::max(1.0, std::round(seconds / 60)))
       << " min on the machine above). `--quick` is the ctest smoke run (without `--out` it writes "
          "precision-quick.md, never this file).\n";

    // -------------------------------------------------------------- output
    std::string text = md.str();
    // The reading of the numbers is prose written for the full run; a quick run says so.
    text.replace(text.find("@CHOOSING@"), 10,
                 o.quick ? "(A quick run: too few pixels and widths to read anything into; see docs/precision.md.)"
                         : kReading);
    write_report(o, text, data);
    std::fprintf(stderr, "[precision] wrote %s (%.0f s)\n", o.out.c_str(), seconds);
    return consistent ? 0 : 1;
  };
  return c;
}

}  // namespace fmpp::report
