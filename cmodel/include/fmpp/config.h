// The size of an FMPP (blocks and words per block, as the CONFIG register reports it),
// the named configurations of rtl/fmpp_map.json, and what the responder registers
// hold: the types every layer shares, from the golden model to the host driver.
#pragma once

#include <cstdint>
#include <string>

#include "fmpp/map.h"

namespace fmpp {

struct Config {
  unsigned blocks = 64;  // NumBlocks, 1 .. map::kMaxBlocks
  unsigned words = 32;   // NumWords, even, 2 .. map::kMaxWords

  // Throws std::invalid_argument naming the bad value.
  void validate() const;
  unsigned tiles() const { return (blocks + map::kLaneW - 1) / map::kLaneW; }
  // log2 of the WORDS window block stride in bytes.
  unsigned word_shift() const;
  std::string str() const;
};

// Looks up a named configuration of rtl/fmpp_map.json ("small", "large", ...).
// Throws std::invalid_argument listing the known names.
Config named_config(const std::string& name);

struct Responders {
  bool any = false;
  uint32_t count = 0;
  uint32_t first = 0;  // lowest selected block; 0 when none
};

}  // namespace fmpp
