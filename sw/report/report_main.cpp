// fmpp-report: the command line front end. Subcommands register themselves here
// (see report.h); this file holds no report logic.
//
//   fmpp-report area [--synth-dir build/synth]
//   fmpp-report paper [--out docs/paper-reproduction.md]
//   fmpp-report precision [--out docs/precision.md] [--quick]
#include <cstdio>
#include <exception>
#include <vector>

#include "sw/report/report.h"

int main(int argc, char** argv) {
  CLI::App app{"FMPP reports: this project's measured figures beside the paper's"};
  app.require_subcommand(1);
  fmpp::report::register_area(app);
  std::vector<fmpp::report::Command> cmds;
  cmds.push_back(fmpp::report::add_paper(app));
  cmds.push_back(fmpp::report::add_precision(app));
  try {
    app.parse(argc, argv);
    for (auto& c : cmds) {
      if (c.sub->parsed()) return c.run();
    }
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-report: %s\n", e.what());
    return 1;
  }
  return 0;
}
