// Command-line options the tools share that know the backends (fmpp-intersect,
// fmpp-render, fmpp-report). The generic checks are in common/util/cli_checks.h and the
// output-file helpers in common/util/files.h.
#pragma once

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/util/cli_checks.h"
#include "common/util/files.h"
#include "common/util/source_tree.h"
#include "backends/backend.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp {

// --bits: the multiplier width n, one range in every tool (fmpp-render, fmpp-intersect,
// fmpp-report paper): what the kernels accept (sw/isect/kernels.cpp, sw/fmpp/program.cpp).
inline constexpr unsigned kMinBits = 2, kMaxBits = 32;
inline CLI::Validator bits_range() { return int_range(kMinBits, kMaxBits); }

// --config NAME beside --blocks and --words: one or the other, never both (a named
// configuration fixes both sizes). Declared on the options, so CLI11 refuses the
// combination while parsing; the name itself is checked here, before any work.
inline void exclude_config_sizes(CLI::Option* config, CLI::Option* blocks, CLI::Option* words) {
  config->excludes(blocks)->excludes(words);
}
inline void check_config_name(const std::string& backend, const std::string& config) {
  if (config.empty()) return;
  (void)named_config(config);  // throws naming the known ones
  if (backend == "cmodel" || backend == "reference") return;
  for (const std::string& name : backends::rtl_configs()) {
    if (name == config) return;
  }
  throw std::invalid_argument("--config " + config + ": no Verilated FMPP of that configuration is built (built: " +
                              join(backends::rtl_configs(), ", ") + "); use --backend cmodel for any size");
}

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

// The reference backend and the golden model run no RTL: a trace asked of them is
// refused, not ignored, and before any work (make_backend would refuse it for cmodel
// too, but only once the machine is built, after the precision plan).
inline void check_trace_options(const std::string& backend, const BackendOptions& bo) {
  check_trace_window(bo.trace_start, bo.trace_end);
  check_trace_file(bo.trace_file);
  if ((backend == "reference" || backend == "cmodel") && !bo.trace_file.empty()) {
    throw std::invalid_argument("backend '" + backend + "' has no waveform: a trace needs rtl, lockstep or systemc");
  }
}

}  // namespace fmpp
