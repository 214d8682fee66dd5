// The ray-parallel read-back of a pass's bests, reading only the blocks whose best may
// have changed since the host last knew it (docs/intersection.md, "Reading back").
//
// A block's best changes only where a broadcast wins it, and a win writes that
// broadcast's number (1, 2, ... in the pass) into the block's idx word (BestWords); a
// pass's numbers only grow (a refinement that appends numbers on). So a block whose idx
// word is at most T, where T broadcasts had been sent when the host last knew the block,
// still holds what the host knew: one CMP sets a flag where idx > T, a read of the flag
// plane tells 64 blocks at once, and only the flagged blocks' words are read; the others'
// bests come from what the host knew. After the pass's init every block is known (no
// best, idx 0), so the first read-back reads only the blocks with a best.
//
// The answers are the same as from reading every block: a block is either read, or holds
// words equal to those read before. Only the clocks change (KernelOptions::changed_reads).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/pass/pass.h"

namespace fmpp::isect {

// A tile's flag plane is read where at least this many of its blocks are to be read: one
// plane read costs one bus read, and each block it finds unchanged saves one read (no
// best) or more (the best, its number and the form's certification words).
inline constexpr unsigned kChangedTileBlocks = 2;

// Of `want` (blocks 0 .. count - 1 to read), the ones whose idx word exceeds `known`
// (docs above): flags the blocks by one CMP into layout::kTmp, then reads the planes of
// the tiles with at least kChangedTileBlocks wanted blocks. A block of another tile counts
// as changed (it is read as before).
std::vector<char> changed_blocks(Device& dev, unsigned count, unsigned idx_word, uint32_t known,
                                 const std::vector<char>& want, KernelStats* st);

class BestCache {
 public:
  // What the host knows of a block: its best word, the position of the broadcast that
  // set it in the pass's list, and the form's relative bound on its t.
  struct Entry {
    bool hit = false;
    uint32_t best = 0;
    size_t pos = 0;
    double bound = 0;
  };

  // The pass's blocks after the pass's init: no best, known at 0 broadcasts. `on`: read
  // only the changed blocks (off: every block is read, as without the cache).
  void reset(unsigned count, bool on) {
    known_at_.assign(count, 0);
    entry_.assign(count, Entry{});
    on_ = on;
  }

  // read_best for the blocks `only` names (every block without it), after the broadcasts
  // `sent`: calls on_hit(b, best, pos, bound) for every such block without overflow that
  // has a best, whether read now or known. bound(b, best, pos) is the form's relative
  // bound, asked while the block's words are read.
  template <class Bound, class OnHit>
  std::vector<bool> read(Device& dev, unsigned count, const BestWords& w, size_t sent, Bound&& bound, OnHit&& on_hit,
                         const std::vector<char>* only, KernelStats* st) {
    std::vector<char> want = only ? *only : std::vector<char>(count, 1);
    std::vector<char> fetch = want;
    if (on_) fetch = changed_blocks(dev, count, w.idx_word, oldest(want), want, st);
    for (unsigned b = 0; b < count; ++b) {
      if (fetch[b]) entry_[b] = Entry{};
    }
    const std::vector<bool> ovf = read_best(
        dev, count, w, sent, [&](unsigned b, uint32_t best, size_t pos) { entry_[b] = {true, best, pos, bound(b, best, pos)}; },
        &fetch);
    for (unsigned b = 0; b < count; ++b) {
      if (!want[b] || ovf[b]) continue;
      if (fetch[b]) known_at_[b] = static_cast<uint32_t>(sent);
      if (entry_[b].hit) on_hit(b, entry_[b].best, entry_[b].pos, entry_[b].bound);
    }
    return ovf;
  }

 private:
  // The fewest broadcasts at which some wanted block was last known.
  uint32_t oldest(const std::vector<char>& want) const;

  std::vector<uint32_t> known_at_;
  std::vector<Entry> entry_;
  bool on_ = true;
};

}  // namespace fmpp::isect
