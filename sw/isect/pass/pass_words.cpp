// A pass's words: shared values by one WRITES, the rest over the bus (see pass_words.h).
#include "sw/isect/pass/pass_words.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sw/isect/pass/layout.h"
#include "sw/isect/pass/pass.h"

namespace fmpp::isect {

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

void PassWords::flush(Device& dev, Program pre, KernelStats* st) {
  // Per word, its most shared value (the lowest of equally shared ones: deterministic).
  std::vector<std::pair<bool, uint32_t>> shared(columns_.size(), {false, 0});
  std::vector<uint32_t> sorted;
  last_writes_ = 0;
  for (size_t i = 0; i < columns_.size(); ++i) {
    sorted.clear();
    for (const auto& v : columns_[i].values) sorted.push_back(v.second);
    std::sort(sorted.begin(), sorted.end());
    size_t best = 0;
    uint32_t mode = 0;
    for (size_t a = 0; a < sorted.size();) {
      size_t e = a;
      while (e < sorted.size() && sorted[e] == sorted[a]) ++e;
      if (e - a > best) {
        best = e - a;
        mode = sorted[a];
      }
      a = e;
    }
    if (best < 2) continue;  // one WRITES would save no bus write
    shared[i] = {true, mode};
    pre.mask(0);
    pre << ins::writes(columns_[i].word, mode, layout::kSel);
    ++last_writes_;
  }
  pre.mask(layout::kDataMask);
  if (pre.size() > 0) push_counted(dev, pre.code(), st);
  last_bus_ = 0;
  for (size_t i = 0; i < columns_.size(); ++i) {
    for (const auto& v : columns_[i].values) {
      if (shared[i].first && v.second == shared[i].second) continue;
      dev.write_word(v.first, columns_[i].word, v.second);
      ++last_bus_;
    }
  }
  columns_.clear();
}

}  // namespace fmpp::isect
