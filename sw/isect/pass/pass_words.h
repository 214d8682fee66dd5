// The words a pass writes into its blocks, gathered before any is sent: per word, the
// value most blocks share goes out as one WRITES to every selected block; another value
// whose blocks a few cubes of block indices cover exactly (the blocks that agree with a
// key outside a mask: one REF on the index part each) as those REFs and one WRITES; the
// others as one bus write each (docs/intersection.md, "Loading a pass").
//
// A ray of a shared-origin form has one direction component equal to +-2^vbits (its
// largest), and the rays of a coherent pass mostly share it: primary rays all look down
// one axis. So do most blocks' hint words (none). And where a pass's rays come from a
// grid of pixels laid out in Z-order (cull/order.h), each column of pixels shares one
// component and each row another, and each fills a cube of indices. One instruction or a
// few then replace up to one bus write per block; the words each block ends up holding
// are the same.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// A cube of block indices: the blocks whose index agrees with `key` outside `mask`.
struct AddrCube {
  uint32_t key, mask;
};
// Appends to *out cubes that cover the `n` distinct increasing block indices exactly
// (every cube within them, together all of them), splitting at the highest bit where
// they differ until each part fills a cube; false (and *out unfinished) once more than
// `limit` cubes in all would be needed.
bool cover_by_cubes(const uint32_t* blocks, size_t n, size_t limit, std::vector<AddrCube>* out);
// The instructions that write one value into the blocks of `cubes`: a REF per cube, a
// MASKSET where the mask changes, a MASKSET 0 and the WRITES.
size_t cube_writes_cost(const std::vector<AddrCube>& cubes);

class PassWords {
 public:
  // Starts a pass of `count` blocks (0 .. count - 1), every word unset.
  void begin(unsigned count);
  // Block b's word w <- value. Each (b, w) at most once per pass.
  void set(unsigned b, unsigned w, uint32_t value);
  // Pushes `pre` (which must leave SEL = the blocks 0 .. count - 1, as select_below
  // does) followed by one WRITES per word whose most shared value is held by two or more
  // blocks and the REFs and WRITES of the values whose cubes cost fewer clocks than
  // their bus writes (flag layout::kTmp is left changed), then the mask kDataMask; then
  // writes every other value over the bus. The instructions count in *st. Then forgets
  // the pass.
  void flush(Device& dev, Program pre, KernelStats* st);

  // What the last flush did: WRITES pushed, REFs of cubes and bus writes made.
  unsigned last_writes() const { return last_writes_; }
  size_t last_cubes() const { return last_cubes_; }
  size_t last_bus_writes() const { return last_bus_; }

 private:
  struct Column {
    unsigned word = 0;
    std::vector<std::pair<unsigned, uint32_t>> values;  // (block, value)
  };
  Column& column(unsigned w);
  void plan_column(Column& c, Program& pre, std::vector<char>* bus);

  unsigned count_ = 0;
  std::vector<Column> columns_;
  unsigned last_writes_ = 0;
  size_t last_bus_ = 0, last_cubes_ = 0;
};

}  // namespace fmpp::isect
