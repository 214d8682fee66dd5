// The FMPP TLM-2.0 target (see tlm_target.h).
#include "backends/systemc/tlm_target.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace fmpp::sc {

// The data array holds the 64-bit beat in host byte order, and byte i must be AXI
// byte lane i (strobe bit i): true on a little-endian host only.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "fmpp::sc::TlmTarget maps TLM bytes to AXI lanes as little-endian");

namespace {
constexpr unsigned kBeatBytes = 8;
}  // namespace

TlmTarget::TlmTarget(const sc_core::sc_module_name& name, Bus& device, uint64_t clock_period_ps)
    : sc_core::sc_module(name), socket("socket"), device_(device) {
  if (clock_period_ps == 0) throw std::invalid_argument("fmpp::sc::TlmTarget: clock period 0 ps");
  // Delays are whole multiples of the period, kept in resolution units, so that SystemC
  // time never drifts from the device's clock count.
  const uint64_t units_per_ps = sc_core::sc_time(1, sc_core::SC_PS).value();
  if (units_per_ps == 0) {
    throw std::invalid_argument("fmpp::sc::TlmTarget: SystemC time resolution " +
                                sc_core::sc_get_time_resolution().to_string() + " is coarser than 1 ps");
  }
  period_ = sc_core::sc_time::from_value(clock_period_ps * units_per_ps);
  socket.register_b_transport(this, &TlmTarget::b_transport);
}

tlm::tlm_response_status TlmTarget::refuse(const tlm::tlm_generic_payload& t) {
  if (t.get_address() > 0xFFFFFFFFull) return tlm::TLM_ADDRESS_ERROR_RESPONSE;
  if (!t.is_read() && !t.is_write()) return tlm::TLM_COMMAND_ERROR_RESPONSE;
  if (t.get_data_ptr() == nullptr || t.get_data_length() != kBeatBytes || t.get_streaming_width() < kBeatBytes) {
    return tlm::TLM_BURST_ERROR_RESPONSE;
  }
  if (const unsigned char* be = t.get_byte_enable_ptr()) {
    const unsigned n = t.get_byte_enable_length();
    if (n == 0) return tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE;
    // A byte enable array shorter than the data is applied repeatedly (IEEE 1666 14.14).
    for (unsigned i = 0; i < kBeatBytes; ++i) {
      if (be[i % n] != TLM_BYTE_DISABLED && be[i % n] != TLM_BYTE_ENABLED) return tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE;
    }
  }
  return tlm::TLM_INCOMPLETE_RESPONSE;
}

void TlmTarget::b_transport(tlm::tlm_generic_payload& t, sc_core::sc_time& delay) {
  t.set_dmi_allowed(false);
  const tlm::tlm_response_status refused = refuse(t);
  if (refused != tlm::TLM_INCOMPLETE_RESPONSE) {
    ++stats_.refused;
    t.set_response_status(refused);
    return;
  }
  uint8_t strb = 0xFF;
  if (const unsigned char* be = t.get_byte_enable_ptr()) {
    strb = 0;
    for (unsigned i = 0; i < kBeatBytes; ++i) {
      if (be[i % t.get_byte_enable_length()] == TLM_BYTE_ENABLED) strb |= static_cast<uint8_t>(1u << i);
    }
  }
  const uint32_t addr = static_cast<uint32_t>(t.get_address());
  unsigned char* data = t.get_data_ptr();
  const uint64_t c0 = device_.cycles();
  Resp r;
  if (t.is_write()) {
    uint64_t v;
    std::memcpy(&v, data, kBeatBytes);
    r = device_.write(addr, v, strb);
    ++stats_.writes;
  } else {
    // AXI reads have no strobes: the whole beat is read, and only the enabled bytes
    // are copied back (a target must not touch disabled bytes of the data array).
    uint64_t v = 0;
    r = device_.read(addr, &v);
    unsigned char bytes[kBeatBytes];
    std::memcpy(bytes, &v, kBeatBytes);
    for (unsigned i = 0; i < kBeatBytes; ++i) {
      if ((strb >> i) & 1u) data[i] = bytes[i];
    }
    ++stats_.reads;
  }
  const uint64_t clocks = device_.cycles() - c0;
  stats_.clocks += clocks;
  delay += sc_core::sc_time::from_value(clocks * period_.value());
  if (r == Resp::kOkay) {
    t.set_response_status(tlm::TLM_OK_RESPONSE);
  } else {
    ++stats_.slverr;
    t.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
  }
}

}  // namespace fmpp::sc
