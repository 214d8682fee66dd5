// fmpp-render's command line (render_args.h).
#include "sw/tools/render_args.h"

#include <CLI/CLI.hpp>
#include <stdexcept>

#include "common/util/cli_usage.h"
#include "sw/render/image.h"
#include "sw/render/render.h"

using namespace fmpp;

namespace render_cli {
namespace {

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

}  // namespace

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

}  // namespace render_cli
