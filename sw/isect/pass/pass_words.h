// The words a pass writes into its blocks, gathered before any is sent: per word, the
// value most blocks share goes out as one WRITES to every selected block, the others
// as one bus write each (docs/intersection.md, "Loading a pass").
//
// A ray of a shared-origin form has one direction component equal to +-2^vbits (its
// largest), and the rays of a coherent pass mostly share it: primary rays all look down
// one axis. So do most blocks' hint words (none). One instruction then replaces up to
// one bus write per block; the words each block ends up holding are the same.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

class PassWords {
 public:
  // Starts a pass of `count` blocks (0 .. count - 1), every word unset.
  void begin(unsigned count);
  // Block b's word w <- value. Each (b, w) at most once per pass.
  void set(unsigned b, unsigned w, uint32_t value);
  // Pushes `pre` (which must leave SEL = the blocks 0 .. count - 1 and the mask at
  // kDataMask, as select_below and the passes' init do) followed by one WRITES per word
  // whose most shared value is held by two or more blocks, then writes every other value
  // over the bus; the instructions count in *st. Then forgets the pass.
  void flush(Device& dev, Program pre, KernelStats* st);

  // What the last flush did: WRITES pushed and bus writes made (for the tests).
  unsigned last_writes() const { return last_writes_; }
  size_t last_bus_writes() const { return last_bus_; }

 private:
  struct Column {
    unsigned word = 0;
    std::vector<std::pair<unsigned, uint32_t>> values;  // (block, value)
  };
  Column& column(unsigned w);

  unsigned count_ = 0;
  std::vector<Column> columns_;
  unsigned last_writes_ = 0;
  size_t last_bus_ = 0;
};

}  // namespace fmpp::isect
