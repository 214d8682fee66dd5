// fmpp-report: reports built from measurements of the FMPP (see report.h).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <vector>

#include "sw/report/report.h"

int main(int argc, char** argv) {
  CLI::App app{"FMPP reports: reproductions and measurements"};
  app.require_subcommand(1);
  std::vector<fmpp::report::Command> cmds;
  cmds.push_back(fmpp::report::add_paper(app));
  CLI11_PARSE(app, argc, argv);
  for (auto& c : cmds) {
    if (!c.sub->parsed()) continue;
    try {
      return c.run();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fmpp-report %s: %s\n", c.sub->get_name().c_str(), e.what());
      return 1;
    }
  }
  return 1;
}
