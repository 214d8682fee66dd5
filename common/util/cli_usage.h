// Command-line errors in the tools' own voice, shared by every tool (fmpp-render,
// fmpp-intersect, fmpp-report, fmpp-sim, fmpp-embree-bench): a leaf header that depends
// on CLI11 and the standard library only, so any layer may use it.
//
// A usage error - an unknown option, a bad or missing value, options that exclude or
// need each other, whether CLI11 finds it or the tool's own checks of the options after
// parsing (a UsageError, or a std::invalid_argument before any input is read:
// error_status) - prints "<tool>: <message>" and a hint on stderr and gives exit
// status 2 (kExitUsage), not CLI11's own codes (105, 109, ...); an unknown option names
// the closest known one: "fmpp-render: --widht: unknown option; did you mean --width?".
// --help prints the help (with the exit statuses in its footer) and gives 0.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace fmpp {

inline constexpr int kExitUsage = 2;

// An option value or combination that the tool's own checks refuse after parsing, before
// any work ("--out x.jpg: unknown image format", "--watertight with --mapping object"): a
// usage error too. The tools catch it before std::exception.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Runs checks of the options; what they throw as std::invalid_argument (how the project's
// checks refuse a value; a file that cannot be written is a std::runtime_error) is a
// UsageError.
template <class F>
void usage_checks(F&& checks) {
  try {
    checks();
  } catch (const UsageError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// The footer line of every tool's --help: what its exit statuses mean. `failure` is what
// status 1 means for the tool.
inline std::string exit_status_footer(const std::string& failure = "the work failed (its message says why)") {
  return "Exit status: 0 done, 1 " + failure + ", 2 a usage error (an unknown option, a bad or missing value).";
}

// Edit distance (optimal string alignment: insertions, deletions, substitutions and
// swaps of two neighbours each count 1), so "widht" is 1 from "width".
inline size_t edit_distance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i) {
    for (size_t j = 1; j <= m; ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[n][m];
}

// The candidate closest to `word`, if it is close: at most a third of the word's
// letters apart (at least 1), or the only candidate `word` begins (of 3 letters or more).
// "" when none is.
inline std::string closest_word(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_d = std::max<size_t>(1, word.size() / 3) + 1;
  std::vector<std::string> prefixed;
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
    if (word.size() >= 3 && c.size() > word.size() && c.compare(0, word.size(), word) == 0) prefixed.push_back(c);
  }
  if (best.empty() && prefixed.size() == 1) best = prefixed.front();
  return best;
}

namespace cli_detail {

// The long option names (without the dashes) of `app` and of the subcommands given on
// this command line.
inline void long_names(const CLI::App& app, std::vector<std::string>* out) {
  for (const CLI::Option* opt : app.get_options()) {
    for (const std::string& n : opt->get_lnames()) out->push_back(n);
  }
  for (const CLI::App* sub : app.get_subcommands()) long_names(*sub, out);
}

inline std::string tool_name(const CLI::App& app) {
  const std::string& n = app.get_name();
  const size_t slash = n.find_last_of('/');
  return slash == std::string::npos ? n : n.substr(slash + 1);
}

}  // namespace cli_detail

// The exit status of an error a tool caught: a std::invalid_argument (a UsageError
// among them) thrown while the tool checked its options, before it read any input, is a
// usage error; anything else is an error of the work (1).
inline int error_status(const std::exception& e, bool checking_options) {
  return dynamic_cast<const UsageError*>(&e) || (checking_options && dynamic_cast<const std::invalid_argument*>(&e))
             ? kExitUsage
             : 1;
}

// "<tool>: <what>" on stderr, with the --help hint after a usage error; returns `status`.
inline int print_error(const std::string& tool, const std::string& what, int status) {
  std::fprintf(stderr, "%s: %s\n%s", tool.c_str(), what.c_str(),
               status == kExitUsage ? "Run with --help for more information.\n" : "");
  return status;
}

// "<tool>: <what>" and the hint on stderr; returns kExitUsage.
inline int usage_error(const CLI::App& app, const std::string& what) {
  return print_error(cli_detail::tool_name(app), what, kExitUsage);
}

// The message of an unexpected argument: an option the tool does not know, with the
// closest one it does, or a word where the tool takes none.
inline std::string unexpected_argument(const CLI::App& app, const std::string& arg) {
  if (arg.size() < 2 || arg[0] != '-') return "'" + arg + "': unexpected argument (options start with --)";
  const std::string name = arg.substr(0, arg.find('='));
  std::vector<std::string> names;
  cli_detail::long_names(app, &names);
  const size_t letters = name.find_first_not_of('-');
  const std::string bare = letters == std::string::npos ? "" : name.substr(letters);
  const std::string near = closest_word(bare, names);
  return name + ": unknown option" + (near.empty() || bare.empty() ? "" : "; did you mean --" + near + "?");
}

// The exit of a CLI11 parse error: --help (and --help-all) print the help on stdout and
// give 0; any other error is a usage error, in the tool's voice. An argument the tool
// does not know is named first, whatever CLI11 found after it ("--triangle t.txt" is an
// unknown option, not a missing --triangles).
inline int parse_error_exit(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
  const std::vector<std::string> extra = app.remaining(true);
  if (!extra.empty()) return usage_error(app, unexpected_argument(app, extra.front()));
  return usage_error(app, e.what());
}

// Parses the command line: -1 when the tool goes on, else its exit status (0 after
// --help, kExitUsage after a usage error). Sets the footer of --help (exit_status_footer)
// unless the tool has set one.
inline int parse_command_line(CLI::App& app, int argc, const char* const* argv) {
  if (app.get_footer().empty()) app.footer(exit_status_footer());
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return parse_error_exit(app, e);
  }
  return -1;
}

}  // namespace fmpp
