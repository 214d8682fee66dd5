// fmpp-report: the command line front end. Subcommands register themselves here
// (see report.h); this file holds no report logic.
//
//   fmpp-report area [--synth-dir build/synth]
#include <cstdio>
#include <exception>

#include "sw/report/report.h"

int main(int argc, char** argv) {
  CLI::App app{"FMPP reports: this project's measured figures beside the paper's"};
  app.require_subcommand(1);
  fmpp::report::register_area(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-report: %s\n", e.what());
    return 1;
  }
  return 0;
}
