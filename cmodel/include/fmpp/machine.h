// The FMPP golden model: architectural state and the effect of each instruction.
//
// Bit-exact with the RTL (rtl/fmpp_tile.sv, fmpp_alu_exec.sv). Timing and the bus are
// in ModelBus; this class only knows what one queue entry does. Words are stored
// word-major (all blocks' word w contiguous) and flags one byte per block, so each
// instruction is one branch-free loop over blocks that the compiler vectorizes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fmpp/config.h"
#include "fmpp/isa.h"

namespace fmpp {

// FNV-1a digest of an architectural state visited block by block (its words in order,
// then its flags), then the mask. A layout-independent order: Machine::state_hash and
// the RTL state extractor (tb/) both feed it, so equal states give equal digests.
template <class WordAt, class FlagsAt>
uint64_t state_digest(const Config& cfg, WordAt word, FlagsAt flags, uint32_t mask) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](uint64_t v) {
    for (int k = 0; k < 8; ++k) {
      h ^= (v >> (8 * k)) & 0xFF;
      h *= 1099511628211ull;
    }
  };
  for (unsigned b = 0; b < cfg.blocks; ++b) {
    for (unsigned w = 0; w < cfg.words; ++w) mix(word(b, w));
    mix(flags(b));
  }
  mix(mask);
  return h;
}

class Machine {
 public:
  explicit Machine(const Config& cfg);

  const Config& config() const { return cfg_; }

  // Executes one legal instruction in every block. Precondition: is_legal().
  void execute(uint64_t raw);
  // Window writes (queued host writes). strb4: byte enables of the 32-bit word.
  void write_word(unsigned block, unsigned word, uint32_t data, uint8_t strb4 = 0xF);
  void write_flags(unsigned block, uint8_t flags);
  // The RTL's reset: flags, mask and INSTRET to zero; the words keep their values
  // (memory has no reset).
  void reset();

  uint32_t word(unsigned block, unsigned word) const { return mem_[word * stride_ + block]; }
  uint8_t flags(unsigned block) const { return flags_[block]; }
  bool flag(unsigned block, unsigned f) const { return (flags_[block] >> f) & 1; }
  // Flag f of the 64 blocks of tile t, bit i = block 64t + i.
  uint64_t plane(unsigned f, unsigned tile) const;
  uint32_t mask() const { return mask_; }
  uint64_t instret() const { return instret_; }

  Responders responders() const;
  bool ovf_any() const;

  // state_digest of words, flags and mask: the blocks in index order whatever the
  // storage layout, so the RTL's digest of an equal state is equal (fast lockstep checks).
  uint64_t state_hash() const;

 private:
  const uint32_t* row(unsigned w) const { return mem_.data() + size_t{w} * stride_; }
  uint32_t* row(unsigned w) { return mem_.data() + size_t{w} * stride_; }

  Config cfg_;
  size_t stride_;               // words of one row (blocks, padded)
  std::vector<uint32_t> mem_;   // [word][block]
  std::vector<uint8_t> flags_;  // [block], bit f = flag f
  uint32_t mask_ = 0;
  uint64_t instret_ = 0;
};

}  // namespace fmpp
