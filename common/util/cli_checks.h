// Generic checks of command-line values, shared by every tool (fmpp-sim, fmpp-intersect,
// fmpp-render, fmpp-report): a leaf header that depends on CLI11 and the standard
// library only, so any layer may use it.
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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

// The strings of `v` separated by `sep`.
inline std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
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

}  // namespace fmpp
