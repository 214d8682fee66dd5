// Shared by the fmpp-report subcommands: number formatting for the Markdown tables and
// writing a report (Markdown, its JSON data, the plots drawn from that data).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace fmpp::report {

// v with `prec` digits after the point ("%.*f").
std::string fmt(double v, int prec = 0);

// Today's local date, YYYY-MM-DD, for a report's "Generated ... on" line.
std::string today();

// The machine a report was measured on, for the same line: the CPU model from
// /proc/cpuinfo ("unknown CPU" where there is none), the number of cores and the
// 1-minute load average as the report is written (where /proc/loadavg exists).
std::string machine_description();

// The build directory the tool was built in (FMPP_BINARY_DIR): where a report goes
// unless told otherwise. Never the source tree: only `make docs-update` copies the
// generated documents over the committed ones (tools/docs.py).
std::string build_dir();

// Where a report subcommand (`fmpp-report paper`, `precision`) writes: its Markdown
// (out), its JSON data (data_dir/data_name) and the plots tools/<plot_script> draws
// from that data (img_dir). By default the build directory's copy of the docs/ layout:
// BUILD/docs/generated/<doc_name>, BUILD/docs/img, BUILD/docs/data (what `make docs`
// makes). A --quick run (a smoke test, the subcommand's own flag) writes
// BUILD/<quick_name>.md and BUILD/<quick_name>/ instead. Whatever the current
// directory: a default never depends on it.
struct ReportOutput {
  ReportOutput(std::string doc, std::string quick, std::string data, std::string plot)
      : doc_name(std::move(doc)), quick_name(std::move(quick)), data_name(std::move(data)), plot_script(std::move(plot)) {
    out = build_dir() + "/docs/generated/" + doc_name;
    img_dir = build_dir() + "/docs/img";
    data_dir = build_dir() + "/docs/data";
  }
  std::string out, img_dir, data_dir;
  bool quick = false;
  bool no_plots = false;
  std::string doc_name, quick_name, data_name, plot_script;
  CLI::Option* out_opt = nullptr;  // set by add_output_options
  CLI::Option* img_opt = nullptr;
  CLI::Option* data_opt = nullptr;
};

// Declares --out, --img-dir, --data-dir (defaults shown) and --no-plots on the subcommand.
void add_output_options(CLI::App* sub, ReportOutput& o);

// Before the measurements: settles the paths (the --quick defaults) and checks them.
// Creates the directories and checks that the report, img_dir and data_dir/data_name
// can be written; throws naming the option and path ("--out -" too: the report goes beside
// its data and plots, not to stdout).
void prepare_outputs(ReportOutput& o);

// Writes `markdown` to o.out and `data` to o.data_dir/o.data_name (creating the
// directories), then, unless --no-plots, runs
// python3 FMPP_SOURCE_DIR/tools/<plot_script> <data file> <img_dir> (fmpp::run_program,
// common/util/process.h: no shell).
// Throws std::runtime_error naming the file or command that failed.
void write_report(const ReportOutput& o, const std::string& markdown, const nlohmann::json& data);

}  // namespace fmpp::report
