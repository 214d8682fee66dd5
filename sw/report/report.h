// fmpp-report: reports that set this project's measured figures beside the paper's
// (Yamada and Yasuura, "High speed Ray Tracing Algorithms on FMPP").
//
// Each subcommand lives in its own file and is added to the CLI by report_main.cpp.
// Two styles: `register_*` subcommands do their work in their CLI11 callback (during
// parsing); `add_*` subcommands return a Command that main runs after parsing. Either
// throws std::exception on bad input (the message names the file, line and field);
// main prints it and exits 1.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace fmpp::report {

// `fmpp-report area`: synthesis cost per block and per stored bit (tools/synth.sh
// output) beside the paper's Table 3 transistor counts.
void register_area(CLI::App& app);

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;
};

// `fmpp-report paper`: the paper's Table 1, steps per broadcast, Table 2, Fig. 7, Amdahl
// and the CPU baseline, from cycles measured on the RTL (paper.cpp).
Command add_paper(CLI::App& app);

// `fmpp-report precision`: accuracy against cycles for each multiplier width n, both
// multiplies and the watertight form, on the scenes (golden model), the leak rate on a
// closed mesh, and the hard-case list (precision.cpp).
Command add_precision(CLI::App& app);

}  // namespace fmpp::report
