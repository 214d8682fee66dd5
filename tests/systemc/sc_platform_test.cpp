// The SystemC TLM-2.0 platform (backends/systemc/) over the golden model: the target's mapping
// of generic payloads onto AXI beats, its refusal of every payload the AXI port cannot
// express, its delay annotation. (SystemCBus running host code: sc_bus_test.cpp.)
#include <gtest/gtest.h>

#include <cstring>
#include <functional>

#include "fmpp/model_bus.h"
#include "backends/systemc/kernel.h"
#include "backends/systemc/systemc_bus.h"
#include "backends/systemc/tlm_target.h"

namespace fmpp::sc {
namespace {

using namespace ins;
using sc_core::sc_time;
using sc_core::SC_NS;

// Records the beats the target forwards, then passes them to the golden model.
class SpyBus : public Bus {
 public:
  explicit SpyBus(const Config& cfg) : model(cfg) {}
  Resp write(uint32_t addr, uint64_t data, uint8_t strb) override {
    ++writes;
    last_addr = addr;
    last_data = data;
    last_strb = strb;
    return model.write(addr, data, strb);
  }
  Resp read(uint32_t addr, uint64_t* data) override {
    ++reads;
    last_addr = addr;
    return model.read(addr, data);
  }
  uint64_t cycles() const override { return model.cycles(); }
  std::string name() const override { return "spy"; }

  ModelBus model;
  unsigned reads = 0, writes = 0;
  uint32_t last_addr = 0;
  uint64_t last_data = 0;
  uint8_t last_strb = 0;
};

struct RawHost : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<RawHost, 64> socket;
  explicit RawHost(const sc_core::sc_module_name& n) : sc_core::sc_module(n), socket("socket") {}
};

// A target around a spied model, driven from a raw initiator socket.
struct Rig {
  explicit Rig(uint64_t period_ps = kDefaultClockPeriodPs, const Config& cfg = Config{100, 16}) : spy(cfg) {
    open_elaboration();
    target = std::make_unique<TlmTarget>("target", spy, period_ps);
    host = std::make_unique<RawHost>("host");
    host->socket.bind(target->socket);
    close_elaboration();
  }
  ~Rig() {
    host.reset();
    target.reset();
  }
  tlm::tlm_response_status send(tlm::tlm_generic_payload& p, sc_time& delay) {
    host->socket->b_transport(p, delay);
    return p.get_response_status();
  }

  SpyBus spy;
  std::unique_ptr<TlmTarget> target;
  std::unique_ptr<RawHost> host;
};

// One well-formed 8-byte payload; tests then break one attribute at a time.
struct Beat {
  Beat(tlm::tlm_command cmd, uint64_t addr, uint64_t value = 0) {
    p.set_command(cmd);
    p.set_address(addr);
    std::memcpy(data, &value, 8);
    p.set_data_ptr(data);
    p.set_data_length(8);
    p.set_streaming_width(8);
    p.set_byte_enable_ptr(nullptr);
    p.set_byte_enable_length(0);
    p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  }
  void enables(std::initializer_list<unsigned char> e) {
    std::copy(e.begin(), e.end(), be);
    p.set_byte_enable_ptr(be);
    p.set_byte_enable_length(static_cast<unsigned>(e.size()));
  }
  uint64_t value() const {
    uint64_t v;
    std::memcpy(&v, data, 8);
    return v;
  }
  tlm::tlm_generic_payload p;
  unsigned char data[16] = {};
  unsigned char be[16] = {};
};

uint32_t word_addr(const Config& c, unsigned block, unsigned word) {
  return map::kWinWordsBase + (block << c.word_shift()) + (word << 3);
}

constexpr unsigned char kOn = TLM_BYTE_ENABLED;
constexpr unsigned char kOff = TLM_BYTE_DISABLED;

TEST(TlmTarget, ServesReadsAndWritesAtTheFmppAddresses) {
  Rig r;
  const Config& c = r.spy.model.config();
  sc_time delay = sc_core::SC_ZERO_TIME;
  Beat id(tlm::TLM_READ_COMMAND, map::kRegId);
  ASSERT_EQ(r.send(id.p, delay), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(id.value(), 0x464D505000010001ull);

  Beat w(tlm::TLM_WRITE_COMMAND, word_addr(c, 99, 15), 0xCAFEF00D);
  w.enables({kOn, kOn, kOn, kOn, kOff, kOff, kOff, kOff});
  ASSERT_EQ(r.send(w.p, delay), tlm::TLM_OK_RESPONSE);
  Beat back(tlm::TLM_READ_COMMAND, word_addr(c, 99, 15));
  ASSERT_EQ(r.send(back.p, delay), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(back.value(), 0xCAFEF00Dull);
  EXPECT_EQ(r.spy.model.machine().word(99, 15), 0xCAFEF00Du);
  EXPECT_FALSE(w.p.is_dmi_allowed());
  EXPECT_EQ(r.target->stats().reads, 2u);
  EXPECT_EQ(r.target->stats().writes, 1u);
}

TEST(TlmTarget, AnnotatesTheClocksTakenTimesThePeriod) {
  Rig r(10'000);  // 100 MHz
  sc_time delay(7, SC_NS);  // the initiator's offset: the target adds to it
  Beat gap(tlm::TLM_WRITE_COMMAND, map::kRegCtrl, 3);  // the array idles 3 clocks per entry
  ASSERT_EQ(r.send(gap.p, delay), tlm::TLM_OK_RESPONSE);
  for (int i = 0; i < 40; ++i) {  // fills the queue: pushes wait for room
    Beat push(tlm::TLM_WRITE_COMMAND, map::kRegQueue, nop().encode());
    ASSERT_EQ(r.send(push.p, delay), tlm::TLM_OK_RESPONSE);
  }
  Beat cyc(tlm::TLM_READ_COMMAND, map::kRegCycles);  // waits for the queue to drain
  ASSERT_EQ(r.send(cyc.p, delay), tlm::TLM_OK_RESPONSE);
  const uint64_t clocks = r.spy.model.cycles();
  EXPECT_GE(clocks, 160u) << "GAP 3 makes 40 entries take 4 clocks each";
  EXPECT_EQ(delay, sc_time(7, SC_NS) + sc_time(10, SC_NS) * static_cast<double>(clocks));
  EXPECT_EQ(r.target->stats().clocks, clocks);
  EXPECT_EQ(r.target->clock_period(), sc_time(10, SC_NS));
}

TEST(TlmTarget, SlvErrIsAGenericErrorAndTheDeviceRecordsIt) {
  Rig r;
  sc_time delay = sc_core::SC_ZERO_TIME;
  struct Case {
    tlm::tlm_command cmd;
    uint64_t addr, data;
    map::Err cause;
  } cases[] = {
      {tlm::TLM_WRITE_COMMAND, map::kRegId, 0, map::Err::kReadonly},
      {tlm::TLM_READ_COMMAND, map::kRegQueue, 0, map::Err::kWriteonly},
      {tlm::TLM_READ_COMMAND, 0x0FFF0000, 0, map::Err::kUnmapped},
      {tlm::TLM_WRITE_COMMAND, map::kRegQueue, uint64_t{31} << 59, map::Err::kIllegal},
      // Not 8-byte aligned: the AXI port carries such an address, so the device decides.
      {tlm::TLM_WRITE_COMMAND, map::kRegCtrl + 4, 0, map::Err::kAlign},
      {tlm::TLM_READ_COMMAND, map::kRegId + 1, 0, map::Err::kAlign},
  };
  for (const Case& k : cases) {
    Beat b(k.cmd, k.addr, k.data);
    EXPECT_EQ(r.send(b.p, delay), tlm::TLM_GENERIC_ERROR_RESPONSE) << std::hex << k.addr;
    EXPECT_EQ(r.spy.model.error().cause, k.cause) << std::hex << k.addr;
    EXPECT_EQ(r.spy.model.error().addr, k.addr);
    if (k.cmd == tlm::TLM_READ_COMMAND) {
      EXPECT_EQ(b.value(), 0u) << "SLVERR reads return 0";
    }
    Beat clear(tlm::TLM_WRITE_COMMAND, map::kRegError, 1);
    ASSERT_EQ(r.send(clear.p, delay), tlm::TLM_OK_RESPONSE);
  }
  EXPECT_EQ(r.target->stats().slverr, std::size(cases));
}

TEST(TlmTarget, RefusesPayloadsTheAxiPortCannotExpress) {
  struct Case {
    const char* what;
    std::function<void(Beat&)> spoil;
    tlm::tlm_response_status want;
  } cases[] = {
      {"address above 32 bits", [](Beat& b) { b.p.set_address(0x1'0000'0000ull); }, tlm::TLM_ADDRESS_ERROR_RESPONSE},
      {"address far above 32 bits", [](Beat& b) { b.p.set_address(~0ull - 7); }, tlm::TLM_ADDRESS_ERROR_RESPONSE},
      {"ignore command", [](Beat& b) { b.p.set_command(tlm::TLM_IGNORE_COMMAND); }, tlm::TLM_COMMAND_ERROR_RESPONSE},
      {"4 bytes", [](Beat& b) { b.p.set_data_length(4); }, tlm::TLM_BURST_ERROR_RESPONSE},
      {"16 bytes", [](Beat& b) { b.p.set_data_length(16); }, tlm::TLM_BURST_ERROR_RESPONSE},
      {"0 bytes", [](Beat& b) { b.p.set_data_length(0); }, tlm::TLM_BURST_ERROR_RESPONSE},
      {"16 bytes, streaming width 16",
       [](Beat& b) {
         b.p.set_data_length(16);
         b.p.set_streaming_width(16);
       },
       tlm::TLM_BURST_ERROR_RESPONSE},
      {"streaming width 4", [](Beat& b) { b.p.set_streaming_width(4); }, tlm::TLM_BURST_ERROR_RESPONSE},
      {"streaming width 0", [](Beat& b) { b.p.set_streaming_width(0); }, tlm::TLM_BURST_ERROR_RESPONSE},
      {"no data pointer", [](Beat& b) { b.p.set_data_ptr(nullptr); }, tlm::TLM_BURST_ERROR_RESPONSE},
      {"byte enable length 0",
       [](Beat& b) {
         b.enables({kOn});
         b.p.set_byte_enable_length(0);
       },
       tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE},
      {"byte enable 0x0f", [](Beat& b) { b.enables({kOn, 0x0F, kOn, kOn, kOn, kOn, kOn, kOn}); },
       tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE},
      {"byte enable 0x01 repeated", [](Beat& b) { b.enables({0x01}); }, tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE},
      // The address is checked first, then the command, then the length, then the enables.
      {"bad address and command",
       [](Beat& b) {
         b.p.set_address(0x1'0000'0000ull);
         b.p.set_command(tlm::TLM_IGNORE_COMMAND);
       },
       tlm::TLM_ADDRESS_ERROR_RESPONSE},
      {"bad command and length",
       [](Beat& b) {
         b.p.set_command(tlm::TLM_IGNORE_COMMAND);
         b.p.set_data_length(4);
       },
       tlm::TLM_COMMAND_ERROR_RESPONSE},
      {"bad length and enables",
       [](Beat& b) {
         b.enables({0x0F});
         b.p.set_data_length(4);
       },
       tlm::TLM_BURST_ERROR_RESPONSE},
  };
  Rig r;
  const sc_time start(3, SC_NS);
  uint64_t refused = 0;
  for (const auto cmd : {tlm::TLM_READ_COMMAND, tlm::TLM_WRITE_COMMAND}) {
    for (const Case& k : cases) {
      // A valid target (a word of block 5), so only the spoiled attribute is wrong.
      Beat b(cmd, word_addr(r.spy.model.config(), 5, 1), 0x5555'5555'5555'5555ull);
      k.spoil(b);
      sc_time delay = start;
      EXPECT_EQ(r.send(b.p, delay), k.want) << k.what << (cmd == tlm::TLM_READ_COMMAND ? " (read)" : " (write)");
      EXPECT_EQ(delay, start) << k.what << ": a refused payload takes no time";
      EXPECT_EQ(b.value(), 0x5555'5555'5555'5555ull) << k.what << ": the data array is untouched";
      ++refused;
    }
  }
  EXPECT_EQ(r.spy.reads + r.spy.writes, 0u) << "no refused payload reached the device";
  EXPECT_EQ(r.spy.model.cycles(), 0u);
  EXPECT_FALSE(r.spy.model.error().sticky);
  EXPECT_EQ(r.target->stats().refused, refused);
}

TEST(TlmTarget, ByteEnablesBecomeTheWriteStrobes) {
  Rig r;
  const Config& c = r.spy.model.config();
  sc_time delay = sc_core::SC_ZERO_TIME;
  const uint32_t a = word_addr(c, 3, 2);
  struct Case {
    std::vector<unsigned char> be;  // empty: no byte enable array
    uint8_t strb;
  } cases[] = {
      {{}, 0xFF},
      {{kOn, kOn, kOff, kOff, kOff, kOff, kOff, kOff}, 0x03},
      {{kOff, kOff, kOn, kOn, kOff, kOff, kOff, kOff}, 0x0C},
      {{kOff, kOff, kOff, kOff, kOff, kOff, kOff, kOff}, 0x00},
      {{kOn, kOff}, 0x55},               // applied repeatedly
      {{kOff, kOff, kOff, kOn}, 0x88},
      {{kOn}, 0xFF},
      {{kOn, kOn, kOn, kOn, kOff, kOff, kOff, kOff, kOn, kOn}, 0x0F},  // longer than the data: the rest unused
  };
  for (const Case& k : cases) {
    Beat b(tlm::TLM_WRITE_COMMAND, a, 0x1122334455667788ull);
    if (!k.be.empty()) {
      std::copy(k.be.begin(), k.be.end(), b.be);
      b.p.set_byte_enable_ptr(b.be);
      b.p.set_byte_enable_length(static_cast<unsigned>(k.be.size()));
    }
    r.send(b.p, delay);
    EXPECT_EQ(r.spy.last_strb, k.strb) << "byte enables of length " << k.be.size();
    EXPECT_EQ(r.spy.last_data, 0x1122334455667788ull);
  }
  // The strobes reach the device: a write of bytes 2-3 of the word changes only those.
  Beat clear(tlm::TLM_WRITE_COMMAND, a, 0);
  clear.enables({kOn, kOn, kOn, kOn, kOff, kOff, kOff, kOff});
  ASSERT_EQ(r.send(clear.p, delay), tlm::TLM_OK_RESPONSE);
  Beat part(tlm::TLM_WRITE_COMMAND, a, 0xAABBCCDD);
  part.enables({kOff, kOff, kOn, kOn, kOff, kOff, kOff, kOff});
  ASSERT_EQ(r.send(part.p, delay), tlm::TLM_OK_RESPONSE);
  Beat back(tlm::TLM_READ_COMMAND, a);
  ASSERT_EQ(r.send(back.p, delay), tlm::TLM_OK_RESPONSE);
  EXPECT_EQ(back.value(), 0xAABB0000ull);
  // Strobes the window cannot take are the device's STROBE error, as on the AXI port.
  Beat high(tlm::TLM_WRITE_COMMAND, a, 1);
  high.enables({kOff, kOff, kOff, kOff, kOn, kOff, kOff, kOff});
  EXPECT_EQ(r.send(high.p, delay), tlm::TLM_GENERIC_ERROR_RESPONSE);
  EXPECT_EQ(r.spy.model.error().cause, map::Err::kStrobe);
}

TEST(TlmTarget, ReadCopiesOnlyTheEnabledBytes) {
  Rig r;
  sc_time delay = sc_core::SC_ZERO_TIME;
  Beat b(tlm::TLM_READ_COMMAND, map::kRegId, 0xEEEE'EEEE'EEEE'EEEEull);
  b.enables({kOn, kOff});
  ASSERT_EQ(r.send(b.p, delay), tlm::TLM_OK_RESPONSE);
  // ID = 0x464D5050_00010001 (version 1.1): bytes 0, 2, 4, 6 are 0x01, 0x01, 0x50, 0x4D.
  EXPECT_EQ(b.value(), 0xEE4DEE50EE01EE01ull);
}

TEST(TlmTarget, OffersNoDmiAndNoDebugTransport) {
  Rig r;
  Beat b(tlm::TLM_READ_COMMAND, map::kRegId);
  tlm::tlm_dmi dmi;
  EXPECT_FALSE(r.host->socket->get_direct_mem_ptr(b.p, dmi));
  EXPECT_EQ(r.host->socket->transport_dbg(b.p), 0u);
  EXPECT_EQ(r.spy.reads, 0u);
}

TEST(TlmTarget, RejectsABadClockPeriod) {
  open_elaboration();
  ModelBus m(Config{1, 8});
  EXPECT_THROW(TlmTarget("bad_period", m, 0), std::invalid_argument);
}

// ------------------------------------------------------------------ SystemCBus

}  // namespace
}  // namespace fmpp::sc
