// fmpp-report: reports that set this project's measured figures beside the paper's
// (Yamada and Yasuura, "High speed Ray Tracing Algorithms on FMPP").
//
// Each subcommand lives in its own file (area.cpp, ...) and is added to the CLI by
// its registration function, called from report_main.cpp. A subcommand's callback
// does the work and throws std::exception on bad input (the message names the file,
// line and field); main prints it and exits 1.
#pragma once

#include <CLI/CLI.hpp>

namespace fmpp::report {

// `fmpp-report area`: synthesis cost per block and per stored bit (tools/synth.sh
// output) beside the paper's Table 3 transistor counts.
void register_area(CLI::App& app);

}  // namespace fmpp::report
