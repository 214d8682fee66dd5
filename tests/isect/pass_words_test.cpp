// A pass's words (sw/isect/pass/pass_words.h): every block of the pass ends up with its
// own values whichever way each went out, the blocks beyond the pass are never written,
// a shared value costs one instruction instead of a bus write per block, and a value
// whose blocks are a few cubes of indices (a column or a row of a Z-ordered tile) a few.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass_words.h"

namespace fmpp::isect {
namespace {

TEST(PassWords, EveryBlockGetsItsValuesAndNoOtherBlockIsWritten) {
  ModelBus bus(Config{100, 16});
  Device dev(bus);
  const unsigned count = 70;
  for (unsigned b = 0; b < 100; ++b) {
    for (unsigned w = 2; w < 6; ++w) dev.write_word(b, w, 0xDEAD0000u + b);
  }
  PassWords pw;
  pw.begin(count);
  for (unsigned b = 0; b < count; ++b) {
    pw.set(b, 2, b % 7 == 0 ? 1000 + b : 5);               // mostly 5
    pw.set(b, 3, 3 * b);                                   // all different
    pw.set(b, 4, b % 2 == 0 ? 0xFFFFFFF0u : 0x10u);        // a tie: the lower value is shared
    if (b < 40) pw.set(b, 5, b < 39 ? 0x80000000u : 9u);   // set for some blocks only
  }
  EXPECT_THROW(pw.set(count, 2, 1), std::out_of_range);
  Program pre;
  select_below(pre, count, 100);
  KernelStats st;
  const uint64_t c0 = dev.cycles();
  pw.flush(dev, std::move(pre), &st);
  // Words 2, 4 and 5 share a value, word 3 none; word 4's other value lies in the even
  // blocks below 70: 0 .. 62, 64 .. 66 and 68, three cubes.
  EXPECT_EQ(pw.last_writes(), 4u);
  EXPECT_EQ(pw.last_cubes(), 3u);
  const size_t bus_writes = 10 + count + 1;
  EXPECT_EQ(pw.last_bus_writes(), bus_writes);
  EXPECT_EQ(dev.cycles() - c0, st.instructions + bus_writes);
  for (unsigned b = 0; b < 100; ++b) {
    if (b >= count) {
      for (unsigned w = 2; w < 6; ++w) EXPECT_EQ(dev.read_word(b, w), 0xDEAD0000u + b) << b << " " << w;
      continue;
    }
    EXPECT_EQ(dev.read_word(b, 2), b % 7 == 0 ? 1000 + b : 5u) << b;
    EXPECT_EQ(dev.read_word(b, 3), 3 * b) << b;
    EXPECT_EQ(dev.read_word(b, 4), b % 2 == 0 ? 0xFFFFFFF0u : 0x10u) << b;
    // A block without a value for word 5 took the shared one (the pass's words are
    // written for every block by the forms; this only shows what the WRITES does).
    EXPECT_EQ(dev.read_word(b, 5), b == 39 ? 9u : 0x80000000u) << b;
  }
}

TEST(PassWords, NothingSharedIsAllBusWrites) {
  ModelBus bus(Config{64, 8});
  Device dev(bus);
  PassWords pw;
  pw.begin(3);
  for (unsigned b = 0; b < 3; ++b) pw.set(b, 1, b);
  Program pre;
  select_below(pre, 3, 64);
  KernelStats st;
  pw.flush(dev, std::move(pre), &st);
  EXPECT_EQ(pw.last_writes(), 0u);
  EXPECT_EQ(pw.last_bus_writes(), 3u);
  for (unsigned b = 0; b < 3; ++b) EXPECT_EQ(dev.read_word(b, 1), b);
}

// Cubes of block indices cover a set exactly: each within it, none overlapping, all of it;
// a set that is one cube is one cube; past the limit the cover gives up.
TEST(PassWords, CubesCoverTheirSetExactly) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 400; ++trial) {
    const uint32_t universe = 1u << (1 + rng() % 9);
    std::vector<uint32_t> set;
    const int kind = trial % 3;
    const uint32_t fixed = static_cast<uint32_t>(rng()) & (universe - 1), mask = static_cast<uint32_t>(rng()) & (universe - 1);
    for (uint32_t b = 0; b < universe; ++b) {
      const bool in = kind == 0 ? rng() % 3 == 0 : kind == 1 ? (b & ~mask) == (fixed & ~mask) : (b & ~mask) == (fixed & ~mask) && b % 5 != 0;
      if (in) set.push_back(b);
    }
    std::vector<AddrCube> cubes;
    ASSERT_TRUE(cover_by_cubes(set.data(), set.size(), set.size() + 1, &cubes));
    if (kind == 1) {
      EXPECT_EQ(cubes.size(), 1u);
    }
    std::vector<int> covered(universe, 0);
    for (const AddrCube& c : cubes) {
      for (uint32_t b = 0; b < universe; ++b) covered[b] += (b & ~c.mask) == (c.key & ~c.mask) ? 1 : 0;
    }
    for (uint32_t b = 0; b < universe; ++b) {
      const bool in = std::binary_search(set.begin(), set.end(), b);
      EXPECT_EQ(covered[b], in ? 1 : 0) << "trial " << trial << " block " << b;
    }
    if (cubes.size() > 1) {
      std::vector<AddrCube> fewer;
      EXPECT_FALSE(cover_by_cubes(set.data(), set.size(), cubes.size() - 1, &fewer));
    }
  }
}

// Random layouts on machines of every shape: columns, rows, a few shared values, all
// different, words some blocks leave unset; every block of the pass holds what it was
// given (an unset word the most shared value, if any), no other block changes, and the
// clocks are the instructions plus the bus writes.
TEST(PassWords, RandomLayoutsLandExactly) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 60; ++trial) {
    const unsigned blocks = std::vector<unsigned>{64, 100, 256, 1000, 4096}[trial % 5];
    const unsigned count = trial % 2 ? blocks : 1 + static_cast<unsigned>(rng() % blocks);
    ModelBus bus(Config{blocks, 8});
    Device dev(bus);
    for (unsigned b = 0; b < blocks; ++b) {
      for (unsigned w = 0; w < 8; ++w) dev.write_word(b, w, 0xDEAD0000u + b);
    }
    std::vector<std::map<unsigned, uint32_t>> given(8);
    PassWords pw;
    pw.begin(count);
    const uint32_t cols = static_cast<uint32_t>(rng()) & (blocks - 1), shift = static_cast<uint32_t>(rng() % 8);
    for (unsigned w = 1; w < 8; ++w) {
      for (unsigned b = 0; b < count; ++b) {
        if (w == 7 && rng() % 4 == 0) continue;  // unset
        const uint32_t v = w == 1 ? (b & cols) * 977u : w == 2 ? (b >> shift) : w == 3 ? static_cast<uint32_t>(rng() % 3)
                         : w == 4 ? static_cast<uint32_t>(rng()) : w == 5 ? 0x80000000u ^ (b & 0x55u) : w == 6 ? 7u : b % 3;
        pw.set(b, w, v);
        given[w][b] = v;
      }
    }
    Program pre;
    select_below(pre, count, blocks);
    KernelStats st;
    const uint64_t c0 = dev.cycles();
    pw.flush(dev, std::move(pre), &st);
    EXPECT_EQ(dev.cycles() - c0, st.instructions + pw.last_bus_writes());
    for (unsigned w = 1; w < 8; ++w) {
      std::map<uint32_t, unsigned> n;
      for (const auto& [b, v] : given[w]) ++n[v];
      uint32_t mode = 0;
      unsigned most = 0;
      for (const auto& [v, k] : n) {
        if (k > most) mode = v, most = k;
      }
      for (unsigned b = 0; b < blocks; ++b) {
        const uint32_t got = dev.read_word(b, w);
        if (b >= count) {
          ASSERT_EQ(got, 0xDEAD0000u + b) << "trial " << trial << " word " << w << " block " << b;
        } else if (given[w].count(b)) {
          ASSERT_EQ(got, given[w][b]) << "trial " << trial << " word " << w << " block " << b;
        } else {
          ASSERT_EQ(got, most >= 2 ? mode : 0xDEAD0000u + b) << "trial " << trial << " word " << w << " block " << b;
        }
      }
    }
  }
}

// A 64 x 64 tile in Z-order whose word 1 is its column and word 2 its row: each of the 63
// values beside each word's most shared one is one cube, four clocks, no bus write.
TEST(PassWords, ColumnsAndRowsOfAZOrderedTileAreCubes) {
  ModelBus bus(Config{4096, 8});
  Device dev(bus);
  PassWords pw;
  pw.begin(4096);
  for (unsigned b = 0; b < 4096; ++b) {
    unsigned x = 0, y = 0;
    for (unsigned k = 0; k < 6; ++k) x |= ((b >> (2 * k)) & 1u) << k, y |= ((b >> (2 * k + 1)) & 1u) << k;
    pw.set(b, 1, 1000 + x);
    pw.set(b, 2, 5000 + y);
  }
  Program pre;
  select_below(pre, 4096, 4096);
  KernelStats st;
  const uint64_t c0 = dev.cycles();
  pw.flush(dev, std::move(pre), &st);
  EXPECT_EQ(pw.last_bus_writes(), 0u);
  EXPECT_EQ(pw.last_cubes(), 2u * 63);
  EXPECT_EQ(pw.last_writes(), 2u * 64);
  EXPECT_LE(dev.cycles() - c0, 2u * 64 * 4 + 4);
  for (unsigned b = 0; b < 4096; b += 37) {
    EXPECT_EQ(dev.read_word(b, 1) - 1000, (b & 1) | ((b >> 1) & 2) | ((b >> 2) & 4) | ((b >> 3) & 8) | ((b >> 4) & 16) | ((b >> 5) & 32));
  }
}

}  // namespace
}  // namespace fmpp::isect
