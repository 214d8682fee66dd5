#include "sw/report/output.h"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "sw/tools/cli_options.h"

#ifndef FMPP_SOURCE_DIR
#define FMPP_SOURCE_DIR "."
#endif

namespace fmpp::report {

std::string fmt(double v, int prec) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, v);
  return buf;
}

namespace {

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot write");
  f << text;
  if (!f.flush()) throw std::runtime_error(path + ": write failed");
}

}  // namespace

std::string today() {
  char date[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d", std::localtime(&now));
  return date;
}

OutputOptions add_output_options(CLI::App* sub, std::string& md_path, std::string& img_dir,
                                 const std::string& quick_name) {
  OutputOptions o;
  o.out = sub->add_option("--out", md_path, "markdown report to write (with --quick: " + quick_name + ".md)")
              ->capture_default_str();
  o.img_dir = sub->add_option("--img-dir", img_dir,
                              "directory for the PNG plots and their data (with --quick: " + quick_name + ")")
                  ->capture_default_str();
  return o;
}

void prepare_outputs(bool quick, bool out_given, std::string& md_path, bool img_given, std::string& img_dir,
                     const std::string& quick_name, const std::string& data_name) {
  if (quick && !out_given) md_path = quick_name + ".md";
  if (quick && !img_given) img_dir = quick_name;
  if (md_path == "-") {
    throw std::invalid_argument("--out -: the report needs a file name (it is written beside its data and plots)");
  }
  if (md_path.empty()) throw std::invalid_argument("--out: empty path");
  if (img_dir.empty()) throw std::invalid_argument("--img-dir: empty path");
  // The report first, so that a bad --out creates nothing.
  const std::filesystem::path md(md_path);
  std::error_code ec;
  if (std::filesystem::is_directory(md, ec)) throw std::invalid_argument("--out " + md_path + ": is a directory");
  if (md.has_parent_path()) std::filesystem::create_directories(md.parent_path());
  check_writable("--out", md_path, false);
  std::filesystem::create_directories(img_dir);
  check_writable("--img-dir", img_dir + "/" + data_name, false);
}

void write_report(const std::string& md_path, const std::string& markdown, const std::string& img_dir,
                  const std::string& data_name, const nlohmann::json& data, const std::string& plot_script) {
  std::filesystem::create_directories(img_dir);
  const std::filesystem::path md(md_path);
  if (md.has_parent_path()) std::filesystem::create_directories(md.parent_path());
  const std::string data_file = img_dir + "/" + data_name;
  write_file(data_file, data.dump(1) + "\n");
  write_file(md_path, markdown);
  if (plot_script.empty()) return;
  const std::string cmd =
      "/usr/bin/python3 " FMPP_SOURCE_DIR "/tools/" + plot_script + " '" + data_file + "' '" + img_dir + "'";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("plotting failed: " + cmd);
}

}  // namespace fmpp::report
