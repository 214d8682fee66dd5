// Command-line options the host tools share (fmpp-intersect, fmpp-render).
#pragma once

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>

#include "sw/fmpp/backend.h"

namespace fmpp {

// --trace, --trace-start, --trace-end: an FST waveform of the RTL behind the backend.
inline void add_trace_options(CLI::App& app, BackendOptions& bo) {
  app.add_option("--trace", bo.trace_file, "FST waveform of the RTL (rtl, lockstep, systemc)");
  app.add_option("--trace-start", bo.trace_start, "first clock cycle to trace");
  app.add_option("--trace-end", bo.trace_end, "last clock cycle to trace");
}

// The reference backend runs no hardware: a trace asked of it is refused, not ignored.
// (make_backend refuses one for cmodel.)
inline void check_trace_backend(const std::string& backend, const BackendOptions& bo) {
  if (backend == "reference" && !bo.trace_file.empty()) {
    throw std::invalid_argument("backend 'reference' has no waveform: a trace needs rtl, lockstep or systemc");
  }
}

}  // namespace fmpp
