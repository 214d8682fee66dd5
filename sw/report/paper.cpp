// fmpp-report paper: the evaluation of Yamada & Yasuura reproduced from cycles
// measured on the Verilated RTL (the golden model, which is clock-exact with it, where
// the RTL would be too slow; the output says which).
//
// The subcommand measures (paper_measure.cpp), derives from the measured costs what the
// clock model gives for machines too large to simulate (paper_model.cpp), and writes
// the Markdown (paper_markdown.cpp), its JSON data and the plots; paper.h holds the data
// passed between them.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "common/util/cli_usage.h"
#include "sw/report/output.h"
#include "sw/report/paper.h"
#include "sw/report/report.h"
#include "sw/tools/cli_options.h"

namespace fmpp::report {

Command add_paper(CLI::App& app) {
  auto opt = std::make_shared<paper::Options>();
  Command c;
  c.sub = app.add_subcommand("paper", "reproduce the paper's evaluation from cycles measured on the RTL");
  add_output_options(c.sub, *opt);
  c.sub->add_option("--rtl-config", opt->rtl_config, "Verilated configuration to measure on")->capture_default_str();
  c.sub->add_option("--triangles", opt->triangles, "triangles in the step-count scene (at most 300 with --quick)")
      ->capture_default_str()
      ->check(CLI::Range(10u, 1000000u));
  c.sub->add_option("--bits", opt->n, "multiplier bits n of the comparison (the n sweep is 8 to 32 whatever this is)")
      ->capture_default_str()
      ->check(bits_range());
  c.sub->add_flag("--quick", opt->quick, "small measurement sizes (for tests)");
  c.sub->add_flag("--counts-only", opt->counts_only,
                  "measure the clock and instruction counts only, not the CPU's speed: the sections that compare "
                  "with the CPU then hold a rate of 1 test/s (the deterministic part, for the docs_check test)");
  c.sub->add_option("--fpga-csv", opt->fpga_csv, "summary.csv of tools/fpga.sh (the measured clock)")
      ->capture_default_str();
  c.sub->add_option("--clock", opt->clocks,
                    "MHZ:LABEL, a further clock for the comparison with the CPU, labelled measured or projected "
                    "(repeatable; make docs passes make asic's clock and its projection to the CPU's node)");
  c.run = [opt]() -> int {
    const FpgaData fpga = read_fpga(opt->fpga_csv);  // before any output or measurement: a bad file fails at once
    std::vector<paper::Clock> clocks;
    usage_checks([&] {  // a bad --clock is a usage error (exit 2)
      for (const std::string& text : opt->clocks) clocks.push_back(paper::parse_clock(text));
    });
    prepare_outputs(*opt);
    const paper::Options& o = *opt;
    const Config rcfg = named_config(o.rtl_config);
    const unsigned m_scene = o.quick ? std::min(o.triangles, 300u) : o.triangles;
    const std::string date = today();

    const paper::Table1 t1 = paper::measure_table1(o.rtl_config, rcfg, o.n);
    const paper::Workload w = paper::make_workload(rcfg, m_scene, o.quick);
    const paper::Broadcasts b = paper::measure_broadcasts(rcfg, w, o.n);
    const paper::Sweep sweep = paper::measure_sweep(rcfg, w);
    const paper::CpuRates cpu = o.counts_only ? paper::CpuRates{1, 1} : paper::measure_cpu(o.quick);

    const paper::Derived d = paper::derive(w, b, cpu, o.n, clocks);

    const std::string md = paper::markdown(o, rcfg, date, paper::Measured{t1, w, b, sweep, cpu, fpga}, d);
    write_report(o, md, paper::report_data(t1, sweep, cpu, d));
    std::fprintf(stderr, "[paper] wrote %s\n", o.out.c_str());
    return 0;
  };
  return c;
}

}  // namespace fmpp::report
