// FMPP sizes and named configurations (see config.h).
#include "fmpp/config.h"

#include <stdexcept>

namespace fmpp {

void Config::validate() const {
  if (blocks < 1 || blocks > map::kMaxBlocks) {
    throw std::invalid_argument("fmpp::Config: blocks = " + std::to_string(blocks) + " outside [1, " +
                                std::to_string(map::kMaxBlocks) + "]");
  }
  if (words < 2 || words > map::kMaxWords || words % 2 != 0) {
    throw std::invalid_argument("fmpp::Config: words = " + std::to_string(words) + " must be even and in [2, " +
                                std::to_string(map::kMaxWords) + "]");
  }
}

unsigned Config::word_shift() const {
  unsigned l = 0;
  while ((1u << l) < words) ++l;
  return 3 + l;
}

std::string Config::str() const { return std::to_string(blocks) + "x" + std::to_string(words); }

Config named_config(const std::string& name) {
  std::string known;
  for (const auto& c : map::kConfigs) {
    if (name == c.name) return Config{c.blocks, c.words};
    known += known.empty() ? c.name : std::string(", ") + c.name;
  }
  throw std::invalid_argument("unknown FMPP configuration '" + name + "' (known: " + known + ")");
}

}  // namespace fmpp
