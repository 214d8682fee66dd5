// fmpp-report subcommands. Each adds itself to the CLI11 app and returns how to run it;
// main() runs the chosen one and turns exceptions into an error message and exit code 1.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace fmpp::report {

struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> run;
};

// `paper`: the paper's Table 1, steps per broadcast, Table 2, Fig. 7, Amdahl and the
// CPU baseline, from cycles measured on the RTL (paper.cpp).
Command add_paper(CLI::App& app);

}  // namespace fmpp::report
