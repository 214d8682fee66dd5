// Golden model behind the bus: address map, access rules, errors and clock timing.
#include <gtest/gtest.h>

#include "fmpp/model_bus.h"

namespace fmpp {
namespace {

using namespace ins;
using map::Err;

uint32_t word_addr(const Config& c, unsigned block, unsigned word) {
  return map::kWinWordsBase + (block << c.word_shift()) + (word << 3);
}

uint64_t rd(Bus& bus, uint32_t addr) {
  uint64_t v = 0;
  EXPECT_EQ(bus.read(addr, &v), Resp::kOkay) << std::hex << addr;
  return v;
}

TEST(ModelBus, IdentificationAndConfig) {
  ModelBus bus(Config{100, 16});
  EXPECT_EQ(rd(bus, map::kRegId), 0x464D505000010001ull);
  const uint64_t cfg = rd(bus, map::kRegConfig);
  EXPECT_EQ(cfg & 0xFFFFFFFF, 100u);
  EXPECT_EQ((cfg >> 32) & 0xFF, 16u);
  EXPECT_EQ((cfg >> 40) & 0xFF, map::kQueueDepth);
  EXPECT_EQ((cfg >> 48) & 0xFF, 64u);
  EXPECT_EQ((cfg >> 56) & 0xFF, 7u);  // 16 words: 128-byte stride
}

TEST(ModelBus, DecodeAddress) {
  const Config c{100, 6};
  EXPECT_EQ(decode_address(c, word_addr(c, 99, 5)).region, Decoded::Region::kWord);
  EXPECT_EQ(decode_address(c, word_addr(c, 99, 6)).region, Decoded::Region::kNone) << "word 6 of 6";
  EXPECT_EQ(decode_address(c, word_addr(c, 100, 0)).region, Decoded::Region::kNone);
  EXPECT_EQ(decode_address(c, map::kWinFlagsBase + 8 * 99).region, Decoded::Region::kFlags);
  EXPECT_EQ(decode_address(c, map::kWinFlagsBase + 8 * 100).region, Decoded::Region::kNone);
  const Decoded p = decode_address(c, map::kWinPlanesBase + (7u << 13) + 8);
  EXPECT_EQ(p.region, Decoded::Region::kPlane);
  EXPECT_EQ(p.flag, 7u);
  EXPECT_EQ(p.block, 1u);
  EXPECT_EQ(decode_address(c, map::kWinPlanesBase + 16).region, Decoded::Region::kNone) << "tile 2 of 2";
  EXPECT_FALSE(decode_address(c, 0x44).aligned);
  EXPECT_EQ(decode_address(c, 0x0FF8).region, Decoded::Region::kReg);
  EXPECT_EQ(decode_address(c, 0x1000).region, Decoded::Region::kNone);
}

TEST(ModelBus, WordAndFlagWindowsRoundTrip) {
  const Config c{100, 16};
  ModelBus bus(c);
  EXPECT_EQ(bus.write(word_addr(c, 99, 15), 0xCAFEF00D, 0x0F), Resp::kOkay);
  EXPECT_EQ(bus.write(word_addr(c, 0, 0), 0x12345678, 0x0F), Resp::kOkay);
  EXPECT_EQ(bus.write(word_addr(c, 0, 0), 0xAABBCCDD, 0x06), Resp::kOkay);
  EXPECT_EQ(bus.write(map::kWinFlagsBase + 8 * 64, 0x81, 0x01), Resp::kOkay);
  EXPECT_EQ(rd(bus, word_addr(c, 99, 15)), 0xCAFEF00Dull);
  EXPECT_EQ(rd(bus, word_addr(c, 0, 0)), 0x12BBCC78ull);
  EXPECT_EQ(rd(bus, map::kWinFlagsBase + 8 * 64), 0x81ull);
  EXPECT_EQ(rd(bus, map::kWinPlanesBase + 8), 1ull) << "SEL plane of tile 1";
  EXPECT_EQ(rd(bus, map::kWinPlanesBase + (7u << 13) + 8), 1ull) << "V plane of tile 1";
  EXPECT_EQ(rd(bus, map::kRegStatus), 0b110ull) << "ANY and OVF";
  const uint64_t resp = rd(bus, map::kRegResp);
  EXPECT_EQ(resp, (1ull << 63) | (64ull << 32) | 1);
}

struct BadAccess {
  const char* what;
  bool write;
  uint32_t addr;
  uint64_t data;
  uint8_t strb;
  Err cause;
};

TEST(ModelBus, BadAccessesAnswerSlverrAndAreRecorded) {
  const Config c{100, 6};
  const BadAccess cases[] = {
      {"unknown opcode", true, map::kRegQueue, uint64_t{map::kNumOpcodes} << 59, 0xFF, Err::kIllegal},
      {"word operand out of range", true, map::kRegQueue, add(6, 0, 0).encode(), 0xFF, Err::kIllegal},
      {"partial queue strobe", true, map::kRegQueue, 0, 0x0F, Err::kStrobe},
      {"write ID", true, map::kRegId, 0, 0xFF, Err::kReadonly},
      {"write RESP", true, map::kRegResp, 0, 0xFF, Err::kReadonly},
      {"read QUEUE", false, map::kRegQueue, 0, 0, Err::kWriteonly},
      {"unmapped register", false, 0x0800, 0, 0, Err::kUnmapped},
      {"unmapped high", true, 0x20000000, 0, 0xFF, Err::kUnmapped},
      {"misaligned", false, map::kRegId + 4, 0, 0, Err::kAlign},
      {"block past end", true, word_addr(c, 100, 0), 0, 0x0F, Err::kUnmapped},
      {"word past end", false, word_addr(c, 3, 7), 0, 0, Err::kUnmapped},
      {"upper word strobe", true, word_addr(c, 3, 1), 0, 0xF0, Err::kStrobe},
      {"empty strobe", true, word_addr(c, 3, 1), 0, 0x00, Err::kStrobe},
      {"flags strobe", true, map::kWinFlagsBase, 0, 0x03, Err::kStrobe},
      {"plane write", true, map::kWinPlanesBase, 0, 0xFF, Err::kReadonly},
      {"ctrl strobe", true, map::kRegCtrl, 0, 0x01, Err::kStrobe},
  };
  for (const BadAccess& b : cases) {
    ModelBus bus(c);
    uint64_t v = 0xDEAD;
    const Resp r = b.write ? bus.write(b.addr, b.data, b.strb) : bus.read(b.addr, &v);
    EXPECT_EQ(r, Resp::kSlvErr) << b.what;
    if (!b.write) {
      EXPECT_EQ(v, 0u) << b.what;
    }
    const uint64_t e = rd(bus, map::kRegError);
    EXPECT_EQ(e & 1, 1u) << b.what;
    EXPECT_EQ((e >> 4) & 0xF, static_cast<unsigned>(b.cause)) << b.what;
    EXPECT_EQ((e >> 16) & 0xFFFF, 1u) << b.what;
    EXPECT_EQ(e >> 32, b.addr) << b.what;
    EXPECT_EQ(bus.machine().instret(), 0u) << b.what << ": nothing executed";
  }
}

TEST(ModelBus, ErrorKeepsTheFirstCauseCountsAndClears) {
  ModelBus bus(Config{4, 8});
  uint64_t v;
  bus.read(map::kRegQueue, &v);
  bus.write(map::kRegId, 0);
  bus.write(map::kRegId, 0);
  uint64_t e = rd(bus, map::kRegError);
  EXPECT_EQ((e >> 4) & 0xF, static_cast<unsigned>(Err::kWriteonly));
  EXPECT_EQ((e >> 16) & 0xFFFF, 3u);
  EXPECT_EQ(rd(bus, map::kRegStatus) & 1, 1u);
  EXPECT_EQ(bus.write(map::kRegError, 0), Resp::kOkay);  // writing 0 clears nothing
  EXPECT_EQ(rd(bus, map::kRegError), e);
  EXPECT_EQ(bus.write(map::kRegError, 1), Resp::kOkay);
  EXPECT_EQ(rd(bus, map::kRegError), 0u);
  // Saturating count.
  for (int k = 0; k < 70000; ++k) bus.write(map::kRegMask, 0);
  e = rd(bus, map::kRegError);
  EXPECT_EQ((e >> 16) & 0xFFFF, 0xFFFFu);
}

TEST(ModelBus, AReadWaitsOneClockAfterAnAccessThatChangesError) {
  ModelBus bus(Config{4, 8});
  uint64_t v;
  // Reference: a read right after a good register write is accepted at the next edge.
  EXPECT_EQ(bus.write(map::kRegCtrl, 0), Resp::kOkay);
  uint64_t t = bus.cycles();
  EXPECT_EQ(bus.read(map::kRegId, &v), Resp::kOkay);
  EXPECT_EQ(bus.cycles() - t, 1u);
  // After a write with an error, a read with an error and a write to ERROR (even one
  // that clears nothing), the read waits one clock for ERROR to change, then sees it.
  struct Step {
    const char* what;
    bool write;
    uint32_t addr;
    uint64_t data;
    uint64_t count_after;
  } steps[] = {{"bad write", true, map::kRegId, 0, 1},
               {"bad read", false, map::kRegQueue, 0, 2},
               {"ERROR write of 0", true, map::kRegError, 0, 2},
               {"ERROR write of 1", true, map::kRegError, 1, 0}};
  for (const Step& s : steps) {
    if (s.write) {
      bus.write(s.addr, s.data);
    } else {
      bus.read(s.addr, &v);
    }
    t = bus.cycles();
    EXPECT_EQ(bus.read(map::kRegError, &v), Resp::kOkay) << s.what;
    EXPECT_EQ(bus.cycles() - t, 2u) << s.what;
    EXPECT_EQ(map::kErrorCount.get(v), s.count_after) << s.what;
    // A good read changes nothing: the next read is not held.
    t = bus.cycles();
    EXPECT_EQ(bus.read(map::kRegError, &v), Resp::kOkay) << s.what;
    EXPECT_EQ(bus.cycles() - t, 1u) << s.what;
  }
  // A push right after an error is not held (only reads wait).
  bus.write(map::kRegId, 0);
  t = bus.cycles();
  EXPECT_EQ(bus.write(map::kRegQueue, nop().encode()), Resp::kOkay);
  EXPECT_EQ(bus.cycles() - t, 1u);
}

TEST(ModelBus, PushesTakeOneClockAndReadsDrain) {
  ModelBus bus(Config{4, 8});
  constexpr unsigned kLat = ModelBus::kPipeLatency;
  for (int k = 0; k < 10; ++k) EXPECT_EQ(bus.write(map::kRegQueue, sets().encode()), Resp::kOkay);
  EXPECT_EQ(bus.cycles(), 10u);
  // Push k lands at edge k, is popped at edge k + 1 and executes kLat edges later: after
  // edge 10 the last push is still queued and the kLat before it are in the pipeline.
  EXPECT_EQ(bus.machine().instret(), 9u - kLat) << "the last entries are queued or in flight";
  EXPECT_EQ(bus.in_flight(), kLat);
  // The read waits one clock for the queue to drain, kLat for the pipeline and one with the
  // array idle, then is accepted.
  EXPECT_EQ(rd(bus, map::kRegCycles), 12u + kLat);
  EXPECT_EQ(bus.cycles(), 13u + kLat);
  EXPECT_EQ(bus.in_flight(), 0u);
  EXPECT_EQ(rd(bus, map::kRegInstret), 10u);
}

TEST(ModelBus, GapFillsTheQueueAndBackPressures) {
  ModelBus bus(Config{4, 8});
  EXPECT_EQ(bus.write(map::kRegCtrl, 3), Resp::kOkay);  // cycle 1
  EXPECT_EQ(bus.cycles(), 1u);
  // Each entry now occupies the array for 4 clocks (pops at clocks 2, 6, 10, ... after
  // the CTRL write) while pushes arrive every clock: the queue holds t - floor((t + 2) / 4)
  // entries after clock t and is full after 21 pushes. Pushes 22..40 each wait for a pop:
  // push 21 + j lands the clock after pop j, at clock 23 + 4 (j - 1); push 40 at clock 95.
  for (int k = 0; k < 40; ++k) bus.write(map::kRegQueue, nop().encode());
  EXPECT_EQ(bus.cycles(), 1u + 95u);
  EXPECT_EQ(bus.queue_level(), map::kQueueDepth) << "full when the last push lands";
  // 24 pops so far: pop j at clock 4 j - 1, so pop 24 came at clock 95, with push 40, and
  // executes kPipeLatency clocks later; the 23 before it have executed.
  EXPECT_EQ(bus.in_flight(), 1u);
  EXPECT_EQ(bus.machine().instret(), 40u - map::kQueueDepth - 1u);
  const uint64_t before = bus.cycles();
  EXPECT_EQ(rd(bus, map::kRegInstret), 40u);
  // Drain: 2 clocks left of the current gap, 16 pops 4 clocks apart, the last entry's
  // kPipeLatency clocks in the pipeline, the clock idle, then the read.
  EXPECT_EQ(bus.cycles() - before, 2u + 1u + 4u * 15 + ModelBus::kPipeLatency + 1u + 1u);
}

TEST(ModelBus, RespAndStatusWaitForTheResponderTree) {
  ModelBus bus(Config{4, 8});
  EXPECT_EQ(bus.write(map::kRegQueue, sets().encode()), Resp::kOkay);
  (void)rd(bus, map::kRegCycles);  // drained
  // A read of any other register is accepted at the first edge; RESP and STATUS wait
  // kRespLatency more, and see every block selected.
  uint64_t t = bus.cycles();
  (void)rd(bus, map::kRegMask);
  EXPECT_EQ(bus.cycles() - t, 1u);
  t = bus.cycles();
  const uint64_t resp = rd(bus, map::kRegResp);
  EXPECT_EQ(bus.cycles() - t, 1u + map::kRespLatency);
  EXPECT_EQ(map::kRespCount.get(resp), 4u);
  t = bus.cycles();
  EXPECT_EQ(map::kStatusAny.get(rd(bus, map::kRegStatus)), 1u);
  EXPECT_EQ(bus.cycles() - t, 1u + map::kRespLatency);
}

TEST(ModelBus, FlagopIfAnyHoldsThePipelineForTheAnyTree) {
  // The same program with FLAG_ANY set and clear: the first holds stage 3 kAnyLatency
  // clocks more, and writes only where some block has the value 1.
  for (bool any : {false, true}) {
    ModelBus bus(Config{4, 8});
    EXPECT_EQ(bus.write(map::kRegQueue, resets().encode()), Resp::kOkay);
    (void)rd(bus, map::kRegCycles);
    const uint64_t t = bus.cycles();
    // SEL <- SEL and SEL (0 everywhere): with FLAG_ANY no block has 1, so nothing is written.
    EXPECT_EQ(bus.write(map::kRegQueue, flagop(map::kFlagSEL, map::kFlagSEL, map::kFlagSEL, 0b1000, any).encode()),
              Resp::kOkay);
    EXPECT_EQ(bus.write(map::kRegQueue, sets().encode()), Resp::kOkay);
    EXPECT_EQ(rd(bus, map::kRegInstret), 3u);
    // Two pushes, a clock to pop the last, the pipeline's latency, the clock idle, the read;
    // and the hold.
    EXPECT_EQ(bus.cycles() - t, 2u + 1u + ModelBus::kPipeLatency + 1u + 1u + (any ? map::kAnyLatency : 0u)) << any;
  }
}

TEST(ModelBus, AnAccessWaitsForTheArrayIdleAWholeClock) {
  // A read right after the pipeline drains waits one clock (what it reads then stood still
  // two clocks); a read with nothing in flight the clock before does not.
  ModelBus bus(Config{4, 8});
  EXPECT_EQ(bus.write(map::kRegQueue, sets().encode()), Resp::kOkay);  // edge 1: pushed
  uint64_t t = bus.cycles();
  (void)rd(bus, map::kRegMask);
  // Popped at edge 2, retires at 2 + kPipeLatency, idle a clock, then accepted.
  EXPECT_EQ(bus.cycles() - t, 1u + ModelBus::kPipeLatency + 1u + 1u);
  t = bus.cycles();
  (void)rd(bus, map::kRegMask);
  EXPECT_EQ(bus.cycles() - t, 1u);
  // A CTRL write waits the same way; an ERROR write with nothing in flight does not.
  EXPECT_EQ(bus.write(map::kRegQueue, sets().encode()), Resp::kOkay);
  t = bus.cycles();
  EXPECT_EQ(bus.write(map::kRegCtrl, 0), Resp::kOkay);
  EXPECT_EQ(bus.cycles() - t, 1u + ModelBus::kPipeLatency + 1u + 1u);
  t = bus.cycles();
  EXPECT_EQ(bus.write(map::kRegCtrl, 0), Resp::kOkay);
  EXPECT_EQ(bus.cycles() - t, 1u);
}

}  // namespace
}  // namespace fmpp
