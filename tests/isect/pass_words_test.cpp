// A pass's words (sw/isect/pass/pass_words.h): every block of the pass ends up with its
// own values whichever way each went out, the blocks beyond the pass are never written,
// and a shared value costs one instruction instead of a bus write per block.
#include <gtest/gtest.h>

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
  EXPECT_EQ(pw.last_writes(), 3u);  // words 2, 4 and 5; word 3 shares no value
  const size_t bus_writes = 10 + count + count / 2 + 1;
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

}  // namespace
}  // namespace fmpp::isect
