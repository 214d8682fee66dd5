// Shared by the fmpp-report subcommands: number formatting for the Markdown tables and
// writing a report (Markdown, its JSON data, the plots drawn from that data).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace fmpp::report {

// v with `prec` digits after the point ("%.*f").
std::string fmt(double v, int prec = 0);

// Today's local date, YYYY-MM-DD, for a report's "Generated ... on" line.
std::string today();

// Before the measurements of `fmpp-report paper` or `precision`: settles and checks the
// paths the run will write. A --quick run (a smoke test) given no --out or --img-dir
// writes <quick_name>.md and <quick_name>/ in the current directory instead of the
// committed docs/ files. Creates the directories and checks that the report and
// img_dir/data_name can be written; throws naming the option and path ("--out -" too:
// the report goes beside its data and plots, not to stdout).
void prepare_outputs(bool quick, bool out_given, std::string& md_path, bool img_given, std::string& img_dir,
                     const std::string& quick_name, const std::string& data_name);

// --out and --img-dir of a report subcommand (defaults shown; --quick alternatives
// <quick_name>.md and <quick_name>/ named in the help). Returns the two options, whose
// count() says whether they were given.
struct OutputOptions {
  CLI::Option* out;
  CLI::Option* img_dir;
};
OutputOptions add_output_options(CLI::App* sub, std::string& md_path, std::string& img_dir,
                                 const std::string& quick_name);

// Writes `markdown` to md_path and `data` to img_dir/data_name (creating both
// directories), then, unless `plot_script` is empty, runs
// python3 FMPP_SOURCE_DIR/tools/<plot_script> <data file> <img_dir>.
// Throws std::runtime_error naming the file or command that failed.
void write_report(const std::string& md_path, const std::string& markdown, const std::string& img_dir,
                  const std::string& data_name, const nlohmann::json& data, const std::string& plot_script);

}  // namespace fmpp::report
