// fmpp-report precision: what the FMPP's fixed-point format costs in accuracy and what
// accuracy costs in clocks, measured on the project's scenes with the golden model
// (clock-exact with the RTL), for each multiplier width n, both multiplies (generic and
// constant, bit-identical by construction) and the watertight form; plus the leak rate
// of the paper's form and the watertight one on a closed mesh around the eye.
//
// The subcommand measures (precision_measure.cpp), picks per scene the smallest n
// meeting each criterion (precision_choose.cpp) and writes docs/generated/precision.md
// (precision_markdown.cpp), its JSON data and the plots (tools/plot_precision.py);
// precision.h holds the data passed between them.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "sw/report/output.h"
#include "sw/report/precision.h"
#include "sw/report/report.h"

namespace fmpp::report {

Command add_precision(CLI::App& app) {
  auto opt = std::make_shared<precision::Options>();
  Command c;
  c.sub = app.add_subcommand("precision", "accuracy against cycles for each multiplier width, on the scenes (golden model)");
  add_output_options(c.sub, *opt);
  c.sub->add_option("--scenes", opt->scenes_dir, "directory holding the scene JSON files")->capture_default_str();
  CLI::Option* size_opt = c.sub->add_option("--size", opt->size, "image width and height in pixels")
                              ->capture_default_str()
                              ->check(CLI::Range(2, 256));
  std::vector<std::string> names(std::begin(precision::kScenes), std::end(precision::kScenes));
  names.push_back(precision::kScannedScene);
  c.sub->add_option("--only-scene", opt->only_scene,
                    "measure this scene only and no leak rates: its section alone is the full run's (for the "
                    "docs_check test)")
      ->check(CLI::IsMember(names));
  c.sub->add_flag("--quick", opt->quick, "8 x 8 pixels, n = 8 and 24 only, fewer leak rays (for tests)")
      ->excludes(size_opt);
  c.run = [opt]() -> int {
    prepare_outputs(*opt);
    const precision::Options& o = *opt;
    const precision::Setup setup = precision::make_setup(o);
    const std::string date = today();

    const precision::SceneResults scenes = precision::measure_scenes(o, setup);
    const precision::Leaks leaks = precision::measure_leaks(o, setup);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup.start).count();

    const std::vector<precision::Choice> choices = precision::choose_n(scenes);

    const std::string md = precision::markdown(o, setup, date, seconds, scenes, leaks, choices);
    write_report(o, md, precision::report_data(setup, scenes, leaks, choices));
    std::fprintf(stderr, "[precision] wrote %s (%.0f s)\n", o.out.c_str(), seconds);
    return scenes.consistent ? 0 : 1;
  };
  return c;
}

}  // namespace fmpp::report
