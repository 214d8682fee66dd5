// fmpp_addr_decode alone against the golden model's decoder (fmpp::decode_address):
// every register offset, the edges of every window and random addresses, on a
// configuration with a partial tile and a non-power-of-two word count and on a full tile.
#include <gtest/gtest.h>
#include <verilated.h>

#include <random>
#include <vector>

#include "Vunit_decode_odd.h"
#include "Vunit_decode_small.h"
#include "fmpp/map.h"
#include "fmpp/model_bus.h"

namespace {

using fmpp::Decoded;

// Addresses worth checking: around every window and register edge, and random ones.
std::vector<uint32_t> addresses(const fmpp::Config& cfg) {
  std::vector<uint32_t> a;
  for (uint32_t r = 0; r < 0x1010; r += 4) a.push_back(r);
  const uint32_t bases[] = {fmpp::map::kWinPlanesBase, fmpp::map::kWinFlagsBase, fmpp::map::kWinWordsBase};
  const uint32_t sizes[] = {fmpp::map::kWinPlanesSize, fmpp::map::kWinFlagsSize, fmpp::map::kWinWordsSize};
  for (int w = 0; w < 3; ++w) {
    for (int64_t d = -64; d < 4096; d += 4) a.push_back(static_cast<uint32_t>(bases[w] + d));
    for (int64_t d = -64; d < 64; d += 4) a.push_back(static_cast<uint32_t>(bases[w] + sizes[w] + d));
  }
  // The last block and word of the WORDS window, and just past them.
  const uint32_t stride = 1u << cfg.word_shift();
  for (uint32_t b = cfg.blocks - 2; b <= cfg.blocks; ++b) {
    for (uint32_t w = 0; w < stride / 8 + 1; ++w) a.push_back(fmpp::map::kWinWordsBase + b * stride + 8 * w);
  }
  std::mt19937 rng(11);
  for (int i = 0; i < 200000; ++i) {
    const uint32_t r = static_cast<uint32_t>(rng());
    a.push_back(i % 2 ? r : (r & 0x0FFFFFF8u));
    // Inside each window, up to twice the mapped size (mapped and unmapped slots).
    a.push_back(fmpp::map::kWinFlagsBase + r % (16 * cfg.blocks));
    a.push_back(fmpp::map::kWinWordsBase + r % (2 * cfg.blocks * stride));
    a.push_back(fmpp::map::kWinPlanesBase + r % fmpp::map::kWinPlanesSize);
  }
  return a;
}

template <class V>
void check_against_model(const fmpp::Config& cfg) {
  VerilatedContext ctx;
  V top(&ctx, "TOP");
  unsigned mapped = 0;
  for (const uint32_t addr : addresses(cfg)) {
    top.addr_i = addr;
    top.eval();
    const Decoded m = fmpp::decode_address(cfg, addr);
    SCOPED_TRACE(::testing::Message() << cfg.str() << " address 0x" << std::hex << addr);
    ASSERT_EQ(top.aligned_o != 0, m.aligned);
    ASSERT_EQ(top.is_reg_o != 0, m.region == Decoded::Region::kReg);
    ASSERT_EQ(top.is_plane_o != 0, m.region == Decoded::Region::kPlane);
    ASSERT_EQ(top.is_flags_o != 0, m.region == Decoded::Region::kFlags);
    ASSERT_EQ(top.is_word_o != 0, m.region == Decoded::Region::kWord);
    switch (m.region) {
      case Decoded::Region::kReg:
        ASSERT_EQ(top.reg_o, m.reg);
        break;
      case Decoded::Region::kPlane:
        ASSERT_EQ(top.block_o, m.block);
        ASSERT_EQ(top.flag_o, m.flag);
        ++mapped;
        break;
      case Decoded::Region::kFlags:
        ASSERT_EQ(top.block_o, m.block);
        ++mapped;
        break;
      case Decoded::Region::kWord:
        ASSERT_EQ(top.block_o, m.block);
        ASSERT_EQ(top.word_o, m.word);
        ++mapped;
        break;
      case Decoded::Region::kNone:
        break;
    }
  }
  EXPECT_GT(mapped, 100000u) << "too few mapped addresses exercised";
}

}  // namespace

TEST(RtlUnitDecode, MatchesTheModelOnAPartialTileAndTenWords) {
  check_against_model<Vunit_decode_odd>(fmpp::Config{100, 10});
}

TEST(RtlUnitDecode, MatchesTheModelOnOneFullTile) { check_against_model<Vunit_decode_small>(fmpp::Config{64, 32}); }
