// The systemc backend, offered by make_backend (backends/backend.h) in the binaries that
// link this object: registered before main.
#include "backends/backend.h"
#include "backends/systemc/systemc_bus.h"

namespace {

const bool registered = fmpp::register_systemc_backend(
    [](std::unique_ptr<fmpp::backends::RtlBus> rtl) -> std::unique_ptr<fmpp::Bus> {
      return fmpp::sc::make_systemc_bus(std::move(rtl));
    });

}  // namespace
