// Choosing a built RTL configuration by size (the by-name factory is generated
// by CMake into rtl_configs.cpp, one case per configuration of fmpp_map.json).
#include "tb/rtl_bus.h"

#include <stdexcept>

#include <verilated.h>

namespace fmpp::tb {

std::unique_ptr<RtlBus> make_rtl_bus(unsigned blocks, unsigned words, const RtlOptions& opt) {
  std::string best;
  Config best_cfg{0, 0};
  std::string built;
  for (const std::string& name : rtl_configs()) {
    const Config c = named_config(name);
    built += (built.empty() ? "" : ", ") + name + " (" + c.str() + ")";
    if (c.blocks < blocks || c.words < words) continue;
    if (best.empty() || c.blocks < best_cfg.blocks || (c.blocks == best_cfg.blocks && c.words < best_cfg.words)) {
      best = name;
      best_cfg = c;
    }
  }
  if (best.empty()) {
    throw std::invalid_argument("no Verilated FMPP with at least " + std::to_string(blocks) + " blocks and " +
                                std::to_string(words) + " words is built; built: " + built);
  }
  return make_rtl_bus(best, opt);
}

std::string verilator_version() { return Verilated::productVersion(); }

}  // namespace fmpp::tb
