// A pass's words: shared values by WRITES, the rest over the bus (see pass_words.h).
#include "sw/isect/pass/pass_words.h"

#include <algorithm>
#include <bitset>
#include <stdexcept>
#include <string>

#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"

namespace fmpp::isect {

bool cover_by_cubes(const uint32_t* blocks, size_t n, size_t limit, std::vector<AddrCube>* out) {
  if (n == 0) return true;
  uint32_t all = ~0u, any = 0;
  for (size_t i = 0; i < n; ++i) all &= blocks[i], any |= blocks[i];
  const uint32_t vary = all ^ any;
  const size_t free_bits = std::bitset<32>(vary).count();
  if (free_bits < 32 && n == (size_t{1} << free_bits)) {  // n distinct blocks fill the cube
    if (out->size() >= limit) return false;
    out->push_back({all, vary});
    return true;
  }
  // Above its highest varying bit every block agrees, so in increasing order the blocks
  // with that bit 0 come first.
  uint32_t top = vary;
  while (top & (top - 1)) top &= top - 1;
  const size_t split = static_cast<size_t>(
      std::partition_point(blocks, blocks + n, [&](uint32_t b) { return (b & top) == 0; }) - blocks);
  return cover_by_cubes(blocks, split, limit, out) && cover_by_cubes(blocks + split, n - split, limit, out);
}

size_t cube_writes_cost(const std::vector<AddrCube>& cubes) {
  size_t cost = 2;  // the WRITES and the MASKSET 0 before it (counted even where not needed)
  uint32_t mask = 0;
  for (const AddrCube& c : cubes) {
    cost += 1 + (c.mask != mask ? 1 : 0);
    mask = c.mask;
  }
  return cost;
}

void PassWords::begin(unsigned count) {
  count_ = count;
  columns_.clear();
}

PassWords::Column& PassWords::column(unsigned w) {
  for (Column& c : columns_) {
    if (c.word == w) return c;
  }
  columns_.push_back(Column{w, {}});
  columns_.back().values.reserve(count_);
  return columns_.back();
}

void PassWords::set(unsigned b, unsigned w, uint32_t value) {
  if (b >= count_) {
    throw std::out_of_range("PassWords::set: block " + std::to_string(b) + " of a pass of " + std::to_string(count_));
  }
  column(w).values.emplace_back(b, value);
}

// One column's values: the most shared (the lowest of equally shared ones: deterministic)
// by one WRITES to every selected block, each other value held by blocks that a few
// cubes of block indices cover exactly by REF on the index and a WRITES under kTmp,
// the rest marked for the bus (bus[i]: the column's i-th value goes over the bus).
void PassWords::plan_column(Column& c, Program& pre, std::vector<char>* bus) {
  auto& v = c.values;
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second < b.second : a.first < b.first;
  });
  bus->assign(v.size(), 1);
  // The end of the run of equal values that starts at a.
  const auto run_end = [&](size_t a) {
    size_t e = a;
    while (e < v.size() && v[e].second == v[a].second) ++e;
    return e;
  };
  size_t mode_at = 0, mode_n = 0;
  for (size_t a = 0, e; a < v.size(); a = e) {
    e = run_end(a);
    if (e - a > mode_n) mode_at = a, mode_n = e - a;
  }
  if (mode_n >= 2) {  // one WRITES would save no bus write for a value of one block
    pre.mask(0);
    pre << ins::writes(c.word, v[mode_at].second, layout::kSel);
    ++last_writes_;
    std::fill(bus->begin() + static_cast<long>(mode_at), bus->begin() + static_cast<long>(mode_at + mode_n), 0);
  }
  std::vector<uint32_t> blocks;
  std::vector<AddrCube> cubes;
  for (size_t a = 0, e; a < v.size(); a = e) {
    e = run_end(a);
    if (a == mode_at || e - a < 4) continue;  // four blocks at least to beat the bus
    blocks.clear();
    for (size_t i = a; i < e; ++i) blocks.push_back(v[i].first);
    cubes.clear();
    if (!cover_by_cubes(blocks.data(), blocks.size(), blocks.size(), &cubes) ||
        cube_writes_cost(cubes) >= blocks.size()) {
      continue;
    }
    std::stable_sort(cubes.begin(), cubes.end(), [](const AddrCube& x, const AddrCube& y) { return x.mask < y.mask; });
    for (size_t i = 0; i < cubes.size(); ++i) {
      pre.mask(cubes[i].mask);
      pre << ins::ref(i == 0 ? RefFn::kThrough : RefFn::kOr, RefPart::kAddr, 0, cubes[i].key, layout::kTmp,
                      layout::kTmp);
    }
    pre.mask(0);
    pre << ins::writes(c.word, v[a].second, layout::kTmp);
    ++last_writes_;
    last_cubes_ += cubes.size();
    std::fill(bus->begin() + static_cast<long>(a), bus->begin() + static_cast<long>(e), 0);
  }
}

void PassWords::flush(Device& dev, Program pre, KernelStats* st) {
  last_writes_ = 0;
  last_cubes_ = 0;
  std::vector<std::vector<char>> bus(columns_.size());
  for (size_t i = 0; i < columns_.size(); ++i) plan_column(columns_[i], pre, &bus[i]);
  pre.mask(layout::kDataMask);
  if (pre.size() > 0) push_counted(dev, pre.code(), st);
  last_bus_ = 0;
  for (size_t i = 0; i < columns_.size(); ++i) {
    for (size_t j = 0; j < columns_[i].values.size(); ++j) {
      if (!bus[i][j]) continue;
      dev.write_word(columns_[i].values[j].first, columns_[i].word, columns_[i].values[j].second);
      ++last_bus_;
    }
  }
  columns_.clear();
}

}  // namespace fmpp::isect
