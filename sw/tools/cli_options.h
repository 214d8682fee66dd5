// Command-line options the tools share that know the backends (fmpp-intersect,
// fmpp-render, fmpp-report). The generic checks are in sw/util/cli_checks.h and the
// output-file helpers in sw/util/files.h.
#pragma once

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "sw/util/cli_checks.h"
#include "sw/util/files.h"
#include "tb/backend.h"

namespace fmpp {

// --backend: "reference" (the host's double-precision reference, no machine) and the
// names make_backend accepts.
inline std::vector<std::string> tool_backends() {
  std::vector<std::string> names = {"reference"};
  for (const auto& n : backend_names()) names.push_back(n);
  return names;
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

// The reference backend runs no hardware: a trace asked of it is refused, not ignored.
// (make_backend refuses one for cmodel.)
inline void check_trace_options(const std::string& backend, const BackendOptions& bo) {
  check_trace_window(bo.trace_start, bo.trace_end);
  check_trace_file(bo.trace_file);
  if (backend == "reference" && !bo.trace_file.empty()) {
    throw std::invalid_argument("backend 'reference' has no waveform: a trace needs rtl, lockstep or systemc");
  }
}

}  // namespace fmpp
