// The SystemC kernel's life cycle, for the FMPP's TLM platforms (backends/systemc/).
//
// The SystemC kernel (one per process) accepts new modules only until elaboration
// ends, and elaboration ends at the first use of a platform. A program that builds
// one platform, uses it, destroys it and builds another (each test case, each run
// of a benchmark) therefore needs a fresh kernel in between. open_elaboration()
// provides one when that is safe: elaboration has ended and no SystemC object is
// left. The platforms here never run SystemC processes of their own; host code
// calls b_transport directly and advances SystemC time with sc_start() (see
// systemc_bus.h), so a kernel holds nothing else worth keeping.
#pragma once

namespace fmpp::sc {

// Call before creating modules. If elaboration has already ended and the kernel holds
// no object any more, replaces it with a fresh kernel (SystemC time starts at 0
// again). Throws std::logic_error naming the live top-level objects if elaboration
// has ended and objects remain: SystemC cannot add modules to a running simulation,
// so every earlier platform must be destroyed first.
void open_elaboration();

// Ends elaboration (binds every port and socket) unless it has ended already.
// Afterwards sockets may be used and no module may be added.
void close_elaboration();

// True once elaboration has ended in the current kernel.
bool elaboration_closed();

}  // namespace fmpp::sc
