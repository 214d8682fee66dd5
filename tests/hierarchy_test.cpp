// The culling hierarchy's structure (sw/isect/geometry/hierarchy.h): every non-empty item
// in exactly one leaf, each node's box and slack exactly those of the items below it,
// leaves of at most leaf_items items, and median splits (the two halves of a node differ
// by at most one item), on random boxes, on boxes with equal centres, and with empty ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "sw/isect/geometry/hierarchy.h"

namespace fmpp::isect {
namespace {

// Items below node `id`, appended to `out`.
void items_below(const Bvh& bvh, uint32_t id, std::vector<uint32_t>& out) {
  const Bvh::Node& n = bvh.nodes()[id];
  if (n.count > 0) {
    for (uint32_t i = n.first; i < n.first + n.count; ++i) out.push_back(bvh.item(i));
    return;
  }
  items_below(bvh, n.first, out);
  items_below(bvh, n.first + 1, out);
}

void check(const std::vector<Box>& boxes, const std::vector<double>& slack, unsigned leaf_items) {
  const Bvh bvh(boxes, slack, leaf_items);
  size_t live = 0;
  for (const Box& b : boxes) live += !b.empty();
  ASSERT_EQ(bvh.items(), live);
  std::vector<uint32_t> all;
  items_below(bvh, 0, all);
  std::sort(all.begin(), all.end());
  ASSERT_EQ(all.size(), live);
  for (size_t i = 0; i + 1 < all.size(); ++i) ASSERT_NE(all[i], all[i + 1]) << "item " << all[i] << " twice";
  for (uint32_t it : all) ASSERT_FALSE(boxes[it].empty()) << "empty item " << it << " kept";
  for (uint32_t id = 0; id < bvh.nodes().size(); ++id) {
    const Bvh::Node& n = bvh.nodes()[id];
    std::vector<uint32_t> below;
    items_below(bvh, id, below);
    Box want;
    double most = 0;
    for (uint32_t it : below) {
      want.grow(boxes[it]);
      if (!slack.empty()) most = std::max(most, slack[it]);
    }
    EXPECT_EQ(n.box.lo, want.lo) << "node " << id;
    EXPECT_EQ(n.box.hi, want.hi) << "node " << id;
    EXPECT_EQ(n.slack, most) << "node " << id;
    if (n.count > 0) {
      EXPECT_LE(n.count, leaf_items) << "leaf " << id;
    } else {
      std::vector<uint32_t> l, r;
      items_below(bvh, n.first, l);
      items_below(bvh, n.first + 1, r);
      EXPECT_LE(r.size() - l.size(), 1u) << "node " << id << " splits " << l.size() << " / " << r.size();
    }
  }
}

TEST(Hierarchy, NodesHoldExactlyTheirItemsBoxesAndSlack) {
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (size_t count : {1u, 2u, 5u, 100u, 3000u}) {
    std::vector<Box> boxes(count);
    std::vector<double> slack(count);
    for (size_t i = 0; i < count; ++i) {
      const glm::dvec3 p(u(g), u(g), u(g));
      boxes[i].grow(p);
      boxes[i].grow(p + 0.01 * glm::dvec3(u(g) + 1, u(g) + 1, u(g) + 1));
      slack[i] = 1e-3 * (u(g) + 1);
    }
    for (unsigned leaf : {1u, 4u, 8u}) {
      check(boxes, {}, leaf);
      check(boxes, slack, leaf);
    }
  }
}

TEST(Hierarchy, EqualCentresAndEmptyItems) {
  std::mt19937_64 g(11);
  std::uniform_int_distribution<int> cell(0, 3);
  std::vector<Box> boxes(2000);
  for (size_t i = 0; i < boxes.size(); ++i) {
    if (i % 13 == 0) continue;  // empty: left out
    const glm::dvec3 c(cell(g), cell(g), 0.5);  // 16 distinct centres for 1,846 items
    boxes[i].grow(c - glm::dvec3(0.1 * static_cast<double>(i % 3)));
    boxes[i].grow(c + glm::dvec3(0.1 * static_cast<double>(i % 3)));
  }
  for (unsigned leaf : {1u, 4u}) check(boxes, {}, leaf);
  // Every box empty: no node at all.
  EXPECT_TRUE(Bvh(std::vector<Box>(5)).nodes().empty());
}

}  // namespace
}  // namespace fmpp::isect
