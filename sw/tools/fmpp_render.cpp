// fmpp-render: Whitted ray tracing with every intersection computed on the FMPP.
//
//   fmpp-render --scene scenes/cornell.json --backend rtl --width 128 --height 128
//               --out cornell.png --report cornell.json
//
// Backends: reference (double precision on the host), cmodel (golden model), rtl
// (Verilated RTL), lockstep (both, cross-checked). The JSON report counts rays by type,
// broadcasts, FMPP cycles, passes, wall time, the simulated time at a clock, overflows,
// the same by batch kind (primary, shadow, secondary), with --oracle the counts culling
// is measured against (docs/raytracer.md), and with --compare-reference the pixels that
// differ from the reference render.
//
// Started by mpirun, every rank drives one FMPP and the passes are handed out among them
// (sw/mpi/, docs/multichip.md); rank 0 writes the picture and the report.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "backends/backend.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/stats_json.h"
#include "common/util/cli_usage.h"
#include "sw/tools/cli_options.h"
#include "sw/tools/kernel_flags.h"
#include "sw/tools/render_plan.h"
#include "sw/tools/render_progress.h"
#include "sw/rt/plan.h"
#include "sw/rt/plan_cache.h"
#include "sw/rt/exact_check.h"
#include "sw/rt/render.h"
#include "sw/mpi/render_chips.h"

using namespace fmpp;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The command line, as given.
struct Args {
  // The default scene is the repository's Cornell box wherever the tool is started; the
  // picture goes to the path given, by default render.png in the current directory.
  std::string scene_file = repo_file("scenes/cornell.json"), backend = "rtl", config, out = "render.png", report_file;
  int width = 128, height = 128, depth = -1;
  unsigned blocks = 4096, words = 32;  // the plan decides unless given
  double clock_mhz = 50, target = 0.002;
  bool compare = false, quiet = false, replan = false, accept_miss = false, verify = false, no_shadow_stop = false;
  std::string plan_cache = rt::default_plan_cache_dir(), shadow_calls, rank0 = "work";
  int sample_pixels = 3000, spp = 0;
  uint64_t seed = 0;
  BackendOptions bo;
  tools::KernelFlags kernel_flags;  // the kernel options' flags (sw/tools/kernel_flags.h)
  // Once parsed: the kernel options given, which of the plan's choices the user made, and
  // the command line itself (for --verify-exact's message).
  isect::KernelOptions given;
  bool spp_given = false, seed_given = false, bits_given = false, mapping_given = false, order_given = false,
       merge_given = false, blocks_given = false, words_given = false;
  std::string command = "The command:";
};

// Wall time by phase: the report's "phase_seconds" and the summary. From its creation,
// the "total".
class Phases {
 public:
  // Runs f, its wall time kept as phase `name`; returns what f returns.
  template <class F>
  auto time(const char* name, F&& f) {
    struct Stopwatch {
      Phases* p;
      const char* name;
      Clock::time_point t = Clock::now();
      ~Stopwatch() { p->set(name, seconds_since(t)); }
    } watch{this, name};
    return f();
  }
  void set(const char* name, double seconds) { j_[name] = seconds; }
  nlohmann::json with_total() {
    j_["total"] = seconds_since(start_);
    return j_;
  }

 private:
  Clock::time_point start_ = Clock::now();
  nlohmann::json j_;
};

// The flags of the scene, the frame and the machine (the kernel options' among them).
void declare_frame(CLI::App& app, Args& a) {
  app.add_option("--scene", a.scene_file, "scene JSON file (default: the repository's Cornell box)")
      ->capture_default_str();
  app.add_option("--backend", a.backend,
                 "reference (double precision on the host) or the machine: " + join(backend_names(), " | "))
      ->capture_default_str()
      ->check(CLI::IsMember(tool_backends()));
  app.add_option("--width", a.width, "image width")->capture_default_str()->check(int_range(1, 16384));
  app.add_option("--height", a.height, "image height")->capture_default_str()->check(int_range(1, 16384));
  // The plan chooses --bits, --mapping, --merge-below and --pass-order unless given.
  a.kernel_flags.add(app, tools::FlagTool::kRender);
  CLI::Option* blocks = app.add_option("--blocks", a.blocks, "FMPP blocks (default: chosen by the precision plan)")
                            ->check(int_range(1, map::kMaxBlocks));
  CLI::Option* words =
      app.add_option("--words", a.words, "FMPP words per block, even (default: chosen by the precision plan)")
          ->check(even_words());
  exclude_config_sizes(app.add_option("--config", a.config, "a named FMPP configuration instead of --blocks/--words"),
                       blocks, words);
}

// The flags of the precision plan and of the frame's sampling.
void declare_plan(CLI::App& app, Args& a) {
  app.add_option("--error-target", a.target,
                 "precision plan: wrong-triangle rate allowed per primary ray, and share of the frame's "
                 "pixels allowed off the reference (a 95 % upper bound from sampled pixels)")
      ->capture_default_str()
      ->check(finite_range(0.0, 1.0));
  app.add_flag("--replan", a.replan, "plan again even if this scene and these options have a cached plan");
  app.add_option("--plan-cache", a.plan_cache,
                 "directory of cached precision plans (a second render of the same scene files with the same options "
                 "reuses its plan; empty: no cache)")
      ->capture_default_str();
  app.add_flag("--accept-plan-miss", a.accept_miss,
               "render even when the precision plan finds no n that keeps --error-target (without it, such a "
               "render stops with an error before any work on the frame)");
  app.add_option("--plan-pixels", a.sample_pixels,
                 "precision plan: pixels of the frame drawn at random and rendered per candidate n")
      ->capture_default_str()
      ->check(int_range(1, 1 << 24));
  app.add_option("--max-depth", a.depth, "recursion depth (default: the scene's)")->check(int_range(1, 16));
  app.add_option("--spp", a.spp,
                 "samples per pixel: stratified, jittered, averaged with a box filter over the pixel (default: the "
                 "scene's samples_per_pixel, else 1, the pixel's centre)")
      ->check(int_range(1, rt::kMaxSpp));
  app.add_option("--seed", a.seed,
                 "seed of the pixel samples and the area lights' samples (default: the scene's seed, else " +
                     std::to_string(rt::kDefaultSeed) + ")")
      ->check(non_negative());
}

// The flags of the outputs, the checks, the shadow rays and the run.
void declare_outputs(CLI::App& app, Args& a) {
  app.add_option("--out", a.out,
                 "output image: .png (8-bit), .pfm or .exr (linear radiance, 32-bit float, unclamped); by default in the "
                 "current directory")
      ->capture_default_str();
  app.add_option("--report", a.report_file, "JSON report file ('-' for stdout)");
  app.add_option("--clock-mhz", a.clock_mhz, "clock for the simulated time")
      ->capture_default_str()
      ->check(finite_range(1.0, 1e5));
  app.add_flag("--compare-reference", a.compare, "also render with the reference and count differing pixels");
  app.add_flag("--verify-exact", a.verify,
               "check every answer of the frame against the exact reference's answer for the same ray; the first "
               "answer the intersection contract does not allow stops the render with the ray, its pass, n, the "
               "machine and the options (docs/certification.md)");
  app.add_option("--shadow-calls", a.shadow_calls,
                 "together | apart: each depth's last shadow batch in one kernel call with the next depth's rays, or "
                 "in its own (default: the precision plan's choice, from its cost model)")
      ->check(CLI::IsMember({"together", "apart"}));
  app.add_flag("--no-shadow-stop", a.no_shadow_stop,
               "shadow rays as nearest-hit queries, not stopped at their first certified occluder (the same image, "
               "more clocks)");
  add_trace_options(app, a.bo);
  app.add_flag("--quiet", a.quiet,
               "no progress display and no closing summary on the console (the report keeps the figures); without "
               "it, stderr gets one progress line for the frame (rays of the rays expected, rate, ETA), redrawn on a "
               "terminal and printed every 3 s otherwise (FMPP_PROGRESS_INTERVAL=seconds sets another interval), "
               "and a summary at the end");
  app.add_option("--rank0", a.rank0, "under mpirun: rank 0 drives an FMPP too (work) or only hands out passes (schedule)")
      ->capture_default_str()
      ->check(CLI::IsMember({"work", "schedule"}));
}

// Parses the command line into *a: -1 to go on, else the exit status (help, a usage error).
int parse(int argc, char** argv, Args* a) {
  CLI::App app{"Whitted ray tracing with the intersections on the FMPP"};
  declare_frame(app, *a);
  declare_plan(app, *a);
  declare_outputs(app, *a);
  app.footer(exit_status_footer("an error of the work (a scene or output it cannot use, a plan that misses its target)"));
  if (const int status = parse_command_line(app, argc, argv); status >= 0) return status;
  a->given = a->kernel_flags.options();
  a->spp_given = app.count("--spp") > 0;
  a->seed_given = app.count("--seed") > 0;
  a->bits_given = app.count("--bits") > 0;
  a->mapping_given = app.count("--mapping") > 0 || a->kernel_flags.form_given();
  a->order_given = app.count("--pass-order") > 0;
  a->merge_given = app.count("--merge-below") > 0;
  a->blocks_given = app.count("--blocks") > 0;
  a->words_given = app.count("--words") > 0;
  for (int i = 0; i < argc; ++i) a->command += std::string(" ") + argv[i];
  return -1;
}

// Every option and output checked before any work.
void check(const Args& a, const mpi::Session& session) {
  if (session.size() > 1 && a.given.mapping == isect::Mapping::kObject) {
    throw std::invalid_argument("--mapping object cannot run on several FMPPs (its passes keep each ray's best "
                                "across passes); use --mapping ray or one rank");
  }
  if (session.size() > 1 && !a.bo.trace_file.empty()) {
    throw std::invalid_argument("--trace " + a.bo.trace_file + " on several ranks: every FMPP would write that file");
  }
  check_trace_options(a.backend, a.bo);
  check_config_name(a.backend, a.config);
  if (a.given.mapping == isect::Mapping::kObject && a.given.watertight) {
    throw std::invalid_argument("--watertight with --mapping object: the watertight form exists in the ray-parallel "
                                "mapping only; use --mapping ray");
  }
  rt::check_resolution(a.width, a.height);
  if (a.out == "-") throw std::invalid_argument("--out -: the image needs a file name (stdout is only for --report -)");
  rt::image_format(a.out);  // .png, .pfm or .exr, refused before any work otherwise
  if (session.leader()) check_writable("--out", a.out, false);
  if (session.leader() && !a.report_file.empty()) check_writable("--report", a.report_file);
}

// The scene with --spp and --seed in place of its own (for the plan's sample as for the
// frame); no output may be one of its files.
rt::Scene load(const Args& a) {
  rt::Scene scene = rt::load_scene(a.scene_file);
  if (a.spp_given) scene.spp = a.spp;
  if (a.seed_given) scene.seed = a.seed;
  std::vector<NamedPath> inputs;
  for (const auto& f : scene.files) inputs.push_back({f == a.scene_file ? "--scene" : "mesh of --scene", f});
  check_no_alias({{"--out", a.out}, {"--report", a.report_file}, {"--trace", a.bo.trace_file}}, inputs);
  return scene;
}

// The report's head: the scene, the frame and the lights.
nlohmann::json scene_report(const Args& a, const rt::Scene& scene) {
  nlohmann::json rep;
  rep["scene"] = a.scene_file;
  rep["triangles"] = scene.triangles.size();
  rep["resolution"] = {a.width, a.height};
  rep["backend"] = a.backend;
  rep["spp"] = scene.spp;
  rep["seed"] = scene.seed;
  for (const rt::Light& l : scene.lights) {
    nlohmann::json jl = {{"type", rt::to_string(l.type)}};
    if (l.area()) {
      jl["samples"] = l.samples;
      jl["pool"] = l.pool;
    }
    rep["lights"].push_back(jl);
  }
  return rep;
}

// The frame rendered through `isect`, every answer checked against the exact reference
// where `verify`: the report's "verify_exact" (with the plan's checked renders, `plan`).
rt::Image render_frame(const rt::Scene& scene, rt::Intersector& isect, const rt::RenderOptions& ro, rt::RenderStats* rs,
                       bool verify, const std::string& command, const rt::ExactCheckStats& plan, nlohmann::json* rep) {
  rt::ExactCheckStats st;
  rt::Image img = rt::render_checked(scene, isect, ro, rs, verify, command, &st);
  if (verify) (*rep)["verify_exact"] = rt::exact_check_json(st, plan);
  return img;
}

// The frame on the host, every ray through the double-precision reference.
rt::Image render_on_host(const Args& a, const rt::Scene& scene, const rt::RenderOptions& ro, Phases* phases,
                         rt::RenderStats* rs, nlohmann::json* rep) {
  rt::ReferenceIntersector ref(scene.triangles);
  return phases->time("frame", [&] { return render_frame(scene, ref, ro, rs, a.verify, a.command, {}, rep); });
}

// What the precision plan is asked: it chooses what the options leave open. It starts from
// the defaults of what it chooses (n, the pass order, merge_below: the user's, where
// given, go in the request) and never counts for the oracle.
rt::PlanRequest plan_request(const Args& a, const mpi::Session& session) {
  const isect::KernelOptions defaults;
  rt::PlanRequest pr;
  pr.base = a.given;
  pr.base.n = defaults.n;
  pr.base.coherent = defaults.coherent;
  pr.base.merge_below = defaults.merge_below;
  pr.base.oracle = false;
  pr.width = a.width;
  pr.height = a.height;
  pr.max_depth = a.depth;
  pr.target_wrong_rate = a.target;
  pr.sample_pixels = a.sample_pixels;
  if (a.backend != "cmodel") pr.rtl_configs = backends::rtl_configs();
  pr.choose_mapping = !a.mapping_given && session.size() == 1;
  if (a.bits_given) pr.bits = a.given.n;
  if (!a.quiet) pr.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  if (!a.config.empty()) {
    const Config c = named_config(a.config);
    pr.blocks = c.blocks;
    pr.words = c.words;
  }
  if (a.blocks_given) pr.blocks = a.blocks;
  if (a.words_given) pr.words = a.words;
  // The frame's settings the plan's check renders with (plan.h).
  pr.shadow_stop = !a.no_shadow_stop;
  if (a.order_given) pr.coherent = a.given.coherent;
  if (a.merge_given) pr.merge_below = a.given.merge_below;
  if (!a.shadow_calls.empty()) pr.kinds_together = a.shadow_calls == "together";
  pr.verify_exact = a.verify;
  return pr;
}

// The machine's part of the report: its size and options, its counters in all and by kind
// of batch, and each chip's on several.
void report_machine(const Args& a, const Config& cfg, const isect::KernelOptions& ko, const rt::FmppIntersector& fi,
                    const mpi::RenderChips& chips, bool together, nlohmann::json* rep) {
  nlohmann::json& r = *rep;
  r["fmpp"] = isect::options_json(ko, isect::kReported);
  r["fmpp"].update({{"blocks", cfg.blocks}, {"words", cfg.words}, {"shadow_stop", !a.no_shadow_stop},
                    {"object_parallel", r["plan"]["object_parallel"]},
                    {"shadow_calls", together ? "together" : "apart"}});
  const isect::KernelStats st = chips.total(fi.stats());  // one chip's: its own
  r.update(isect::stats_json(st, a.clock_mhz));
  if (ko.oracle) r["oracle"] = isect::oracle_json(st);
  for (int k = 0; k < rt::kNumBatchKinds; ++k) {
    const auto kind = static_cast<rt::BatchKind>(k);
    const isect::KernelStats kst = chips.total(fi.stats(kind));
    nlohmann::json j = isect::stats_json(kst, a.clock_mhz);
    if (ko.oracle) j["oracle"] = isect::oracle_json(kst);
    r["by_kind"][rt::to_string(kind)] = j;
  }
  // The calls of shadow and secondary rays together (--shadow-calls together): not
  // in either kind's counters above, in the totals.
  if (fi.stats_together().cycles > 0) {
    nlohmann::json j = isect::stats_json(chips.total(fi.stats_together()), a.clock_mhz);
    if (ko.oracle) j["oracle"] = isect::oracle_json(fi.stats_together());
    r["by_kind"]["shadow_and_secondary"] = j;
  }
  if (nlohmann::json c = chips.report(fi.stats(), a.clock_mhz); !c.is_null()) r["chips"] = c;
}

// The frame on the FMPP: the precision plan, then the frame with the plan's machine and
// choices (the frame's kernel options are the plan's), and the machine's report.
rt::Image render_on_fmpp(const Args& a, const rt::Scene& scene, mpi::Session& session, const rt::RenderOptions& ro,
                         tools::RenderProgress& progress, Phases* phases, rt::RenderStats* rs, nlohmann::json* rep) {
  rt::PlanRequest pr = plan_request(a, session);
  // The forms the plan's golden-model runs prepare are kept for the frame: those of the
  // chosen n it finds (the same answers and clocks) come off the plan's seconds.
  isect::FormCache forms(scene.triangles, rt::kPlanFormBytes);
  pr.forms = &forms;
  rt::ExactCheckStats plan_checked;
  pr.verified = &plan_checked;
  const tools::RenderPlan rp = phases->time("plan", [&] {
    return tools::plan_render(scene, pr, {a.plan_cache, a.replan, a.accept_miss, a.quiet}, rep);
  });
  const rt::Plan& plan = rp.plan;
  forms.next_phase();
  const Config cfg = plan.config;
  mpi::RenderChips chips(session);
  auto be = make_backend(a.backend, cfg, a.bo);
  Device dev(be->bus());
  isect::KernelOptions ko = pr.base;
  ko.n = plan.options.n;
  ko.coherent = plan.options.coherent;  // the user's where given (PlanRequest), else the plan's
  ko.merge_below = plan.options.merge_below;
  ko.t_accuracy = plan.options.t_accuracy;  // the user's, or the plan's escalation
  ko.oracle = a.given.oracle;
  ko.progress = [&](uint64_t done, uint64_t planned) { progress.pass(done, planned); };
  ko.forms = &forms;
  chips.agree(scene.triangles, cfg, ko);
  ko.share = chips.attach(dev, a.rank0 == "work");
  rt::FmppIntersector fi(dev, scene.triangles, ko);
  fi.set_shadow_stop(!a.no_shadow_stop);
  for (int k = 0; k < rt::kNumBatchKinds; ++k) {
    if (plan.object[k]) fi.set_mapping(static_cast<rt::BatchKind>(k), isect::Mapping::kObject);
  }
  fi.set_kinds_together(plan.kinds_together);
  rt::Image img = phases->time("frame", [&] {
    rt::Image frame = render_frame(scene, chips.wrap(fi), ro, rs, a.verify, a.command, plan_checked, rep);
    be->finish();
    return frame;
  });
  // The plan's own seconds: its wall time less the preparation the frame reused.
  (*rep)["plan"]["wall_seconds"] = rp.seconds;
  (*rep)["plan"]["reused_by_frame_seconds"] = forms.carried_seconds();
  (*rep)["plan"]["seconds"] = rp.seconds - forms.carried_seconds();
  report_machine(a, cfg, ko, fi, chips, plan.kinds_together, rep);
  return img;
}

// The rays by kind in the report, and those the host redid.
void report_rays(const Args& a, const rt::RenderStats& rs, nlohmann::json* rep) {
  (*rep)["intersect_seconds"] = rs.intersect_seconds;
  for (int k = 0; k < rt::kNumRayKinds; ++k) {
    const char* kind = rt::to_string(static_cast<rt::RayKind>(k));
    (*rep)["rays"][kind] = rs.rays[k];
    if (a.backend != "reference") {
      (*rep)["rays_redone"][kind] = {
          {"flagged", rs.flagged[k]}, {"t_from_host", rs.t_from_host[k]}, {"overflow", rs.overflow[k]}};
    }
  }
}

// The picture, the comparison with the reference (--compare-reference), the report and
// the console's summary.
void write_outputs(const Args& a, const rt::Scene& scene, const rt::Image& img, const rt::RenderOptions& ro,
                   Phases* phases, nlohmann::json* rep) {
  phases->time("write", [&] { img.write(a.out); });
  if (a.compare) {
    phases->time("compare", [&] {
      rt::ReferenceIntersector ref(scene.triangles);
      rt::RenderOptions quiet_ro = ro;
      quiet_ro.progress = nullptr;
      const rt::Image want = rt::render(scene, ref, quiet_ro, nullptr);
      const rt::ImageDiff d = rt::compare(img, want);
      (*rep)["reference_diff"] = {
          {"pixels", d.pixels}, {"pixels_over_8_levels", d.pixels_over}, {"max_delta", d.max_delta}};
    });
  }
  (*rep)["phase_seconds"] = phases->with_total();
  if (!a.report_file.empty()) write_text(a.report_file, rep->dump(2) + "\n");
  if (!a.quiet) {
    std::fprintf(stderr, "wrote %s (%dx%d, %s)\n", a.out.c_str(), a.width, a.height, a.backend.c_str());
    tools::print_summary(stderr, *rep);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<mpi::Session> session;  // MPI only under a launcher (docs/multichip.md)
  try {
    session = std::make_unique<mpi::Session>(&argc, &argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-render: %s\n", e.what());
    return 1;
  }
  Args a;
  if (const int status = parse(argc, argv, &a); status >= 0) return status;
  a.quiet = a.quiet || !session->leader();
  std::string stage = "checking the options";  // for an out-of-memory message
  try {
    check(a, *session);
    stage = "loading " + a.scene_file;
    Phases phases;
    const rt::Scene scene = phases.time("load", [&] { return load(a); });
    nlohmann::json rep = scene_report(a, scene);
    tools::RenderProgress progress(a.quiet, tools::shadow_prior(scene));
    rt::RenderOptions ro;
    ro.width = a.width;
    ro.height = a.height;
    ro.max_depth = a.depth;
    ro.progress = [&](const rt::BatchProgress& b) { progress.batch(b); };
    rt::RenderStats rs;
    stage = "rendering " + std::to_string(a.width) + "x" + std::to_string(a.height);
    const auto t0 = Clock::now();
    const rt::Image img = a.backend == "reference" ? render_on_host(a, scene, ro, &phases, &rs, &rep)
                                                   : render_on_fmpp(a, scene, *session, ro, progress, &phases, &rs, &rep);
    progress.finish();
    rep["wall_seconds"] = seconds_since(t0);
    phases.set("intersect", rs.intersect_seconds);
    phases.set("shade", rs.shade_seconds);
    report_rays(a, rs, &rep);
    if (!session->leader()) return 0;  // rank 0 writes
    stage = "writing " + a.out;
    write_outputs(a, scene, img, ro, &phases, &rep);
    return 0;
  } catch (const std::bad_alloc&) {
    if (session->size() > 1) session->abort("fmpp-render", "out of memory while " + stage, 1);
    std::fprintf(stderr, "fmpp-render: out of memory while %s (limits: docs/reliability.md)\n", stage.c_str());
    return 1;
  } catch (const std::exception& e) {
    // On several ranks: the rank and the cause, and every rank ends (no picture is written).
    const int status = error_status(e, stage == "checking the options");  // 2: a usage error
    if (session->size() > 1) session->abort("fmpp-render", e.what(), status);
    return print_error("fmpp-render", e.what(), status);
  }
}
