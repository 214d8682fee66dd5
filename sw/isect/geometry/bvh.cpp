// The bounding volume hierarchy of culling (see hierarchy.h: Bvh): its build, subsets,
// refits and the packets' walk.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sw/isect/geometry/hierarchy.h"

namespace fmpp::isect {

Bvh::Bvh(const std::vector<Box>& boxes, const std::vector<double>& slack, unsigned leaf_items)
    : leaf_items_(std::max(1u, leaf_items)) {
  std::vector<Entry> items;
  for (size_t i = 0; i < boxes.size(); ++i) {
    if (boxes[i].empty()) continue;
    items.push_back({0.5 * boxes[i].lo + 0.5 * boxes[i].hi, static_cast<uint32_t>(i)});
  }
  if (items.empty()) return;
  nodes_.reserve(4 * items.size() / leaf_items_ + 2);  // leaves hold at least half of leaf_items_
  items_.reserve(items.size());
  nodes_.emplace_back();
  build(0, items, 0, items.size());
  fit(boxes, slack);
}

// Fills node `self` with the subtree of items[begin, end) (its shape; fit() gives the
// boxes); an inner node's children are appended as a pair. Every split halves the items,
// so the depth stays below 40.
void Bvh::build(uint32_t self, std::vector<Entry>& items, size_t begin, size_t end) {
  if (end - begin <= leaf_items_) {
    for (size_t i = begin; i < end; ++i) items_.push_back(items[i].id);
    nodes_[self].first = static_cast<uint32_t>(items_.size() - (end - begin));
    nodes_[self].count = static_cast<uint32_t>(end - begin);
    return;
  }
  Box cb;
  for (size_t i = begin; i < end; ++i) cb.grow(items[i].centre);
  const glm::dvec3 span = cb.hi - cb.lo;
  const int axis = span.x >= span.y && span.x >= span.z ? 0 : span.y >= span.z ? 1 : 2;
  const size_t mid = begin + (end - begin) / 2;
  // Ties broken by the index: a total order, so the halves do not depend on the order
  // the items come in.
  std::nth_element(items.begin() + static_cast<std::ptrdiff_t>(begin),
                   items.begin() + static_cast<std::ptrdiff_t>(mid), items.begin() + static_cast<std::ptrdiff_t>(end),
                   [axis](const Entry& a, const Entry& b) {
                     return a.centre[axis] < b.centre[axis] || (a.centre[axis] == b.centre[axis] && a.id < b.id);
                   });
  const uint32_t left = static_cast<uint32_t>(nodes_.size());
  nodes_[self].first = left;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build(left, items, begin, mid);
  build(left + 1, items, mid, end);
}

Bvh Bvh::subset(const std::vector<int>& keep, const std::vector<Box>& boxes, const std::vector<double>& slack) const {
  for (uint32_t item : items_) {
    if (item >= keep.size()) throw std::invalid_argument("fmpp::isect::Bvh::subset: no entry for item " + std::to_string(item));
  }
  Bvh out;
  out.leaf_items_ = leaf_items_;
  if (nodes_.empty()) return out;
  // Which nodes keep an item (children come after their parent).
  std::vector<char> alive(nodes_.size(), 0);
  std::vector<char> used(boxes.size(), 0);
  for (size_t id = nodes_.size(); id-- > 0;) {
    const Node& n = nodes_[id];
    if (n.count == 0) {
      alive[id] = alive[n.first] | alive[n.first + 1];
      continue;
    }
    for (uint32_t i = n.first; i < n.first + n.count; ++i) {
      const int k = keep[items_[i]];
      if (k < 0) continue;
      const auto item = static_cast<size_t>(k);
      if (item >= boxes.size() || boxes[item].empty()) {
        throw std::invalid_argument("fmpp::isect::Bvh::subset: item " + std::to_string(item) + " has no box");
      }
      if (used[item]) throw std::invalid_argument("fmpp::isect::Bvh::subset: two items become item " +
                                                  std::to_string(item));
      used[item] = 1;
      alive[id] = 1;
    }
  }
  if (!alive[0]) return out;
  out.nodes_.reserve(nodes_.size());
  out.items_.reserve(items_.size());
  out.nodes_.emplace_back();
  out.take(*this, 0, 0, keep, alive);
  out.fit(boxes, slack);
  return out;
}

// A node's box and slack are its children's, joined after theirs (children come after
// their parent): the same values as over its items (min and max are exact), each item's
// read once rather than once per level.
void Bvh::fit(const std::vector<Box>& boxes, const std::vector<double>& slack) {
  for (size_t id = nodes_.size(); id-- > 0;) {
    Node& n = nodes_[id];
    Box box;
    double most = 0;
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        box.grow(boxes[items_[i]]);
        if (!slack.empty()) most = std::max(most, slack[items_[i]]);
      }
    } else {
      box = nodes_[n.first].box;
      box.grow(nodes_[n.first + 1].box);
      most = std::max(nodes_[n.first].slack, nodes_[n.first + 1].slack);
    }
    n.box = box;
    n.slack = most;
  }
}

// The nodes are laid out as build() lays them out: a pair of children appended, then the
// first child's subtree, then the second's; so a subset of every item is a copy.
void Bvh::take(const Bvh& src, uint32_t from, uint32_t self, const std::vector<int>& keep,
               const std::vector<char>& alive) {
  const Node& n = src.nodes_[from];
  if (n.count > 0) {
    nodes_[self].first = static_cast<uint32_t>(items_.size());
    for (uint32_t i = n.first; i < n.first + n.count; ++i) {
      if (keep[src.items_[i]] >= 0) items_.push_back(static_cast<uint32_t>(keep[src.items_[i]]));
    }
    nodes_[self].count = static_cast<uint32_t>(items_.size() - nodes_[self].first);
    return;
  }
  if (!alive[n.first] || !alive[n.first + 1]) {  // one child left: it takes the node's place
    take(src, alive[n.first] ? n.first : n.first + 1, self, keep, alive);
    return;
  }
  const auto left = static_cast<uint32_t>(nodes_.size());
  nodes_[self].first = left;
  nodes_[self].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  take(src, n.first, left, keep, alive);
  take(src, n.first + 1, left + 1, keep, alive);
}

Bvh Bvh::refit(const std::vector<Box>& boxes, const std::vector<double>& slack) const {
  for (uint32_t item : items_) {
    if (item >= boxes.size() || boxes[item].empty()) {
      throw std::invalid_argument("fmpp::isect::Bvh::refit: item " + std::to_string(item) + " has no box");
    }
  }
  // A subset of every item is a copy (take): the same nodes and items, fitted again.
  Bvh out = *this;
  out.fit(boxes, slack);
  return out;
}

void Bvh::reached(const std::vector<RayPacket>& packets, std::vector<char>& reach, uint64_t* tests,
                  const std::vector<PlaneSlab>* planes) const {
  if (nodes_.empty() || packets.empty()) return;
  // Depth-first; each entry carries the packets that entered its parent.
  struct Entry {
    uint32_t node;
    std::vector<uint32_t> live;
  };
  std::vector<Entry> stack;
  std::vector<uint32_t> all(packets.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<uint32_t>(i);
  stack.push_back({0, std::move(all)});
  uint64_t n_tests = 0;
  while (!stack.empty()) {
    Entry e = std::move(stack.back());
    stack.pop_back();
    const Node& n = nodes_[e.node];
    std::vector<uint32_t> live;
    for (uint32_t p : e.live) {
      ++n_tests;
      if (enters(packets[p], n)) live.push_back(p);
    }
    if (live.empty()) continue;
    if (n.count > 0 && planes != nullptr) {
      // Each item only for a packet that may cross its plane within the leaf's box (the
      // packet's reach stretched by the leaf's slack, as enters() stretches it).
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        for (uint32_t p : live) {
          ++n_tests;
          RayPacket q = packets[p];
          q.t1 *= 1 + n.slack;
          if (may_cross(q, n.box, (*planes)[items_[i]])) {
            reach[items_[i]] = 1;
            break;
          }
        }
      }
    } else if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) reach[items_[i]] = 1;
    } else {
      stack.push_back({n.first + 1, live});
      stack.push_back({n.first, std::move(live)});
    }
  }
  if (tests) *tests += n_tests;
}

}  // namespace fmpp::isect
