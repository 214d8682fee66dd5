// Choosing the machine behind the Bus by name, as every command-line tool does:
//   cmodel    the golden model
//   rtl       the Verilated RTL (a configuration built into this binary)
//   lockstep  the RTL and the golden model together, every access cross-checked
//   systemc   the Verilated RTL behind the SystemC TLM-2.0 platform, in binaries that link
//             the fmpp_backend_systemc object library (only those link SystemC)
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fmpp/model_bus.h"
#include "backends/lockstep.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp {

struct BackendOptions {
  std::string trace_file;  // FST waveform (rtl, lockstep, systemc; cmodel refuses it)
  uint64_t trace_start = 0;  // first clock cycle traced
  uint64_t trace_end = ~0ull;  // last clock cycle traced (start > end is refused)
  std::string lockstep_mode = "fast";  // lockstep: check | fast | off
};

class Backend {
 public:
  Bus& bus() { return *bus_; }
  const std::string& name() const { return name_; }
  const Config& config() const { return cfg_; }
  // The Verilated model behind rtl, lockstep and systemc (nullptr for cmodel).
  backends::RtlBus* rtl_bus() { return rtl_view_; }
  // Lockstep: compares the final state (throws backends::LockstepMismatch). rtl, systemc:
  // throws std::runtime_error if an RTL assertion failed (every access checks it too).
  void finish();

  friend std::unique_ptr<Backend> make_backend(const std::string&, const Config&, const BackendOptions&);

 private:
  std::string name_;
  Config cfg_;
  std::unique_ptr<ModelBus> model_;
  std::unique_ptr<backends::RtlBus> rtl_;
  std::unique_ptr<backends::Lockstep> lock_;
  std::unique_ptr<Bus> owned_;  // other wrappers (SystemC)
  std::unique_ptr<Bus> checked_;  // rtl, systemc: the bus that stops at an RTL assertion failure
  backends::RtlBus* rtl_view_ = nullptr;  // the Verilated model behind any of them
  Bus* bus_ = nullptr;
};

// Names accepted by make_backend in this binary.
std::vector<std::string> backend_names();

// The systemc backend's maker: wraps a Verilated model in the SystemC platform. Set once,
// before main, by the fmpp_backend_systemc object library (backends/systemc/register.cpp).
using SystemcWrapper = std::function<std::unique_ptr<Bus>(std::unique_ptr<backends::RtlBus>)>;
bool register_systemc_backend(SystemcWrapper wrap);

// Builds the named backend with exactly `cfg` blocks and words. For rtl and lockstep the
// configuration must be one of the built ones; the error lists them.
std::unique_ptr<Backend> make_backend(const std::string& name, const Config& cfg, const BackendOptions& opt = {});

}  // namespace fmpp
