// The lockstep checker itself: it must catch every kind of disagreement, and a
// random program (also under random bus stalls) must run clean.
#include <gtest/gtest.h>

#include <random>

#include "backends/lockstep.h"
#include "tb/progen.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp::backends {
namespace {

using namespace ins;
using tb::ProgramGenerator;

struct Rig {
  explicit Rig(const std::string& name, LockstepOptions lo = {}, RtlOptions ro = {})
      : cfg(named_config(name)), rtl(make_rtl_bus(name, ro)), model(cfg), lock(*rtl, model, lo) {}
  Config cfg;
  std::unique_ptr<RtlBus> rtl;
  ModelBus model;
  Lockstep lock;
};

TEST(Lockstep, CatchesAStateDifferenceAtTheEntryThatExposesIt) {
  // Without clock comparison, so that the state check (not the clock check) fires.
  LockstepOptions lo;
  lo.compare_cycles = false;
  Rig r("small", lo);
  r.lock.write(map::kRegQueue, sets().encode());
  // Corrupt the RTL behind the checker's back: block 5 word 2 differs from now on.
  const uint32_t a = map::kWinWordsBase + (5u << r.cfg.word_shift()) + (2u << 3);
  ASSERT_EQ(r.rtl->write(a, 42, 0x0F), Resp::kOkay);
  try {
    r.lock.write(map::kRegQueue, add(3, 2, 2).encode());
    r.lock.write(map::kRegQueue, nop().encode());
    r.lock.final_check();
    FAIL() << "no mismatch reported";
  } catch (const LockstepMismatch& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("block 5 word 2: rtl 0x0000002a model 0x00000000"), std::string::npos) << msg;
    EXPECT_NE(msg.find("LOCKSTEP MISMATCH after queue entry #"), std::string::npos) << msg;
  }
}

TEST(Lockstep, CatchesReadDataAndClockDifferences) {
  {
    Rig r("tiny", LockstepOptions{LockstepOptions::Mode::kOff});
    ASSERT_EQ(r.rtl->write(map::kWinFlagsBase, 3, 0x01), Resp::kOkay);
    uint64_t v;
    EXPECT_THROW(r.lock.read(map::kWinFlagsBase, &v), LockstepMismatch);
  }
  {
    Rig r("tiny", LockstepOptions{LockstepOptions::Mode::kOff});
    r.rtl->idle(1);
    EXPECT_THROW(r.lock.write(map::kRegQueue, nop().encode()), LockstepMismatch);
  }
  {
    Rig r("tiny", LockstepOptions{LockstepOptions::Mode::kFast, 1});
    ASSERT_EQ(r.rtl->write(map::kRegQueue, sets().encode()), Resp::kOkay);
    ASSERT_EQ(r.model.write(map::kRegQueue, sets().encode()), Resp::kOkay);
    ASSERT_EQ(r.rtl->write(map::kWinWordsBase, 7, 0x0F), Resp::kOkay);  // RTL only
    ASSERT_EQ(r.model.write(map::kRegQueue, nop().encode()), Resp::kOkay);
    // The differing entries take effect kPipeLatency clocks after their pop: the hash
    // differs once the second of them has executed, at the third push from here.
    EXPECT_THROW(
        {
          for (unsigned k = 0; k <= ModelBus::kPipeLatency; ++k) r.lock.write(map::kRegQueue, nop().encode());
        },
        LockstepMismatch);
  }
}

class LockstepModes : public ::testing::TestWithParam<LockstepOptions::Mode> {};

TEST_P(LockstepModes, RandomProgramRunsClean) {
  const LockstepOptions::Mode mode = GetParam();
  Rig r("odd", LockstepOptions{mode, 64});
  ProgramGenerator gen(r.cfg, 11);
  for (int k = 0; k < 3000; ++k) gen.step(r.lock);
  EXPECT_GT(gen.stats().reads, 100u) << "off mode checks read data: the program must read";
  r.lock.final_check();
  if (mode == LockstepOptions::Mode::kOff) {
    EXPECT_EQ(r.lock.state_checks(), 1u) << "off mode compares the state only in final_check()";
  } else {
    EXPECT_GT(r.lock.state_checks(), 10u);
  }
  EXPECT_GT(r.lock.entries(), 1000u);
  EXPECT_EQ(r.rtl->failure(), "");
}

INSTANTIATE_TEST_SUITE_P(Every, LockstepModes,
                         ::testing::Values(LockstepOptions::Mode::kCheck, LockstepOptions::Mode::kFast,
                                           LockstepOptions::Mode::kOff),
                         [](const auto& info) {
                           switch (info.param) {
                             case LockstepOptions::Mode::kCheck: return std::string("check");
                             case LockstepOptions::Mode::kFast: return std::string("fast");
                             case LockstepOptions::Mode::kOff: return std::string("off");
                           }
                           return std::string("unknown");
                         });

TEST(Lockstep, RandomProgramUnderBusStalls) {
  RtlOptions ro;
  ro.stress = true;
  ro.stress_seed = 3;
  LockstepOptions lo;
  lo.compare_cycles = false;
  Rig r("small", lo, ro);
  ProgramGenerator gen(r.cfg, 5);
  for (int k = 0; k < 3000; ++k) gen.step(r.lock);
  r.lock.final_check();
  EXPECT_GT(r.rtl->cycles(), r.model.cycles()) << "the stalls cost clocks";
  EXPECT_EQ(r.rtl->failure(), "");
}

// The SVA assertions run in every simulation: a master that withdraws a write the
// slave has not accepted (here: into a full queue) is caught.
TEST(RtlAssertions, ProtocolViolationIsReported) {
  auto rtl = make_rtl_bus("small");
  ASSERT_EQ(rtl->write(map::kRegCtrl, 200), Resp::kOkay);  // a slow array: the queue fills
  for (unsigned k = 0; k < map::kQueueDepth + 1; ++k) ASSERT_EQ(rtl->write(map::kRegQueue, nop().encode()), Resp::kOkay);
  EXPECT_EQ(rtl->failure(), "");
  rtl->withdraw_write_for_test(map::kRegQueue, nop().encode());
  EXPECT_NE(rtl->failure().find("RTL assertion failed"), std::string::npos) << rtl->failure();
}

TEST(Lockstep, ConfigurationsMustMatch) {
  auto rtl = make_rtl_bus("tiny");
  ModelBus model(Config{2, 8});
  EXPECT_THROW(Lockstep(*rtl, model, {}), std::invalid_argument);
  EXPECT_THROW(make_rtl_bus("nonexistent"), std::invalid_argument);
}

// The state extractor's transposition against the bit-by-bit one, on random planes.
TEST(ArchState, PlanesToWordsIsTheTransposition) {
  std::mt19937_64 rng(7);
  for (unsigned nplanes : {8u, 16u, 32u}) {
    for (int round = 0; round < 50; ++round) {
      uint64_t planes[32];
      for (auto& p : planes) p = rng();
      uint32_t got[64];
      planes_to_words(planes, nplanes, got);
      for (unsigned l = 0; l < 64; ++l) {
        uint32_t want = 0;
        for (unsigned k = 0; k < nplanes; ++k) want |= static_cast<uint32_t>((planes[k] >> l) & 1u) << k;
        ASSERT_EQ(got[l], want) << "lane " << l << ", " << nplanes << " planes";
      }
    }
  }
}

}  // namespace
}  // namespace fmpp::backends
