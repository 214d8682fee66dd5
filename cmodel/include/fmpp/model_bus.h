// The golden model behind the Bus interface: address decode, access rules, the
// ERROR/CTRL registers, and the instruction queue with the RTL's exact timing.
//
// Timing contract (docs/generated/memory-map.md, "Ordering and timing"), clock by clock:
// at each rising edge the entry at the end of the array's pipeline executes (it
// retires), the pipeline advances, the array pops the queue head into the pipeline
// if there is one and its GAP counter is zero, then the bus may push. An entry popped
// at one edge retires kPipeLatency edges later (rtl/fmpp_array.sv: decode, operand
// read, execute; its forwarding makes the order of effects that of the entries). A
// write to QUEUE, FLAGS or WORDS is accepted at the first edge with room in the queue
// (and queued if legal); every other access at the first edge with the queue empty and
// the pipeline drained for a whole clock (rtl/fmpp_top.sv: a clock idle after the last
// entry retired, so that a read's path across the die has two clocks), a read of RESP or
// STATUS map::kRespLatency edges after that (the responder tree's registers). A FLAGOP with FLAG_ANY holds the pipeline map::kAnyLatency
// edges before it executes (the any tree's registers): no entry executes, advances or is
// popped meanwhile, and the GAP counter counts on. An access with an
// error, or any write to ERROR, changes the ERROR register one edge after its own
// (rtl/fmpp_err_reg.sv registers the event first), and a read waits for that edge:
// a read right after such an access is accepted one clock later. cycles() counts
// edges since reset, as the RTL's CYCLES does, for a bus master that holds
// BREADY/RREADY high and starts each access as soon as the previous one is accepted
// (backends/rtl/rtl_bus.h drives the RTL that way).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fmpp/bus.h"
#include "fmpp/machine.h"

namespace fmpp {

// One queued bus write (the RTL's qentry_t).
struct QueueEntry {
  enum class Kind : uint8_t { kInstr = 0, kWord = 1, kFlags = 2 };
  Kind kind = Kind::kInstr;
  uint32_t block = 0;
  uint8_t word = 0;
  uint8_t strb = 0;  // byte enables of a word write
  uint64_t data = 0;
};

// Where an address points (the RTL's fmpp_addr_decode).
struct Decoded {
  enum class Region : uint8_t { kNone, kReg, kPlane, kFlags, kWord };
  Region region = Region::kNone;
  bool aligned = true;
  uint32_t reg = 0;    // register offset
  uint32_t block = 0;  // block (FLAGS, WORDS) or tile (PLANES)
  uint32_t word = 0;
  uint32_t flag = 0;
};
Decoded decode_address(const Config& cfg, uint32_t addr);

struct ErrorState {
  bool sticky = false;
  map::Err cause = map::Err::kNone;
  uint16_t count = 0;
  uint32_t addr = 0;
  uint64_t reg() const;  // the ERROR register value
  void record(map::Err c, uint32_t a);
  bool operator==(const ErrorState& o) const;
};

class ModelBus : public Bus {
 public:
  // Clock edges from an entry's pop to the edge at which it executes (the RTL array's
  // stages after the queue read: operand read, execute and write back).
  static constexpr unsigned kPipeLatency = 2;

  explicit ModelBus(const Config& cfg);

  Resp write(uint32_t addr, uint64_t data, uint8_t strb = 0xFF) override;
  Resp read(uint32_t addr, uint64_t* data) override;
  uint64_t cycles() const override { return cycle_; }
  std::string name() const override { return "cmodel"; }

  const Machine& machine() const { return m_; }
  // Sets one word before the run, as the RTL's memory powered up (soak with random
  // initial state). Not a bus access: no clock, no queue.
  void preload_word(unsigned block, unsigned word, uint32_t value) { m_.write_word(block, word, value); }
  // The RTL's reset (rst_ni low): the queue and the pipeline are emptied without executing, CYCLES,
  // CTRL and ERROR restart from zero, the machine resets (Machine::reset: words kept).
  void reset();
  const Config& config() const { return m_.config(); }
  const ErrorState& error() const { return err_; }
  uint8_t gap() const { return gap_; }
  size_t queue_level() const { return count_; }
  // Entries popped from the queue that have not executed yet (0 .. kPipeLatency).
  size_t in_flight() const { return pipe_count_; }

  // Called after every queue entry executes, at the edge it retires (lockstep checking hooks in here).
  using ExecHook = std::function<void(const QueueEntry&)>;
  void set_exec_hook(ExecHook h) { exec_hook_ = std::move(h); }

  // Checks a write without performing it: the error cause it would raise (kNone
  // if legal) and, for a legal push, the queue entry it would create.
  map::Err check_write(uint32_t addr, uint64_t data, uint8_t strb, QueueEntry* push, bool* is_push) const;
  // Whether a write goes to a queued target (QUEUE, FLAGS or WORDS, aligned): such a write
  // is accepted at the first edge with room in the queue, legal or not.
  bool queued_target(uint32_t addr) const;

 private:
  void tick(const QueueEntry* push);  // one rising clock edge
  void push_entry(const QueueEntry* push);  // the bus's push at an edge (none if null)
  static bool waits_for_any(const QueueEntry& e);  // FLAGOP with FLAG_ANY
  void execute(const QueueEntry& e);
  void drain();
  void settle();  // drain, then the clock idle that an access waiting for the array needs
  uint64_t register_value(uint32_t reg) const;

  Machine m_;
  std::vector<QueueEntry> ring_;
  size_t head_ = 0, count_ = 0;
  // The pipeline after the queue: pipe_[0] holds the entry popped at the last edge,
  // pipe_[kPipeLatency - 1] the one that executes at the next; pipe_valid_ marks the
  // stages that hold an entry and pipe_count_ counts them.
  QueueEntry pipe_[kPipeLatency];
  bool pipe_valid_[kPipeLatency] = {};
  size_t pipe_count_ = 0;
  uint64_t cycle_ = 0;
  uint8_t gap_ = 0;       // CTRL.GAP
  uint8_t gap_cnt_ = 0;   // idle clocks left before the next pop
  unsigned any_wait_ = 0;  // clocks the FLAGOP with FLAG_ANY in stage 3 has waited
  bool was_busy_ = false;  // the pipeline held an entry in the clock before the last edge
  // The last edge accepted an access that changes ERROR (an error, or a write to ERROR):
  // the RTL applies it at the next edge, and a read waits for that edge. err_ holds the
  // value as applied (what a read shows).
  bool err_event_ = false;
  ErrorState err_;
  ExecHook exec_hook_;
};

}  // namespace fmpp
