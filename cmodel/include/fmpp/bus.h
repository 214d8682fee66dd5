// The one way into an FMPP: AXI4-Lite beats at byte addresses (docs/generated/memory-map.md).
//
// Implemented by the golden model (fmpp::ModelBus), the Verilated RTL (tb/ RtlBus),
// the lockstep checker that drives both, and the SystemC TLM platform. Host
// software (sw/) only ever sees this interface, so it runs unchanged on each.
#pragma once

#include <cstdint>
#include <string>

namespace fmpp {

// AXI response codes the FMPP returns.
enum class Resp : uint8_t { kOkay = 0, kSlvErr = 2 };

class Bus {
 public:
  virtual ~Bus() = default;

  // One write beat. `strb` are the AXI byte strobes of the 64-bit beat.
  // Returns the write response; a SLVERR write had no effect other than
  // recording the error in the ERROR register.
  [[nodiscard]] virtual Resp write(uint32_t addr, uint64_t data, uint8_t strb = 0xFF) = 0;

  // One read beat. Sets *data to RDATA (0 on SLVERR). A read completes only
  // after every earlier write has taken effect.
  [[nodiscard]] virtual Resp read(uint32_t addr, uint64_t* data) = 0;

  // Clock cycles since reset.
  virtual uint64_t cycles() const = 0;

  // Short name of the backend ("cmodel", "rtl", "lockstep", "systemc").
  virtual std::string name() const = 0;
};

}  // namespace fmpp
