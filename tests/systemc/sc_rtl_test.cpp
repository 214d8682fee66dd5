// The Verilated RTL behind the SystemC TLM-2.0 platform (make_systemc_rtl_bus): the
// lockstep against the golden model still holds, and the checker's back door and
// idle clocks stay consistent with the clocks counted over TLM.
#include <gtest/gtest.h>

#include "fmpp/model_bus.h"
#include "backends/lockstep.h"
#include "tb/progen.h"
#include "backends/systemc/systemc_bus.h"

namespace fmpp::sc {
namespace {

using namespace ins;

TEST(SystemCRtl, RandomProgramInLockstepWithTheModel) {
  for (auto mode : {backends::LockstepOptions::Mode::kCheck, backends::LockstepOptions::Mode::kFast}) {
    auto rtl = make_systemc_rtl_bus(backends::make_rtl_bus("tiny"));
    EXPECT_EQ(rtl->name(), "systemc");
    ModelBus model(rtl->config());
    backends::Lockstep lock(*rtl, model, backends::LockstepOptions{mode, 64});
    tb::ProgramGenerator gen(rtl->config(), 17);
    for (int k = 0; k < 4000; ++k) gen.step(lock);
    lock.final_check();
    EXPECT_GT(lock.state_checks(), 10u);
    EXPECT_EQ(rtl->failure(), "");
  }
}

TEST(SystemCRtl, RandomProgramUnderBusStalls) {
  backends::RtlOptions ro;
  ro.stress = true;
  ro.stress_seed = 9;
  auto rtl = make_systemc_rtl_bus(backends::make_rtl_bus("small", ro));
  ModelBus model(rtl->config());
  backends::LockstepOptions lo;
  lo.compare_cycles = false;
  backends::Lockstep lock(*rtl, model, lo);
  tb::ProgramGenerator gen(rtl->config(), 4);
  for (int k = 0; k < 3000; ++k) gen.step(lock);
  lock.final_check();
  EXPECT_GT(rtl->cycles(), model.cycles()) << "stalls cost clocks the model does not see";
}

TEST(SystemCRtl, IdleClocksAndTheBackDoorStayConsistent) {
  auto rtl = make_systemc_rtl_bus(backends::make_rtl_bus("tiny"));
  const Config cfg = rtl->config();
  ASSERT_EQ(rtl->write(map::kWinWordsBase + (1u << 3), 0x1234, 0x0F), Resp::kOkay);
  rtl->idle(7);  // not a bus access: the SystemC side is told of the clocks
  ASSERT_EQ(rtl->write(map::kRegQueue, sets().encode()), Resp::kOkay);
  ASSERT_EQ(rtl->write(map::kRegQueue, add(2, 1, 1).encode()), Resp::kOkay);
  uint64_t cycles = 0;
  ASSERT_EQ(rtl->read(map::kRegCycles, &cycles), Resp::kOkay);
  EXPECT_GE(rtl->cycles(), 10u);
  EXPECT_LE(rtl->cycles() - cycles, 1u);
  const backends::ArchState st = rtl->state();
  EXPECT_EQ(st.word(0, 1), 0x1234u);
  EXPECT_EQ(st.word(0, 2), 0x2468u);
  EXPECT_EQ(st.cfg.blocks, cfg.blocks);
  EXPECT_EQ(rtl->failure(), "");
}

}  // namespace
}  // namespace fmpp::sc
