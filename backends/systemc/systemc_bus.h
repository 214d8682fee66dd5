// The FMPP over SystemC TLM-2.0: an fmpp::Bus whose accesses travel as generic
// payloads from a TLM initiator socket to the FMPP target (tlm_target.h), which
// forwards them to a device Bus (the Verilated RTL or the golden model).
//
//   host code --Bus--> SystemCBus: TlmInitiator --b_transport--> TlmTarget --Bus--> device
//
// Host code written against fmpp::Bus (the ray tracer, fmpp-sim's random programs)
// runs unchanged: make_systemc_bus() wraps any device, make_systemc_rtl_bus() wraps
// a Verilated RTL bus and keeps its checker interface, so the lockstep (backends/lockstep.h)
// can drive the RTL through SystemC while the golden model stays the reference.
//
// Time is loosely timed. The host is not a SystemC process: it calls b_transport
// directly, keeps the target's annotated delays as a local time offset and hands that
// offset to the kernel with sc_start() once it reaches the quantum (ScOptions), so
// SystemC time follows the device's clock. cycles() is the sum of the clocks the
// target reported (its delays divided by the clock period), and after every access it
// is checked against the device's own count: both must agree, or the access throws.
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>

#include <cstdint>
#include <memory>
#include <string>

#include "fmpp/bus.h"
#include "backends/rtl/rtl_bus.h"
#include "backends/systemc/tlm_target.h"

namespace fmpp::sc {

struct ScOptions {
  uint64_t clock_period_ps = kDefaultClockPeriodPs;  // the FMPP clock (default 50 MHz)
  // Local time the host may run ahead of SystemC time before it calls sc_start();
  // 0 synchronizes after every access. (Default: 500 clocks at 50 MHz.)
  uint64_t quantum_ps = 10'000'000;
};

// The initiator side: one 64-bit socket and a reusable generic payload.
class TlmInitiator : public sc_core::sc_module {
 public:
  tlm_utils::simple_initiator_socket<TlmInitiator, 64> socket;

  explicit TlmInitiator(const sc_core::sc_module_name& name);

  // One 8-byte beat. `data` is written (write) or read into (read); `strb` becomes the
  // byte enables of a write (reads carry none). `delay` is the local time offset,
  // increased by the target. Returns the payload's response status.
  tlm::tlm_response_status transport(tlm::tlm_command cmd, uint32_t addr, uint64_t* data, uint8_t strb,
                                     sc_core::sc_time& delay);

 private:
  tlm::tlm_generic_payload trans_;
  unsigned char data_[8] = {};
  unsigned char be_[8] = {};
};

class SystemCBus : public Bus {
 public:
  // Builds an initiator and a target around `device` (which this bus then owns).
  // Must be created before the kernel's elaboration ends, or once every earlier
  // platform is gone (kernel.h); throws std::logic_error otherwise and
  // std::invalid_argument for a null device or a bad ScOptions.
  explicit SystemCBus(std::unique_ptr<Bus> device, const ScOptions& opt = {});
  ~SystemCBus() override;
  SystemCBus(const SystemCBus&) = delete;
  SystemCBus& operator=(const SystemCBus&) = delete;

  // TLM_OK_RESPONSE -> kOkay, TLM_GENERIC_ERROR_RESPONSE -> kSlvErr (read data 0).
  // Any other response means this initiator built a payload the target refused, a
  // bug: throws std::logic_error naming the response and the address.
  Resp write(uint32_t addr, uint64_t data, uint8_t strb = 0xFF) override;
  Resp read(uint32_t addr, uint64_t* data) override;
  uint64_t cycles() const override { return cycles_; }
  std::string name() const override { return "systemc"; }

  // Records `clocks` the device ran outside the TLM path (RtlBus::idle), keeping
  // cycles() equal to the device's count.
  void advance(uint64_t clocks);
  // Hands the local time offset to the kernel now (sc_start).
  void sync();

  Bus& device() { return *device_; }
  const TlmTarget& target() const { return *target_; }
  // SystemC time plus the local offset not yet handed to the kernel.
  sc_core::sc_time local_time() const;

 private:
  Resp finish(tlm::tlm_response_status st, const char* what, uint32_t addr, const sc_core::sc_time& before);

  std::unique_ptr<Bus> device_;  // declared first: the target refers to it
  ScOptions opt_;
  std::unique_ptr<TlmTarget> target_;
  std::unique_ptr<TlmInitiator> initiator_;
  sc_core::sc_time quantum_;
  sc_core::sc_time offset_;  // local time not yet handed to the kernel
  uint64_t cycles_ = 0;
};

// The factory host programs use (a later `fmpp-render --backend systemc` too):
//   auto bus = fmpp::sc::make_systemc_bus(fmpp::backends::make_rtl_bus(blocks, words));
//   auto bus = fmpp::sc::make_systemc_bus(std::make_unique<fmpp::ModelBus>(cfg));
std::unique_ptr<SystemCBus> make_systemc_bus(std::unique_ptr<Bus> device, const ScOptions& opt = {});

// The Verilated RTL behind SystemC, still an RtlBus: bus accesses go through TLM,
// while the checker's back door (state(), exec hook, idle(), failure()) reaches the
// RTL directly. fmpp-sim --backend systemc puts this on the RTL side of the lockstep.
std::unique_ptr<backends::RtlBus> make_systemc_rtl_bus(std::unique_ptr<backends::RtlBus> rtl, const ScOptions& opt = {});

}  // namespace fmpp::sc
