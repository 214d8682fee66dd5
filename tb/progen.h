// Seeded constrained-random FMPP programs for the RTL regression.
//
// Each step() performs one bus access on any Bus (normally the lockstep checker):
// a legal instruction push, a window write, a read of a word, flags, a flag
// plane or a register, a change of CTRL.GAP (which makes the queue fill and
// back-pressure the bus), an ERROR clear, or a bad access of every kind the
// slave must reject. Operands are biased towards the edges: block 0 and the last
// block, word 0 and the last word, masks 0 and all-ones, values that carry or
// overflow out of bit 31, and selections of no, one and all blocks.
// The same seed gives the same access sequence.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <string>

#include "fmpp/bus.h"
#include "fmpp/machine.h"

namespace fmpp::tb {

struct GenStats {
  uint64_t accesses = 0;
  uint64_t instructions = 0;  // legal instruction pushes
  uint64_t window_writes = 0;
  uint64_t reads = 0;
  uint64_t bad = 0;           // accesses that must answer SLVERR
  std::array<uint64_t, map::kNumOpcodes> per_op{};
  std::array<uint64_t, map::kNumErrs> per_error{};  // by map::Err code
  // Names what was never exercised (an opcode or an error cause), empty if all were.
  std::string missing() const;
};

class ProgramGenerator {
 public:
  ProgramGenerator(const Config& cfg, uint64_t seed);

  // One random access. Throws std::runtime_error if the bus answers a bad access
  // with OKAY or a good one with SLVERR (the lockstep catches disagreements too).
  void step(Bus& bus);
  const GenStats& stats() const { return stats_; }

  // Bad-access storms (soak): in every 1000 accesses, 60 in a row are bad accesses.
  void set_storms(bool on) { storms_ = on; }

  // A random legal instruction for this configuration (also used by unit tests).
  uint64_t random_instruction();

 private:
  uint32_t edge_value();
  unsigned word_index();
  unsigned block_index();
  unsigned flag_index();
  // SHR_A of ADD, SUB and RSHIFT: 0 half the time (the plain operation), else the edges
  // 1 and 31 or any amount between.
  unsigned shift_amount();
  // A random code among those a sub-field's legal mask (map::k<Sub>Legal) defines.
  unsigned legal_code(uint32_t legal);
  void push_instruction(Bus& bus, uint64_t raw);
  // One access the bus must refuse (SLVERR), counted by its ERROR cause: of kind 0 .. 5
  // on the registers and the queue (bad_register_access), 6 .. 12 on the windows and the
  // address space (bad_window_access); each returns the cause and sets the address.
  void bad_access(Bus& bus);
  map::Err bad_register_access(unsigned kind, Bus& bus, uint32_t* addr, Resp* r);
  map::Err bad_window_access(unsigned kind, Bus& bus, uint32_t* addr, Resp* r);
  void expect(Resp got, Resp want, const char* what, uint32_t addr);
  uint32_t word_addr(unsigned block, unsigned word) const;

  Config cfg_;
  std::mt19937_64 rng_;
  GenStats stats_;
  unsigned burst_ = 0;  // instructions left in a back-to-back burst
  bool storms_ = false;
};

}  // namespace fmpp::tb
