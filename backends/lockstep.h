// Lockstep cross-check: every bus access goes to the Verilated RTL and to the
// golden model; responses, read data and clock counts must agree, and so must
// the whole architectural state:
//   - checking mode: after every queue entry either side executes (words, flags,
//     mask, INSTRET, CTRL, ERROR, queue level);
//   - fast mode: by hash every `hash_interval` entries, at access boundaries;
//   - off: bus responses, read data and clocks only.
// The first mismatch stops the run: the access throws LockstepMismatch whose
// message names the entry index, the entry (disassembled), the clock edge at which
// it executed, the clock at which the difference was seen and the differing state.
#pragma once

#include <cstdint>
#include <deque>
#include <stdexcept>
#include <string>

#include "fmpp/model_bus.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp::backends {

class LockstepMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LockstepOptions {
  enum class Mode { kCheck, kFast, kOff };
  Mode mode = Mode::kCheck;
  uint64_t hash_interval = 4096;  // fast mode
  bool compare_cycles = true;     // false when the RTL master runs in stress mode
};

// Parses "check", "fast" or "off". Throws std::invalid_argument.
LockstepOptions::Mode parse_lockstep_mode(const std::string& s);

// One-line description of a queue entry ("instr ADD w3 = ...", "word block 5 word 2 = 0x... strb 0xf").
std::string describe(const QueueEntry& e);

class Lockstep : public Bus {
 public:
  Lockstep(RtlBus& rtl, ModelBus& model, const LockstepOptions& opt);

  Resp write(uint32_t addr, uint64_t data, uint8_t strb = 0xFF) override;
  Resp read(uint32_t addr, uint64_t* data) override;
  uint64_t cycles() const override { return rtl_.cycles(); }
  std::string name() const override { return "lockstep"; }

  uint64_t entries() const { return model_entries_; }   // queue entries executed (model side)
  // Clock edge (cycles since reset, 1 = the first edge) at which the model executed
  // the last queue entry: where a mismatch report's entry shows up in a waveform.
  uint64_t last_entry_cycle() const { return last_entry_cycle_; }
  uint64_t state_checks() const { return state_checks_; }
  // Compares the full state now (after draining both queues with a read of ID).
  void final_check();
  // Resets both sides between accesses (RtlBus::reset, ModelBus::reset) and compares
  // the full state after it. With compare_cycles off (stress mode) the two sides are at
  // different clocks, so both queues are drained first (a read of ID).
  void reset();
  uint64_t resets() const { return resets_; }

 private:
  void after_access(const char* what, uint32_t addr);
  void check_hash(const char* where);
  [[noreturn]] void mismatch(const std::string& what);

  RtlBus& rtl_;
  ModelBus& model_;
  LockstepOptions opt_;
  std::deque<ArchState> rtl_snapshots_;  // checking mode: RTL state after each entry
  uint64_t rtl_entries_ = 0;
  uint64_t model_entries_ = 0;
  uint64_t last_hash_entries_ = 0;
  uint64_t state_checks_ = 0;
  QueueEntry last_entry_;
  uint64_t last_entry_cycle_ = 0;
  bool in_read_ = false;
  uint64_t resets_ = 0;
};

}  // namespace fmpp::backends
