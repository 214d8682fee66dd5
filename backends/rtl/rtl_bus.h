// The Verilated FMPP behind the Bus interface: a cycle-driving AXI4-Lite master.
//
// Each built configuration (rtl/fmpp_map.json "configs") is a separate Verilated
// model; make_rtl_bus() picks one by name or by size. The master starts every
// access as soon as the previous one was accepted and holds BREADY/RREADY high,
// which is the timing fmpp::ModelBus reproduces. In stress mode it instead waits
// random idle clocks before each access and drops BREADY/RREADY at random, to
// exercise the protocol; cycle counts then no longer match the model.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fmpp/bus.h"
#include "fmpp/machine.h"
#include "fmpp/model_bus.h"

namespace fmpp::backends {

// The RTL's architectural state, in the golden model's layout.
struct ArchState {
  Config cfg;
  std::vector<uint32_t> words;  // [block * words + word]
  std::vector<uint8_t> flags;   // [block]
  uint32_t mask = 0;
  uint64_t instret = 0;
  uint8_t gap = 0;
  ErrorState error;
  unsigned queue_level = 0;

  uint32_t word(unsigned b, unsigned w) const { return words[size_t{b} * cfg.words + w]; }
  // Same digest as Machine::state_hash().
  uint64_t hash() const;
};

// Reads the golden model's state into the same form.
ArchState model_state(const ModelBus& m);

// Bit planes to words: planes[k] holds bit k of every lane (lane l at bit l), for k below
// nplanes (a multiple of 8, at most 32); out[l] receives lane l's nplanes bits, for all 64
// lanes. The RTL stores its words as planes; the state extractor turns them into words.
void planes_to_words(const uint64_t* planes, unsigned nplanes, uint32_t out[64]);

// Lists up to `max_diffs` differences, one per line ("block 3 word 7: rtl 0x.. model 0x..").
std::string diff_states(const ArchState& rtl, const ArchState& model, unsigned max_diffs = 16);

struct RtlOptions {
  std::string trace_file;      // FST file to write, empty for none
  uint64_t trace_start = 0;    // first cycle to trace
  uint64_t trace_end = ~0ull;  // last cycle to trace
  uint64_t timeout = 1000000;  // clocks an access may wait for READY before failing
  bool stress = false;         // random idle clocks and READY back-pressure
  uint64_t stress_seed = 1;
  // Soak options (tools/soak.sh). random_init != 0: every variable, the words included,
  // powers up with random values from this seed (Verilator randReset(2)); the reset
  // then clears all but the words, which the golden model must be given (preload).
  uint64_t random_init = 0;
  bool max_backpressure = false;  // stress mode: READY held low 8 clocks after every response
  // Coverage builds (cmake -DFMPP_COVERAGE=ON, make coverage): where the Verilator
  // coverage counts go when the bus is destroyed. Refused by a build without coverage.
  std::string coverage_file;
};

class RtlBus : public Bus {
 public:
  ~RtlBus() override = default;
  std::string name() const override { return "rtl"; }

  virtual const Config& config() const = 0;
  // Extracts the full architectural state from the Verilated model.
  virtual ArchState state() const = 0;
  // The slave's ERROR state and CTRL.GAP alone (cheap: checked after every access).
  virtual ErrorState error_state() const = 0;
  virtual uint8_t gap() const = 0;
  // Called after each clock edge at which the array executed a queue entry.
  using ExecHook = std::function<void()>;
  virtual void set_exec_hook(ExecHook h) = 0;
  // Pulls rst_ni low for two clocks between accesses: the queue empties without
  // executing, every register resets, the words keep their values; cycles() restarts.
  virtual void reset() = 0;
  // Clocks the model without any bus access (the array keeps draining its queue).
  virtual void idle(uint64_t clocks) = 0;
  // Assertion failures and timeouts seen so far (empty = none).
  virtual std::string failure() const = 0;
  // For testing the RTL's protocol assertions only: presents a write for one clock and
  // withdraws it whether or not it was accepted (a master must not do that).
  virtual void withdraw_write_for_test(uint32_t addr, uint64_t data) = 0;
};

// The Verilated configurations linked into this binary (generated per binary from
// backends/rtl/rtl_factory.cpp.in by fmpp_rtl_factory() in backends/rtl/CMakeLists.txt), in map order.
std::vector<std::string> rtl_configs();
// The version of the Verilator that built them ("5.006 2023-01-22"; defined beside
// rtl_configs(), so a binary without RTL configurations has none).
std::string verilator_version();
// Builds the configuration `name` (see rtl_configs()). Throws std::invalid_argument
// naming the configurations this binary has.
std::unique_ptr<RtlBus> make_rtl_bus(const std::string& name, const RtlOptions& opt = {});

}  // namespace fmpp::backends
