// The host's Device layer: indices are checked against the device's size, every bus
// error becomes an exception naming its own cause, and an RTL assertion failure stops
// a run on the rtl and systemc backends instead of scrolling past.
#include <gtest/gtest.h>

#include "backends/backend.h"
#include "sw/fmpp/device.h"

namespace fmpp {
namespace {

TEST(Device, IndicesOutsideTheDeviceAreRefused) {
  ModelBus bus(Config{100, 16});  // two tiles, the second partly used
  Device dev(bus);
  EXPECT_THROW(dev.write_word(0, 16, 1), std::out_of_range);  // once wrote block 1, word 0
  EXPECT_THROW(dev.read_word(100, 0), std::out_of_range);
  EXPECT_THROW(dev.read_word(16515072, 0), std::out_of_range);  // once wrapped into the registers
  EXPECT_THROW(dev.write_flags(100, 1), std::out_of_range);
  EXPECT_THROW(dev.read_flags(100), std::out_of_range);
  EXPECT_THROW(dev.read_plane(8, 0), std::out_of_range);
  EXPECT_THROW(dev.read_plane(0, 2), std::out_of_range);  // once read the next flag's plane
  try {
    dev.read_word(0, 16);
    ADD_FAILURE();
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(), "fmpp::Device: word 16 out of range (the 100x16 FMPP has 16)");
  }
  // The last block, word, flag and tile are in range; nothing above touched the device.
  dev.write_word(99, 15, 7);
  EXPECT_EQ(dev.read_word(99, 15), 7u);
  EXPECT_EQ(dev.read_word(1, 0), 0u);
  EXPECT_EQ(dev.read_plane(7, 1), 0u);
  uint64_t err = 0;
  ASSERT_EQ(bus.read(map::kRegError, &err), Resp::kOkay);
  EXPECT_EQ(err, 0u);
}

TEST(Device, EachErrorReportsItsOwnCause) {
  ModelBus bus(Config{64, 8});
  Device dev(bus);
  const uint64_t illegal = map::kFieldOp.put(map::kNumOpcodes);  // no such opcode
  try {
    dev.push(illegal);
    ADD_FAILURE();
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("cause 4 ILLEGAL"), std::string::npos) << e.what();
  }
  uint64_t err = 1;
  ASSERT_EQ(bus.read(map::kRegError, &err), Resp::kOkay);
  EXPECT_EQ(err, 0u) << "the Device clears ERROR once it has reported it";
  // A different error next: its message carries its own cause, not the first one's.
  try {
    dev.push(ins::add(8, 0, 0).encode());  // word 8 of an 8-word device
    ADD_FAILURE();
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("ERROR = 0x"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cause 4 ILLEGAL"), std::string::npos) << e.what();
  }
  ASSERT_EQ(bus.write(map::kRegCtrl, 0, 0x0F), Resp::kSlvErr);  // STROBE, left uncleared
  EXPECT_THROW(Device{bus}, DeviceError) << "a Device must not inherit someone else's error";
  try {
    Device again(bus);
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("uncleared error"), std::string::npos) << e.what();
  }
}

// A device that answers one register with another value.
class AlteredBus final : public Bus {
 public:
  AlteredBus(Bus& inner, uint32_t reg, uint64_t value) : inner_(inner), reg_(reg), value_(value) {}
  Resp write(uint32_t addr, uint64_t data, uint8_t strb) override { return inner_.write(addr, data, strb); }
  Resp read(uint32_t addr, uint64_t* data) override {
    const Resp r = inner_.read(addr, data);
    if (addr == reg_) *data = value_;
    return r;
  }
  uint64_t cycles() const override { return inner_.cycles(); }
  std::string name() const override { return "altered"; }

 private:
  Bus& inner_;
  uint32_t reg_;
  uint64_t value_;
};

TEST(Device, RefusesAnotherVersionOrBlockStride) {
  ModelBus model(Config{64, 8});
  uint64_t id = 0, cfg = 0;
  ASSERT_EQ(model.read(map::kRegId, &id), Resp::kOkay);
  ASSERT_EQ(model.read(map::kRegConfig, &cfg), Resp::kOkay);
  EXPECT_NO_THROW(Device{model});
  AlteredBus v2(model, map::kRegId, id + map::kIdMajor.put(1));
  EXPECT_THROW(Device{v2}, DeviceError);
  AlteredBus stride(model, map::kRegConfig, cfg + map::kConfigWshift.put(1));
  EXPECT_THROW(Device{stride}, DeviceError);
}

// docs/generated/memory-map.md, "Ordering and timing", on the golden model and the RTL alike.
class BusRules : public ::testing::TestWithParam<const char*> {};

TEST_P(BusRules, ReservedRegisterBitsAreIgnoredAndReadAsZero) {
  auto be = make_backend(GetParam(), Config{64, 32});
  Bus& bus = be->bus();
  uint64_t v = 0;
  ASSERT_EQ(bus.write(map::kRegCtrl, 0x1FF), Resp::kOkay);
  ASSERT_EQ(bus.read(map::kRegCtrl, &v), Resp::kOkay);
  EXPECT_EQ(v, 0xFFu);
  ASSERT_EQ(bus.write(map::kRegError, ~uint64_t{1}), Resp::kOkay);  // every bit but STICKY: no effect
  ASSERT_EQ(bus.read(map::kRegError, &v), Resp::kOkay);
  EXPECT_EQ(v, 0u);
  be->finish();
}

TEST_P(BusRules, AnInvalidPushWaitsForRoomInTheQueueNotForTheDrain) {
  auto be = make_backend(GetParam(), Config{64, 32});
  Bus& bus = be->bus();
  ASSERT_EQ(bus.write(map::kRegCtrl, 200), Resp::kOkay);  // 201 clocks per entry
  // The first entry leaves the queue for the pipeline at once; then the queue fills.
  for (unsigned k = 0; k < map::kQueueDepth + 1; ++k) ASSERT_EQ(bus.write(map::kRegQueue, ins::nop().encode()), Resp::kOkay);
  // The queue is full: a write to QUEUE, legal or not, waits for one pop (the address
  // alone decides when a write is accepted), then an illegal one is answered SLVERR and
  // queues nothing.
  const uint64_t c0 = bus.cycles();
  ASSERT_EQ(bus.write(map::kRegQueue, map::kFieldOp.put(map::kNumOpcodes)), Resp::kSlvErr);
  EXPECT_LE(bus.cycles() - c0, 202u) << "waited for more than one pop";
  EXPECT_GE(bus.cycles() - c0, 100u) << "accepted into a full queue";
  uint64_t v = 0;
  ASSERT_EQ(bus.read(map::kRegError, &v), Resp::kOkay);
  EXPECT_EQ(map::kErrorCause.get(v), static_cast<uint64_t>(map::Err::kIllegal));
  EXPECT_EQ(map::kErrorCount.get(v), 1u);
  ASSERT_EQ(bus.read(map::kRegInstret, &v), Resp::kOkay);
  EXPECT_EQ(v, map::kQueueDepth + 1) << "the illegal instruction was queued";
  ASSERT_EQ(bus.write(map::kRegError, 1), Resp::kOkay);
  be->finish();
}

TEST_P(BusRules, ErrorCountSaturatesAndAClearRestartsIt) {
  auto be = make_backend(GetParam(), Config{64, 32});
  Bus& bus = be->bus();
  uint64_t v = 0;
  // Bad writes and bad reads alternately, past the 16-bit count's maximum.
  for (unsigned k = 0; k < 0x10004; ++k) {
    if (k % 2) {
      ASSERT_EQ(bus.read(map::kRegQueue, &v), Resp::kSlvErr);
    } else {
      ASSERT_EQ(bus.write(map::kRegId, 0), Resp::kSlvErr);
    }
    if (k == 0xFFFD) {
      ASSERT_EQ(bus.read(map::kRegError, &v), Resp::kOkay);
      ASSERT_EQ(map::kErrorCount.get(v), 0xFFFEu);
    }
  }
  ASSERT_EQ(bus.read(map::kRegError, &v), Resp::kOkay);
  EXPECT_EQ(map::kErrorCount.get(v), map::kErrorCount.max());
  EXPECT_EQ(map::kErrorCause.get(v), static_cast<uint64_t>(map::Err::kReadonly)) << "the first cause stays";
  ASSERT_EQ(bus.write(map::kRegError, 1), Resp::kOkay);
  ASSERT_EQ(bus.write(map::kRegId, 0), Resp::kSlvErr);
  ASSERT_EQ(bus.read(map::kRegError, &v), Resp::kOkay);
  EXPECT_EQ(map::kErrorCount.get(v), 1u);
  EXPECT_EQ(map::kErrorCause.get(v), static_cast<uint64_t>(map::Err::kReadonly));
  ASSERT_EQ(bus.write(map::kRegError, 1), Resp::kOkay);
  be->finish();
}

INSTANTIATE_TEST_SUITE_P(Backends, BusRules, ::testing::Values("cmodel", "rtl", "lockstep"),
                         [](const auto& info) { return std::string(info.param); });

// A master that withdraws an unaccepted write trips the RTL's protocol assertion; the
// Verilated model only records it, so the backend's bus must stop the run.
void expect_assertion_stops(const std::string& backend) {
  auto be = make_backend(backend, Config{64, 32});
  ASSERT_NE(be->rtl_bus(), nullptr);
  Bus& bus = be->bus();
  ASSERT_EQ(bus.write(map::kRegCtrl, 200), Resp::kOkay);  // a slow array: the queue fills
  for (unsigned k = 0; k < map::kQueueDepth + 1; ++k) ASSERT_EQ(bus.write(map::kRegQueue, ins::nop().encode()), Resp::kOkay);
  be->rtl_bus()->withdraw_write_for_test(map::kRegQueue, ins::nop().encode());
  uint64_t v = 0;
  try {
    (void)bus.read(map::kRegStatus, &v);
    ADD_FAILURE() << backend << ": the read after the assertion failure passed";
  } catch (const std::logic_error& e) {
    // The withdrawn write drove the RTL outside the TLM path: the platform's clock
    // check stops this read even before the assertion check does.
    EXPECT_EQ(backend, "systemc") << e.what();
    EXPECT_NE(std::string(e.what()).find("driven outside the SystemC path"), std::string::npos) << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(backend, "rtl") << e.what();
    EXPECT_NE(std::string(e.what()).find("RTL assertion failed"), std::string::npos) << e.what();
  }
  try {
    be->finish();
    ADD_FAILURE() << backend << ": finish() passed over the assertion failure";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("RTL assertion failed"), std::string::npos) << e.what();
  }
}

TEST(Backend, RtlAssertionFailureStopsTheRun) { expect_assertion_stops("rtl"); }

TEST(Backend, RtlAssertionFailureStopsTheRunOverSystemC) { expect_assertion_stops("systemc"); }

}  // namespace
}  // namespace fmpp
