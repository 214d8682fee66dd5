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

// The frame rendered through `isect`, every answer checked against the exact reference
// where `verify`: the report's "verify_exact" (with the plan's checked renders, `plan`).
rt::Image render_frame(const rt::Scene& scene, rt::Intersector& isect, const rt::RenderOptions& ro, rt::RenderStats* rs,
                       bool verify, const std::string& command, const rt::ExactCheckStats& plan, nlohmann::json* rep) {
  rt::ExactCheckStats st;
  rt::Image img = rt::render_checked(scene, isect, ro, rs, verify, command, &st);
  if (verify) (*rep)["verify_exact"] = rt::exact_check_json(st, plan);
  return img;
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
  const bool leader = session->leader();
  CLI::App app{"Whitted ray tracing with the intersections on the FMPP"};
  // The default scene is the repository's Cornell box wherever the tool is started; the
  // picture goes to the path given, by default render.png in the current directory.
  std::string scene_file = repo_file("scenes/cornell.json"), backend = "rtl", config, out = "render.png", report_file;
  int width = 128, height = 128, depth = -1;
  unsigned blocks = 4096, words = 32;  // the plan decides unless given
  double clock_mhz = 50;
  bool compare = false, quiet = false;
  app.add_option("--scene", scene_file, "scene JSON file (default: the repository's Cornell box)")->capture_default_str();
  app.add_option("--backend", backend,
                 "reference (double precision on the host) or the machine: " + join(backend_names(), " | "))
      ->capture_default_str()
      ->check(CLI::IsMember(tool_backends()));
  app.add_option("--width", width, "image width")->capture_default_str()->check(int_range(1, 16384));
  app.add_option("--height", height, "image height")->capture_default_str()->check(int_range(1, 16384));
  // The kernel options' flags (sw/tools/kernel_flags.h); the plan chooses --bits,
  // --mapping, --merge-below and --pass-order unless given.
  tools::KernelFlags kernel_flags;
  kernel_flags.add(app, tools::FlagTool::kRender);
  CLI::Option* blocks_opt = app.add_option("--blocks", blocks, "FMPP blocks (default: chosen by the precision plan)")
                               ->check(int_range(1, map::kMaxBlocks));
  CLI::Option* words_opt = app.add_option("--words", words, "FMPP words per block, even (default: chosen by the precision plan)")
                              ->check(even_words());
  exclude_config_sizes(app.add_option("--config", config, "a named FMPP configuration instead of --blocks/--words"),
                       blocks_opt, words_opt);
  double target = 0.002;
  app.add_option("--error-target", target,
                 "precision plan: wrong-triangle rate allowed per primary ray, and share of the frame's "
                 "pixels allowed off the reference (a 95 % upper bound from sampled pixels)")
      ->capture_default_str()
      ->check(finite_range(0.0, 1.0));
  bool replan = false;
  app.add_flag("--replan", replan, "plan again even if this scene and these options have a cached plan");
  std::string plan_cache = rt::default_plan_cache_dir();
  app.add_option("--plan-cache", plan_cache,
                 "directory of cached precision plans (a second render of the same scene files with the same options "
                 "reuses its plan; empty: no cache)")
      ->capture_default_str();
  bool accept_miss = false;
  app.add_flag("--accept-plan-miss", accept_miss,
               "render even when the precision plan finds no n that keeps --error-target (without it, such a "
               "render stops with an error before any work on the frame)");
  int sample_pixels = 3000;
  app.add_option("--plan-pixels", sample_pixels,
                 "precision plan: pixels of the frame drawn at random and rendered per candidate n")
      ->capture_default_str()
      ->check(int_range(1, 1 << 24));
  app.add_option("--max-depth", depth, "recursion depth (default: the scene's)")->check(int_range(1, 16));
  int spp = 0;
  app.add_option("--spp", spp,
                 "samples per pixel: stratified, jittered, averaged with a box filter over the pixel (default: the "
                 "scene's samples_per_pixel, else 1, the pixel's centre)")
      ->check(int_range(1, rt::kMaxSpp));
  uint64_t seed = 0;
  app.add_option("--seed", seed,
                 "seed of the pixel samples and the area lights' samples (default: the scene's seed, else " +
                     std::to_string(rt::kDefaultSeed) + ")")
      ->check(non_negative());
  app.add_option("--out", out,
                 "output image: .png (8-bit), .pfm or .exr (linear radiance, 32-bit float, unclamped); by default in the "
                 "current directory")
      ->capture_default_str();
  app.add_option("--report", report_file, "JSON report file ('-' for stdout)");
  app.add_option("--clock-mhz", clock_mhz, "clock for the simulated time")
      ->capture_default_str()
      ->check(finite_range(1.0, 1e5));
  app.add_flag("--compare-reference", compare, "also render with the reference and count differing pixels");
  bool verify = false;
  app.add_flag("--verify-exact", verify,
               "check every answer of the frame against the exact reference's answer for the same ray; the first "
               "answer the intersection contract does not allow stops the render with the ray, its pass, n, the "
               "machine and the options (docs/certification.md)");
  bool no_shadow_stop = false;
  std::string shadow_calls;
  app.add_option("--shadow-calls", shadow_calls,
                 "together | apart: each depth's last shadow batch in one kernel call with the next depth's rays, or "
                 "in its own (default: the precision plan's choice, from its cost model)")
      ->check(CLI::IsMember({"together", "apart"}));
  app.add_flag("--no-shadow-stop", no_shadow_stop,
               "shadow rays as nearest-hit queries, not stopped at their first certified occluder (the same image, "
               "more clocks)");
  BackendOptions bo;
  add_trace_options(app, bo);
  app.add_flag("--quiet", quiet,
               "no progress display and no closing summary on the console (the report keeps the figures); without "
               "it, stderr gets one progress line for the frame (rays of the rays expected, rate, ETA), redrawn on a "
               "terminal and printed every 3 s otherwise (FMPP_PROGRESS_INTERVAL=seconds sets another interval), "
               "and a summary at the end");
  std::string rank0 = "work";
  app.add_option("--rank0", rank0, "under mpirun: rank 0 drives an FMPP too (work) or only hands out passes (schedule)")
      ->capture_default_str()
      ->check(CLI::IsMember({"work", "schedule"}));
  app.footer(exit_status_footer("an error of the work (a scene or output it cannot use, a plan that misses its target)"));
  if (const int status = parse_command_line(app, argc, argv); status >= 0) return status;
  std::string command = "The command:";
  for (int i = 0; i < argc; ++i) command += std::string(" ") + argv[i];

  std::string stage = "checking the options";  // for an out-of-memory message
  quiet = quiet || !leader;
  const isect::KernelOptions given = kernel_flags.options();
  try {
    if (session->size() > 1 && given.mapping == isect::Mapping::kObject) {
      throw std::invalid_argument("--mapping object cannot run on several FMPPs (its passes keep each ray's best "
                                  "across passes); use --mapping ray or one rank");
    }
    if (session->size() > 1 && !bo.trace_file.empty()) {
      throw std::invalid_argument("--trace " + bo.trace_file + " on several ranks: every FMPP would write that file");
    }
    check_trace_options(backend, bo);
    check_config_name(backend, config);
    if (given.mapping == isect::Mapping::kObject && given.watertight) {
      throw std::invalid_argument("--watertight with --mapping object: the watertight form exists in the ray-parallel "
                                  "mapping only; use --mapping ray");
    }
    rt::check_resolution(width, height);
    // Every output is checked before the render, not after it.
    if (out == "-") throw std::invalid_argument("--out -: the image needs a file name (stdout is only for --report -)");
    rt::image_format(out);  // .png, .pfm or .exr, refused before any work otherwise
    if (leader) check_writable("--out", out, false);
    if (leader && !report_file.empty()) check_writable("--report", report_file);
    stage = "loading " + scene_file;
    const auto t_load = std::chrono::steady_clock::now();
    const auto since = [](std::chrono::steady_clock::time_point t) {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    nlohmann::json phases;  // wall time by phase: the report's "phase_seconds" and the summary
    rt::Scene loaded = rt::load_scene(scene_file);
    // --spp and --seed replace the scene's, for the plan's sample as for the frame.
    if (app.count("--spp")) loaded.spp = spp;
    if (app.count("--seed")) loaded.seed = seed;
    const rt::Scene& scene = loaded;
    {
      std::vector<NamedPath> inputs;
      for (const auto& f : scene.files) inputs.push_back({f == scene_file ? "--scene" : "mesh of --scene", f});
      check_no_alias({{"--out", out}, {"--report", report_file}, {"--trace", bo.trace_file}}, inputs);
    }
    phases["load"] = since(t_load);
    nlohmann::json rep;
    rep["scene"] = scene_file;
    rep["triangles"] = scene.triangles.size();
    rep["resolution"] = {width, height};
    rep["backend"] = backend;
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
    tools::RenderProgress progress(quiet, tools::shadow_prior(scene));
    rt::RenderOptions ro;
    ro.width = width;
    ro.height = height;
    ro.max_depth = depth;
    ro.progress = [&](const rt::BatchProgress& b) { progress.batch(b); };
    rt::RenderStats rs;
    stage = "rendering " + std::to_string(width) + "x" + std::to_string(height);
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<rt::Image> img;
    if (backend == "reference") {
      rt::ReferenceIntersector ref(scene.triangles);
      const auto t_frame = std::chrono::steady_clock::now();
      img = std::make_unique<rt::Image>(render_frame(scene, ref, ro, &rs, verify, command, {}, &rep));
      phases["frame"] = since(t_frame);
    } else {
      // The precision plan chooses what the options leave open; the frame's kernel options
      // are the same as the plan's, with its choices. The plan starts from the defaults of
      // what it chooses (n, the pass order, merge_below: the user's, where given, go in the
      // request below) and never counts for the oracle.
      const isect::KernelOptions defaults;
      isect::KernelOptions base = given;
      base.n = defaults.n;
      base.coherent = defaults.coherent;
      base.merge_below = defaults.merge_below;
      base.oracle = false;
      rt::PlanRequest pr;
      pr.width = width;
      pr.height = height;
      pr.max_depth = depth;
      pr.target_wrong_rate = target;
      pr.sample_pixels = sample_pixels;
      if (backend != "cmodel") pr.rtl_configs = backends::rtl_configs();
      pr.base = base;
      pr.choose_mapping = !app.count("--mapping") && !kernel_flags.form_given() && session->size() == 1;
      if (app.count("--bits")) pr.bits = given.n;
      if (!quiet) pr.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
      if (!config.empty()) {
        const Config c = named_config(config);
        pr.blocks = c.blocks;
        pr.words = c.words;
      }
      if (app.count("--blocks")) pr.blocks = blocks;
      if (app.count("--words")) pr.words = words;
      // The frame's settings the plan's check renders with (plan.h).
      pr.shadow_stop = !no_shadow_stop;
      if (app.count("--pass-order")) pr.coherent = given.coherent;
      if (app.count("--merge-below")) pr.merge_below = given.merge_below;
      if (!shadow_calls.empty()) pr.kinds_together = shadow_calls == "together";
      // The forms the plan's golden-model runs prepare are kept for the frame: those of the
      // chosen n it finds (the same answers and clocks) come off the plan's seconds.
      isect::FormCache forms(scene.triangles, rt::kPlanFormBytes);
      pr.forms = &forms;
      rt::ExactCheckStats plan_checked;
      pr.verify_exact = verify;
      pr.verified = &plan_checked;
      const auto t_plan = std::chrono::steady_clock::now();
      const tools::RenderPlan rp = tools::plan_render(scene, pr, {plan_cache, replan, accept_miss, quiet}, &rep);
      phases["plan"] = since(t_plan);
      const rt::Plan& plan = rp.plan;
      forms.next_phase();
      const Config cfg = plan.config;
      mpi::RenderChips chips(*session);
      auto be = make_backend(backend, cfg, bo);
      Device dev(be->bus());
      isect::KernelOptions ko = base;
      ko.n = plan.options.n;
      ko.coherent = plan.options.coherent;  // the user's where given (PlanRequest), else the plan's
      ko.merge_below = plan.options.merge_below;
      ko.t_accuracy = plan.options.t_accuracy;  // the user's, or the plan's escalation
      ko.oracle = given.oracle;
      ko.progress = [&](uint64_t done, uint64_t planned) { progress.pass(done, planned); };
      ko.forms = &forms;
      chips.agree(scene.triangles, cfg, ko);
      ko.share = chips.attach(dev, rank0 == "work");
      rt::FmppIntersector fi(dev, scene.triangles, ko);
      fi.set_shadow_stop(!no_shadow_stop);
      for (int k = 0; k < rt::kNumBatchKinds; ++k) {
        if (plan.object[k]) fi.set_mapping(static_cast<rt::BatchKind>(k), isect::Mapping::kObject);
      }
      const bool together = plan.kinds_together;
      fi.set_kinds_together(together);
      const auto t_frame = std::chrono::steady_clock::now();
      img = std::make_unique<rt::Image>(
          render_frame(scene, chips.wrap(fi), ro, &rs, verify, command, plan_checked, &rep));
      be->finish();
      phases["frame"] = since(t_frame);
      // The plan's own seconds: its wall time less the preparation the frame reused.
      rep["plan"]["wall_seconds"] = rp.seconds;
      rep["plan"]["reused_by_frame_seconds"] = forms.carried_seconds();
      rep["plan"]["seconds"] = rp.seconds - forms.carried_seconds();
      const isect::KernelStats st = chips.total(fi.stats());  // one chip's: its own
      rep["fmpp"] = isect::options_json(ko, isect::kReported);
      rep["fmpp"].update({{"blocks", cfg.blocks}, {"words", cfg.words}, {"shadow_stop", !no_shadow_stop},
                          {"object_parallel", rep["plan"]["object_parallel"]},
                          {"shadow_calls", together ? "together" : "apart"}});
      rep.update(isect::stats_json(st, clock_mhz));
      if (ko.oracle) rep["oracle"] = isect::oracle_json(st);
      for (int k = 0; k < rt::kNumBatchKinds; ++k) {
        const auto kind = static_cast<rt::BatchKind>(k);
        const isect::KernelStats kst = chips.total(fi.stats(kind));
        nlohmann::json j = isect::stats_json(kst, clock_mhz);
        if (ko.oracle) j["oracle"] = isect::oracle_json(kst);
        rep["by_kind"][rt::to_string(kind)] = j;
      }
      // The calls of shadow and secondary rays together (--shadow-calls together): not
      // in either kind's counters above, in the totals.
      if (fi.stats_together().cycles > 0) {
        nlohmann::json j = isect::stats_json(chips.total(fi.stats_together()), clock_mhz);
        if (ko.oracle) j["oracle"] = isect::oracle_json(fi.stats_together());
        rep["by_kind"]["shadow_and_secondary"] = j;
      }
      if (nlohmann::json c = chips.report(fi.stats(), clock_mhz); !c.is_null()) rep["chips"] = c;
    }
    progress.finish();
    rep["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    phases["intersect"] = rs.intersect_seconds;
    phases["shade"] = rs.shade_seconds;
    rep["intersect_seconds"] = rs.intersect_seconds;
    for (int k = 0; k < rt::kNumRayKinds; ++k) {
      const char* kind = rt::to_string(static_cast<rt::RayKind>(k));
      rep["rays"][kind] = rs.rays[k];
      if (backend != "reference") {
        rep["rays_redone"][kind] = {
            {"flagged", rs.flagged[k]}, {"t_from_host", rs.t_from_host[k]}, {"overflow", rs.overflow[k]}};
      }
    }
    if (!leader) return 0;  // rank 0 writes
    stage = "writing " + out;
    const auto t_write = std::chrono::steady_clock::now();
    img->write(out);
    phases["write"] = since(t_write);
    if (compare) {
      const auto t_compare = std::chrono::steady_clock::now();
      rt::ReferenceIntersector ref(scene.triangles);
      rt::RenderOptions quiet_ro = ro;
      quiet_ro.progress = nullptr;
      const rt::Image want = rt::render(scene, ref, quiet_ro, nullptr);
      const rt::ImageDiff d = rt::compare(*img, want);
      rep["reference_diff"] = {{"pixels", d.pixels}, {"pixels_over_8_levels", d.pixels_over}, {"max_delta", d.max_delta}};
      phases["compare"] = since(t_compare);
    }
    phases["total"] = since(t_load);
    rep["phase_seconds"] = phases;
    if (!report_file.empty()) write_text(report_file, rep.dump(2) + "\n");
    if (!quiet) {
      std::fprintf(stderr, "wrote %s (%dx%d, %s)\n", out.c_str(), width, height, backend.c_str());
      tools::print_summary(stderr, rep);
    }
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
