// fmpp-report: the command line front end. Subcommands register themselves here
// (see report.h); this file holds no report logic.
//
//   fmpp-report area [--synth-dir build/synth] [--out FILE]     (stdout without --out)
//   fmpp-report paper [--out FILE] [--quick]
//   fmpp-report precision [--out FILE] [--quick]
// paper and precision write under the build directory unless given paths: BUILD/docs/
// (generated/, img/, data/), or BUILD/paper-quick.md, BUILD/precision-quick.md with
// --quick (output.h); never the source tree, which only `make docs-update` writes.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "common/util/cli_checks.h"
#include "common/util/cli_usage.h"
#include "sw/report/report.h"

int main(int argc, char** argv) {
  CLI::App app{"FMPP reports: this project's measured figures beside the paper's"};
  app.require_subcommand(1);
  fmpp::report::register_area(app);
  std::vector<fmpp::report::Command> cmds;
  cmds.push_back(fmpp::report::add_paper(app));
  cmds.push_back(fmpp::report::add_precision(app));
  // Every subcommand's --help ends with the exit statuses too.
  const std::string footer = fmpp::exit_status_footer(
      "an error (an input or output the report cannot use, measurements that disagree; the message says which)");
  app.footer(footer);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) sub->footer(footer);
  try {
    app.parse(argc, argv);
    for (auto& c : cmds) {
      if (c.sub->parsed()) return c.run();
    }
  } catch (const CLI::ParseError& e) {
    // "fmpp-report foo": CLI11 only says that a subcommand is required; name the word.
    const std::vector<std::string> rest = app.remaining();
    if (e.get_exit_code() != 0 && app.get_subcommands().empty() && !rest.empty() && rest.front().rfind("-", 0) != 0) {
      std::vector<std::string> names;
      for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(sub->get_name());
      const std::string near = fmpp::closest_word(rest.front(), names);
      return fmpp::usage_error(app, "unknown subcommand '" + rest.front() + "' (one of: " + fmpp::join(names, ", ") +
                                        ")" + (near.empty() ? "" : "; did you mean " + near + "?"));
    }
    return fmpp::parse_error_exit(app, e);
  } catch (const std::exception& e) {
    return fmpp::print_error("fmpp-report", e.what(), fmpp::error_status(e, false));  // 2: a UsageError
  }
  return 0;
}
