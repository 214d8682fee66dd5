// The FMPP as a SystemC TLM-2.0 target: a loosely-timed (b_transport) socket in
// front of any fmpp::Bus (the Verilated RTL, the golden model).
//
// A generic payload maps onto one AXI4-Lite beat of the FMPP's 64-bit port
// (docs/generated/memory-map.md): a read or write of 8 bytes at a 32-bit byte address, the
// TLM byte enables becoming the AXI write strobes (byte i of the data array is
// strobe bit i; the platform is little-endian, like the AXI data bus). The device
// answers OKAY -> TLM_OK_RESPONSE or SLVERR -> TLM_GENERIC_ERROR_RESPONSE, and the
// delay is increased by the clocks the access took times the clock period.
//
// A payload the AXI port cannot express is refused before it reaches the device,
// with the TLM-2.0 standard error response, checked in this order:
//   address above 32 bits                 TLM_ADDRESS_ERROR_RESPONSE
//   command other than read or write      TLM_COMMAND_ERROR_RESPONSE
//   (TLM_IGNORE_COMMAND too: the FMPP has no probe operation, and an OK answer
//   would look like an accepted access)
//   no data pointer, data length != 8,
//   streaming width < 8 (a streaming
//   transfer: AXI4-Lite has no bursts)    TLM_BURST_ERROR_RESPONSE
//   byte enable length 0, or an enable
//   that is neither 0x00 nor 0xFF          TLM_BYTE_ENABLE_ERROR_RESPONSE
// A refused payload costs no clock and leaves the device untouched. What the AXI
// port can express the device judges itself, exactly as on the AXI port: an address
// that is not 8-byte aligned, unmapped, read-only or write-only, strobes that do not
// fit the target, an illegal instruction. Those answer SLVERR and are recorded in
// the device's ERROR register, so a SystemC run and a direct run stay identical.
//
// The target never calls wait(): it may be called from outside any SystemC process
// (SystemCBus does). It offers no DMI (the FMPP's state is not a plain memory) and
// no debug transport (every FMPP read has timing: it drains the queue).
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include <cstdint>

#include "fmpp/bus.h"

namespace fmpp::sc {

// 50 MHz, the paper's clock.
inline constexpr uint64_t kDefaultClockPeriodPs = 20000;

class TlmTarget : public sc_core::sc_module {
 public:
  // 64-bit socket: one beat of the FMPP's AXI data bus.
  tlm_utils::simple_target_socket<TlmTarget, 64> socket;

  // `device` must outlive the target. Throws std::invalid_argument if
  // clock_period_ps is 0 or not a whole number of SystemC time resolution units.
  TlmTarget(const sc_core::sc_module_name& name, Bus& device, uint64_t clock_period_ps = kDefaultClockPeriodPs);

  // Serves one payload (registered on the socket; public so tests can call it too).
  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay);

  struct Stats {
    uint64_t reads = 0;     // read beats forwarded to the device
    uint64_t writes = 0;    // write beats forwarded to the device
    uint64_t slverr = 0;    // forwarded beats the device answered SLVERR
    uint64_t refused = 0;   // payloads refused before reaching the device
    uint64_t clocks = 0;    // clocks the device took for the forwarded beats
  };
  const Stats& stats() const { return stats_; }
  const sc_core::sc_time& clock_period() const { return period_; }

 private:
  // The error response for a payload the AXI port cannot express, or
  // TLM_INCOMPLETE_RESPONSE if it may go to the device.
  static tlm::tlm_response_status refuse(const tlm::tlm_generic_payload& trans);

  Bus& device_;
  sc_core::sc_time period_;
  Stats stats_;
};

}  // namespace fmpp::sc
