// fmpp_instr_check alone against the golden model's legality check (fmpp::is_legal):
// structured words (every opcode with each field set to zero, to its largest legal
// value, to the first illegal value and to all ones, every sub-field code) and random
// words, both fully random and built from legal parts, for 10 and 64 words per block.
#include <gtest/gtest.h>
#include <verilated.h>

#include <random>
#include <vector>

#include "Vunit_check10.h"
#include "Vunit_check64.h"
#include "fmpp/isa.h"
#include "fmpp/map.h"

namespace {

struct Field {
  unsigned lsb, width;
};
// OP, F, D, A, B, X, IMM in the map's order (fmpp_map.json "fields").
const Field kFields[] = {{59, 5}, {56, 3}, {50, 6}, {44, 6}, {38, 6}, {32, 6}, {0, 32}};

uint64_t with(uint64_t raw, const Field& f, uint64_t v) {
  const uint64_t m = ((f.width == 64 ? 0 : (uint64_t{1} << f.width)) - 1) << f.lsb;
  return (raw & ~m) | ((v << f.lsb) & m);
}

std::vector<uint64_t> structured(unsigned words) {
  std::vector<uint64_t> out;
  for (uint64_t op = 0; op < 32; ++op) {
    const uint64_t base = op << 59;
    out.push_back(base);
    for (unsigned fi = 1; fi < 7; ++fi) {
      const Field& f = kFields[fi];
      const uint64_t top = (uint64_t{1} << f.width) - 1;
      for (uint64_t v : {uint64_t{1}, uint64_t{words - 1}, uint64_t{words}, top, top >> 1}) {
        out.push_back(with(base, f, v));
      }
    }
    // Every X code (sub-fields of REF, FUNC, FLAGOP) and every IMM bit alone.
    for (uint64_t x = 0; x < 64; ++x) {
      out.push_back(with(base, kFields[5], x));
      out.push_back(with(with(base, kFields[5], x), kFields[3], 1));
    }
    for (unsigned k = 0; k < 32; ++k) out.push_back(with(base, kFields[6], uint64_t{1} << k));
  }
  return out;
}

template <class V>
void check(unsigned words) {
  VerilatedContext ctx;
  V top(&ctx, "TOP");
  unsigned legal = 0, illegal = 0;
  auto one = [&](uint64_t raw) {
    top.instr_i = raw;
    top.eval();
    const bool want = fmpp::is_legal(raw, words);
    ASSERT_EQ(top.legal_o != 0, want) << "instruction 0x" << std::hex << raw << " (" << fmpp::disasm(raw)
                                      << ") with " << std::dec << words << " words";
    (want ? legal : illegal)++;
  };
  for (const uint64_t raw : structured(words)) one(raw);
  std::mt19937_64 rng(words);
  for (int i = 0; i < 300000; ++i) {
    uint64_t raw = rng();
    if (i % 2) {
      // Mostly-legal words: a real opcode, small fields, each field zeroed at random.
      raw = with(raw, kFields[0], rng() % fmpp::map::kNumOpcodes);
      for (unsigned fi = 2; fi < 5; ++fi) raw = with(raw, kFields[fi], rng() % (words + 1));
      for (unsigned fi = 1; fi < 7; ++fi) {
        if (rng() % 2) raw = with(raw, kFields[fi], 0);
      }
      if (rng() % 2) raw = with(raw, kFields[6], rng() & 0x1F1F);
      if (rng() % 2) raw = with(raw, kFields[5], rng() & 0x3F);
    }
    one(raw);
  }
  EXPECT_GT(legal, 5000u);
  EXPECT_GT(illegal, 50000u);
}

}  // namespace

TEST(RtlUnitInstrCheck, AgreesWithTheModelForTenWords) { check<Vunit_check10>(10); }
TEST(RtlUnitInstrCheck, AgreesWithTheModelForSixtyFourWords) { check<Vunit_check64>(64); }
