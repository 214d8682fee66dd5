// `fmpp-report area`: the FMPP's synthesized cost (tools/synth.sh: yosys generic
// gates, `stat -tech cmos`) per block and per stored bit, beside the paper's Table 3
// (FMPP vs DRAM transistors for 128^2, 512^2 and 1024^2 pixels) and its figures of
// 18 transistors per CAM bit and about 1000 per block ALU. The subcommand reads the
// results (area_read.cpp), fits the cost model (area_model.cpp) and writes the
// Markdown (area_markdown.cpp).
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/report/area.h"
#include "sw/report/fpga.h"
#include "sw/report/report.h"
#include "common/util/files.h"

namespace fmpp::report {

namespace {
struct AreaOptions {
  std::string synth_dir = "build/synth";
  unsigned words = kPaperWordsRayParallel;
  std::string out;
  std::string fpga_csv;  // tools/fpga.sh summary.csv: adds the FPGA section (fpga.cpp)
  std::vector<std::string> baseline_dirs;    // earlier syntheses: a section comparing each with this one
  std::vector<std::string> baseline_labels;  // what each earlier RTL was
};
}  // namespace

void register_area(CLI::App& app) {
  auto opt = std::make_shared<AreaOptions>();
  CLI::App* sub = app.add_subcommand(
      "area", "synthesis cost per block and per stored bit beside the paper's Table 3 (reads tools/synth.sh output)");
  sub->add_option("--synth-dir", opt->synth_dir, "directory with summary.csv and cells.csv from tools/synth.sh")
      ->capture_default_str();
  sub->add_option("--words", opt->words, "words per processor for the Table 3 comparison (paper, ray-parallel: 23)")
      ->capture_default_str()
      ->check(CLI::Range(1u, 64u));
  sub->add_option("--out", opt->out, "write the Markdown report to this file instead of stdout ('-': stdout)");
  sub->add_option("--fpga-csv", opt->fpga_csv, "summary.csv of tools/fpga.sh: adds the measured FPGA clock and size");
  sub->add_option("--baseline-dir", opt->baseline_dirs,
                  "tools/synth.sh output of an earlier RTL: adds a section comparing its costs with these (repeatable)");
  sub->add_option("--baseline-label", opt->baseline_labels,
                  "what the earlier RTL of each --baseline-dir was (its heading; one per --baseline-dir, in order)");
  sub->callback([opt] {
    if (!opt->out.empty()) check_writable("--out", opt->out);
    if (opt->baseline_dirs.size() != opt->baseline_labels.size()) {
      throw std::runtime_error("--baseline-dir and --baseline-label go together (got " +
                               std::to_string(opt->baseline_dirs.size()) + " --baseline-dir and " +
                               std::to_string(opt->baseline_labels.size()) + " --baseline-label)");
    }
    const SynthData data = read_synth(opt->synth_dir);
    std::vector<SynthData> before;
    for (const std::string& dir : opt->baseline_dirs) before.push_back(read_synth(dir));
    FpgaData fpga;
    if (!opt->fpga_csv.empty()) fpga = read_fpga(opt->fpga_csv);
    auto write = [&](std::ostream& os) {
      write_area_report(data, opt->words, os);
      for (size_t k = 0; k < before.size(); ++k) {
        if (!before[k].sizes.empty()) write_baseline_section(data, before[k], opt->baseline_labels[k], opt->words, os);
      }
      if (!fpga.runs.empty()) write_fpga_section(fpga, os);
    };
    if (opt->out.empty() || opt->out == "-") {
      write(std::cout);
      return;
    }
    std::ofstream f(opt->out);
    if (!f) throw std::runtime_error(opt->out + ": cannot write");
    write(f);
  });
}

}  // namespace fmpp::report
