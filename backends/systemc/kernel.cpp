// The SystemC kernel's life cycle (see kernel.h).
#include "backends/systemc/kernel.h"

#include <systemc>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace fmpp::sc {

void open_elaboration() {
  sc_core::sc_simcontext* ctx = sc_core::sc_get_curr_simcontext();
  if (!ctx->elaboration_done()) return;
  const std::vector<sc_core::sc_object*>& live = sc_core::sc_get_top_level_objects();
  if (!live.empty()) {
    std::string names;
    for (const sc_core::sc_object* o : live) names += std::string(names.empty() ? "" : ", ") + o->name();
    throw std::logic_error(
        "fmpp::sc::open_elaboration: SystemC elaboration has ended and objects remain (" + names +
        "); SystemC cannot add modules now: destroy every earlier platform before building a new one");
  }
  // sc_simcontext::reset() deletes the kernel's registries and starts a new
  // elaboration phase at time 0; with no object left nothing refers to the old ones.
  ctx->reset();
}

void close_elaboration() {
  sc_core::sc_simcontext* ctx = sc_core::sc_get_curr_simcontext();
  if (ctx->elaboration_done()) return;
  // What sc_start() does first, without running a delta cycle: sc_start(SC_ZERO_TIME)
  // would also end elaboration, but in a second kernel of the same process it warns
  // (W571, "no activity") because of a static flag inside sc_start().
  ctx->initialize(true);
}

bool elaboration_closed() { return sc_core::sc_get_curr_simcontext()->elaboration_done(); }

}  // namespace fmpp::sc

// libsystemc.so calls sc_main() from its own main(), so every program linked with it
// must define sc_main. The programs here have their own main() and never call it; the
// definition is weak so that a program with a real sc_main() overrides it.
extern "C" __attribute__((weak)) int sc_main(int, char*[]) {
  std::fputs("fmpp: this program has its own main(); sc_main() is not an entry point\n", stderr);
  return 1;
}
