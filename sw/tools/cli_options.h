// Command-line options and checks the tools share (fmpp-intersect, fmpp-render, and
// fmpp-sim and fmpp-report for the option checks).
#pragma once

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/fmpp/backend.h"
#include "sw/isect/output_file.h"

namespace fmpp {

// A floating-point option: a finite number in [lo, hi]. (CLI::Range alone lets "nan"
// through, since every comparison with NaN is false.)
inline CLI::Validator finite_range(double lo, double hi) {
  std::ostringstream desc;
  desc << "FLOAT in [" << lo << " - " << hi << "]";
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v)) return "'" + s + "' is not a number";
        if (!std::isfinite(v)) return "value " + s + " is not a finite number";
        if (v < lo || v > hi) {
          std::ostringstream o;
          o << "value " << s << " not in [" << lo << ", " << hi << "]";
          return o.str();
        }
        return "";
      },
      desc.str());
}

// A whole-number option in [lo, hi]: "abc" is "not a whole number", not "not in range"
// (CLI::Range alone says the latter for both).
inline CLI::Validator int_range(long long lo, long long hi) {
  return CLI::Validator(
      [lo, hi](std::string& s) -> std::string {
        long long v = 0;
        if (!CLI::detail::lexical_cast(s, v)) return "'" + s + "' is not a whole number";
        if (v < lo || v > hi) return "value " + s + " not in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        return "";
      },
      "INT in [" + std::to_string(lo) + " - " + std::to_string(hi) + "]");
}

// An unsigned or "no sign" option: CLI11 reads "-1" into a uint64_t as 2^64 - 1 (strtoull
// negates), so a leading minus is refused here.
inline CLI::Validator non_negative() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        const size_t i = s.find_first_not_of(" \t");
        if (i != std::string::npos && s[i] == '-') return "value " + s + " is negative";
        return "";
      },
      "");
}

// Words per block: the RTL holds an even number (fmpp::Config), 2..64.
inline CLI::Validator even_words() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        unsigned v = 0;
        if (!CLI::detail::lexical_cast(s, v)) return "'" + s + "' is not a whole number";
        if (v < 2 || v > 64 || v % 2 != 0) return "value " + s + " is not an even number in [2, 64]";
        return "";
      },
      "EVEN in [2 - 64]");
}

// --backend: "reference" (the host's double-precision reference, no machine) and the
// names make_backend accepts.
inline std::vector<std::string> tool_backends() {
  std::vector<std::string> names = {"reference"};
  for (const auto& n : backend_names()) names.push_back(n);
  return names;
}
inline std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

// --trace, --trace-start, --trace-end: an FST waveform of the RTL behind the backend.
// A window without --trace is refused (it would do nothing).
inline void add_trace_options(CLI::App& app, BackendOptions& bo) {
  CLI::Option* trace = app.add_option("--trace", bo.trace_file, "FST waveform of the RTL (rtl, lockstep, systemc)");
  app.add_option("--trace-start", bo.trace_start, "first clock cycle to trace")
      ->check(non_negative())
      ->needs(trace);
  app.add_option("--trace-end", bo.trace_end, "last clock cycle to trace")
      ->check(non_negative())
      ->needs(trace);
}

// A trace window that ends before it starts is an error whatever the backend (the RTL
// harness refuses it too, with the same message).
inline void check_trace_window(uint64_t start, uint64_t end) {
  if (start > end) {
    throw std::invalid_argument("trace window: first cycle " + std::to_string(start) + " is after the last cycle " +
                                std::to_string(end));
  }
}

// A waveform goes to a regular file: the FST writer does not report write errors, so a
// device (/dev/full, /dev/null) or a pipe would lose it without a word. Refused before
// any work, naming the option.
inline void check_trace_file(const std::string& path, const char* option = "--trace") {
  if (path.empty()) return;
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st) || std::filesystem::is_regular_file(st)) return;
  throw std::invalid_argument(std::string(option) + " " + path + ": not a regular file; a waveform needs a file name");
}

// The reference backend runs no hardware: a trace asked of it is refused, not ignored.
// (make_backend refuses one for cmodel.)
inline void check_trace_options(const std::string& backend, const BackendOptions& bo) {
  check_trace_window(bo.trace_start, bo.trace_end);
  check_trace_file(bo.trace_file);
  if (backend == "reference" && !bo.trace_file.empty()) {
    throw std::invalid_argument("backend 'reference' has no waveform: a trace needs rtl, lockstep or systemc");
  }
}

// Checks before any work that `path` (the value of `option`) can be written: not a
// directory, its directory exists, permission. "-" (stdout) passes when `stdout_ok`.
// An existing file is not truncated here, and one this creates is removed again.
inline void check_writable(const std::string& option, const std::string& path, bool stdout_ok = true) {
  if (path == "-") {
    if (stdout_ok) return;
    throw std::invalid_argument(option + " -: this output needs a file name");
  }
  if (path.empty()) throw std::invalid_argument(option + ": empty path");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::invalid_argument(option + " " + path + ": is a directory");
  const bool existed = std::filesystem::exists(path, ec);
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) {
    throw std::runtime_error(option + " " + path + ": cannot write" +
                             (errno ? std::string(" (") + std::strerror(errno) + ")" : std::string()));
  }
  std::fclose(f);
  if (!existed) std::filesystem::remove(path, ec);
}

// Writes `text` to `path`, or to stdout for "-": checked, and atomic for a file
// (fmpp::write_output).
inline void write_text(const std::string& path, const std::string& text) { write_output(path, text); }

}  // namespace fmpp
