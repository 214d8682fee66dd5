// SystemCBus (backends/systemc/systemc_bus.h) over the golden model: host code runs
// unchanged and counts the same clocks, SystemC time follows the device's clock, the
// quantum batches the kernel's synchronisation, and misuse fails loudly.
#include <gtest/gtest.h>

#include <functional>

#include "backends/systemc/kernel.h"
#include "backends/systemc/systemc_bus.h"
#include "fmpp/isa.h"
#include "fmpp/model_bus.h"
#include "tb/progen.h"

namespace fmpp::sc {
namespace {

using namespace ins;
using sc_core::sc_time;
using sc_core::SC_NS;

TEST(SystemCBus, RunsHostCodeUnchangedAndCountsTheSameClocks) {
  const Config cfg{100, 16};
  auto sc = make_systemc_bus(std::make_unique<ModelBus>(cfg));
  ModelBus ref(cfg);
  tb::ProgramGenerator gen_sc(cfg, 5), gen_ref(cfg, 5);
  for (int i = 0; i < 5000; ++i) {
    gen_sc.step(*sc);
    gen_ref.step(ref);
    ASSERT_EQ(sc->cycles(), ref.cycles()) << "access " << i;
  }
  EXPECT_EQ(sc->name(), "systemc");
  const auto& dev = dynamic_cast<ModelBus&>(sc->device());
  EXPECT_EQ(dev.machine().state_hash(), ref.machine().state_hash());
  EXPECT_EQ(dev.error(), ref.error());
  EXPECT_GT(sc->target().stats().slverr, 0u) << "the program makes bad accesses too";
  EXPECT_EQ(sc->target().stats().refused, 0u) << "SystemCBus never builds a payload the target refuses";
}

TEST(SystemCBus, SystemCTimeFollowsTheDeviceClock) {
  ScOptions opt;
  opt.clock_period_ps = 20'000;
  opt.quantum_ps = 0;  // hand the time to the kernel after every access
  auto sc = make_systemc_bus(std::make_unique<ModelBus>(Config{64, 32}), opt);
  for (int i = 0; i < 100; ++i) {
    sc->write(map::kRegQueue, add(1, 2, 3).encode());
    EXPECT_EQ(sc_core::sc_time_stamp(), sc_time(20, SC_NS) * static_cast<double>(sc->cycles()));
  }
  uint64_t id = 0;
  ASSERT_EQ(sc->read(map::kRegId, &id), Resp::kOkay);
  EXPECT_EQ(sc_core::sc_time_stamp(), sc_time(20, SC_NS) * static_cast<double>(sc->cycles()));
  EXPECT_EQ(sc->local_time(), sc_time(20, SC_NS) * static_cast<double>(sc->cycles()));
}

TEST(SystemCBus, QuantumBatchesTheKernelSynchronisation) {
  ScOptions opt;
  opt.quantum_ps = 1'000'000;  // 1 us = 50 clocks
  auto sc = make_systemc_bus(std::make_unique<ModelBus>(Config{64, 32}), opt);
  for (int i = 0; i < 49; ++i) sc->write(map::kRegQueue, nop().encode());
  EXPECT_EQ(sc_core::sc_time_stamp(), sc_core::SC_ZERO_TIME) << "49 clocks are inside the quantum";
  sc->write(map::kRegQueue, nop().encode());
  EXPECT_EQ(sc_core::sc_time_stamp(), sc_time(1, sc_core::SC_US));
  sc->write(map::kRegQueue, nop().encode());
  EXPECT_EQ(sc->local_time(), sc_time(1020, SC_NS));
  sc->sync();
  EXPECT_EQ(sc_core::sc_time_stamp(), sc_time(1020, SC_NS));
}

TEST(SystemCBus, FailsLoudlyWhenTheDeviceIsDrivenBehindItsBack) {
  auto sc = make_systemc_bus(std::make_unique<ModelBus>(Config{64, 32}));
  sc->write(map::kRegQueue, nop().encode());
  sc->device().write(map::kRegQueue, nop().encode());  // not through SystemC
  try {
    sc->write(map::kRegQueue, nop().encode());
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("the device is at 3"), std::string::npos) << e.what();
  }
}

TEST(SystemCBus, AdvanceAccountsForClocksOutsideTheTlmPath) {
  auto sc = make_systemc_bus(std::make_unique<ModelBus>(Config{64, 32}));
  sc->device().write(map::kRegQueue, nop().encode());
  sc->advance(1);
  EXPECT_EQ(sc->write(map::kRegQueue, nop().encode()), Resp::kOkay);
  EXPECT_EQ(sc->cycles(), 2u);
}

TEST(SystemCKernel, PlatformsCoexistUntilElaborationEndsThenOneAtATime) {
  {
    auto a = make_systemc_bus(std::make_unique<ModelBus>(Config{1, 8}));
    auto b = make_systemc_bus(std::make_unique<ModelBus>(Config{1, 8}));
    EXPECT_EQ(a->write(map::kRegQueue, nop().encode()), Resp::kOkay);  // ends elaboration
    EXPECT_EQ(b->write(map::kRegQueue, nop().encode()), Resp::kOkay);
    try {
      auto c = make_systemc_bus(std::make_unique<ModelBus>(Config{1, 8}));
      FAIL() << "a third platform was built after elaboration ended";
    } catch (const std::logic_error& e) {
      EXPECT_NE(std::string(e.what()).find("fmpp_target"), std::string::npos) << e.what();
    }
  }
  auto d = make_systemc_bus(std::make_unique<ModelBus>(Config{1, 8}));  // a fresh kernel
  EXPECT_EQ(d->write(map::kRegQueue, nop().encode()), Resp::kOkay);
  EXPECT_EQ(sc_core::sc_time_stamp(), sc_core::SC_ZERO_TIME);
}

TEST(SystemCBus, RejectsMisuse) {
  EXPECT_THROW(make_systemc_bus(nullptr), std::invalid_argument);
  ScOptions opt;
  opt.clock_period_ps = 0;
  EXPECT_THROW(make_systemc_bus(std::make_unique<ModelBus>(Config{1, 8}), opt), std::invalid_argument);
  EXPECT_THROW(make_systemc_rtl_bus(nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace fmpp::sc
