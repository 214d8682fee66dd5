#include "sw/report/output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <vector>

#include "common/util/cli_usage.h"
#include "common/util/files.h"
#include "common/util/output_file.h"
#include "common/util/process.h"
#include "common/util/source_tree.h"

#ifndef FMPP_BINARY_DIR
#error "FMPP_BINARY_DIR: the build folder, defined for fmpp_reports (sw/CMakeLists.txt)"
#endif

namespace fmpp::report {

std::string build_dir() { return FMPP_BINARY_DIR; }

std::string fmt(double v, int prec) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, v);
  return buf;
}


std::string today() {
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d", std::localtime(&now));
  return date;
}

std::string machine_description() {
  std::string cpu = "unknown CPU";
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  std::string load;
  std::ifstream l("/proc/loadavg");  // a shared machine's timings depend on what else runs
  double avg = 0;
  if (l >> avg) load = ", load average " + fmt(avg, 1);
  return cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores" + load;
}

void add_output_options(CLI::App* sub, ReportOutput& o) {
  const std::string quick = build_dir() + "/" + o.quick_name;
  o.out_opt = sub->add_option("--out", o.out, "markdown report to write (with --quick: " + quick + ".md)")
                  ->capture_default_str();
  o.img_opt = sub->add_option("--img-dir", o.img_dir, "directory for the PNG plots (with --quick: " + quick + ")")
                  ->capture_default_str();
  o.data_opt = sub->add_option("--data-dir", o.data_dir,
                               "directory for the JSON data of the plots, " + o.data_name + " (with --quick: " + quick + ")")
                   ->capture_default_str();
  sub->add_flag("--no-plots", o.no_plots, "skip running tools/" + o.plot_script);
}

void prepare_outputs(ReportOutput& o) {
  const std::string quick = build_dir() + "/" + o.quick_name;
  if (o.quick && o.out_opt->count() == 0) o.out = quick + ".md";
  if (o.quick && o.img_opt->count() == 0) o.img_dir = quick;
  if (o.quick && o.data_opt->count() == 0) o.data_dir = quick;
  // The options alone: usage errors (exit 2).
  if (o.out == "-") {
    throw UsageError("--out -: the report needs a file name (it is written beside its data and plots)");
  }
  if (o.out.empty()) throw UsageError("--out: empty path");
  if (o.img_dir.empty()) throw UsageError("--img-dir: empty path");
  if (o.data_dir.empty()) throw UsageError("--data-dir: empty path");
  // The report first, so that a bad --out creates nothing.
  const std::filesystem::path md(o.out);
  std::error_code ec;
  if (std::filesystem::is_directory(md, ec)) throw std::invalid_argument("--out " + o.out + ": is a directory");
  if (md.has_parent_path()) std::filesystem::create_directories(md.parent_path());
  check_writable("--out", o.out, false);
  std::filesystem::create_directories(o.img_dir);
  std::filesystem::create_directories(o.data_dir);
  check_writable("--data-dir", o.data_dir + "/" + o.data_name, false);
  check_no_alias({{"--out", o.out}, {"--data-dir", o.data_dir + "/" + o.data_name}}, {});
}

void write_report(const ReportOutput& o, const std::string& markdown, const nlohmann::json& data) {
  std::filesystem::create_directories(o.img_dir);
  std::filesystem::create_directories(o.data_dir);
  const std::filesystem::path md(o.out);
  if (md.has_parent_path()) std::filesystem::create_directories(md.parent_path());
  const std::string data_file = o.data_dir + "/" + o.data_name;
  write_output(data_file, data.dump(1) + "\n");
  write_output(o.out, markdown);
  if (o.no_plots) return;
  // An argument vector, no shell: the paths are passed as they are, whatever they hold.
  run_program({"/usr/bin/python3", source_file("tools/" + o.plot_script), data_file, o.img_dir});
}

}  // namespace fmpp::report
