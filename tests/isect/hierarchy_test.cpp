// The culling hierarchy's structure (sw/isect/geometry/hierarchy.h): every non-empty item
// in exactly one leaf, each node's box and slack exactly those of the items below it,
// leaves of at most leaf_items items, and median splits (the two halves of a node differ
// by at most one item), on random boxes, on boxes with equal centres, and with empty ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

#include "sw/isect/cull/cull_bounds.h"
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

// median: the halves of every inner node differ by at most one item (a built hierarchy;
// not a subset of one).
void check_nodes(const Bvh& bvh, const std::vector<Box>& boxes, const std::vector<double>& slack,
                 unsigned leaf_items, bool median = true) {
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
      if (median) {
        EXPECT_LE(r.size() - l.size(), 1u) << "node " << id << " splits " << l.size() << " / " << r.size();
      }
    }
  }
}

void check(const std::vector<Box>& boxes, const std::vector<double>& slack, unsigned leaf_items) {
  check_nodes(Bvh(boxes, slack, leaf_items), boxes, slack, leaf_items);
}

void expect_same(const Bvh& a, const Bvh& b) {
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  ASSERT_EQ(a.items(), b.items());
  for (size_t i = 0; i < a.items(); ++i) ASSERT_EQ(a.item(i), b.item(i)) << "leaf item " << i;
  for (size_t id = 0; id < a.nodes().size(); ++id) {
    const Bvh::Node &x = a.nodes()[id], &y = b.nodes()[id];
    EXPECT_EQ(x.first, y.first) << "node " << id;
    EXPECT_EQ(x.count, y.count) << "node " << id;
    EXPECT_EQ(x.box.lo, y.box.lo) << "node " << id;
    EXPECT_EQ(x.box.hi, y.box.hi) << "node " << id;
    EXPECT_EQ(x.slack, y.slack) << "node " << id;
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

// Culling's hierarchies are built once over the triangles' own boxes and refitted to each
// form's padded boxes (cull_bounds.h): the refit has the same nodes and leaves, and every
// node's box and slack are exactly those of its items' new boxes.
TEST(Hierarchy, RefitKeepsTheShapeAndTakesTheNewBoxes) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (size_t count : {1u, 7u, 2500u}) {
    std::vector<Box> own(count), padded(count);
    std::vector<double> slack(count);
    for (size_t i = 0; i < count; ++i) {
      const glm::dvec3 p(u(g), u(g), u(g));
      own[i].grow(p);
      own[i].grow(p + 0.02 * glm::dvec3(u(g) + 1, u(g) + 1, u(g) + 1));
      const double pad = i % 5 == 0 ? 0.5 : 1e-6 * (u(g) + 1);  // a few boxes padded far
      padded[i] = own[i];
      padded[i].lo -= glm::dvec3(pad);
      padded[i].hi += glm::dvec3(pad);
      slack[i] = 1e-3 * (u(g) + 1);
    }
    for (unsigned leaf : {1u, 4u}) {
      const Bvh shape(own, {}, leaf);
      expect_same(shape.refit(own, slack), Bvh(own, slack, leaf));  // the same boxes: the same hierarchy
      const Bvh fitted = shape.refit(padded, slack);
      check_nodes(fitted, padded, slack, leaf);
      ASSERT_EQ(fitted.nodes().size(), shape.nodes().size());
      for (size_t i = 0; i < fitted.items(); ++i) EXPECT_EQ(fitted.item(i), shape.item(i));
    }
  }
  // An item of the shape without a box cannot be refitted.
  std::vector<Box> boxes(3);
  for (Box& b : boxes) b.grow(glm::dvec3(u(g), u(g), u(g)));
  const Bvh shape(boxes);
  boxes[1] = Box{};
  EXPECT_THROW(shape.refit(boxes), std::invalid_argument);
  EXPECT_THROW(shape.refit(std::vector<Box>(2, boxes[0])), std::invalid_argument);
}

// A form's hierarchy is a subset of the triangles' shape: exactly the kept items, under
// their new numbers, every node's box and slack those of its items, no node without one.
TEST(Hierarchy, SubsetKeepsExactlyTheKeptItems) {
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (size_t count : {1u, 2u, 9u, 3000u}) {
    std::vector<Box> own(count);
    for (Box& b : own) {
      const glm::dvec3 p(u(g), u(g), u(g));
      b.grow(p);
      b.grow(p + 0.01 * glm::dvec3(u(g) + 1, u(g) + 1, u(g) + 1));
    }
    for (unsigned leaf : {1u, 4u}) {
      const Bvh shape(own, {}, leaf);
      for (double share : {0.0, 0.05, 0.5, 0.97, 1.0}) {
        std::vector<int> keep(count, -1);
        std::vector<size_t> kept;
        for (size_t i = 0; i < count; ++i) {
          if (u(g) < 2 * share - 1 || share == 1) kept.push_back(i);
        }
        std::shuffle(kept.begin(), kept.end(), g);  // new numbers in another order
        std::vector<Box> boxes(kept.size());
        std::vector<double> slack(kept.size());
        for (size_t k = 0; k < kept.size(); ++k) {
          keep[kept[k]] = static_cast<int>(k);
          boxes[k] = own[kept[k]];
          boxes[k].lo -= glm::dvec3(1e-3 * (u(g) + 1));
          slack[k] = 1e-4 * (u(g) + 1);
        }
        const Bvh sub = shape.subset(keep, boxes, slack);
        if (kept.empty()) {
          EXPECT_TRUE(sub.nodes().empty());
          continue;
        }
        check_nodes(sub, boxes, slack, leaf, share == 1);
        for (const Bvh::Node& n : sub.nodes()) EXPECT_TRUE(n.count > 0 || n.first > 0);
      }
    }
  }
  std::vector<Box> boxes(3);
  for (Box& b : boxes) b.grow(glm::dvec3(u(g), u(g), u(g)));
  const Bvh shape(boxes);
  EXPECT_THROW(shape.subset({0, 0, -1}, boxes), std::invalid_argument);  // two items become one
  EXPECT_THROW(shape.subset({0, 1}, boxes), std::invalid_argument);      // no entry for item 2
  EXPECT_THROW(shape.subset({0, 1, 5}, boxes), std::invalid_argument);   // no box for item 5
}

TEST(Hierarchy, TheTrianglesShapeIsBuiltOncePerLeafSize) {
  std::mt19937_64 g(9);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris(400);
  for (Triangle& t : tris) {
    for (glm::dvec3& p : t.p) p = glm::dvec3(u(g), u(g), u(g));
  }
  BvhShapes shapes;
  expect_same(shapes.shape(tris, 1), triangle_shape(tris, 1));
  expect_same(shapes.shape(tris, 4), triangle_shape(tris, 4));
  // Scaled by a power of two: no split moves (the kept boxes are the first call's).
  std::vector<Triangle> scaled = tris;
  for (Triangle& t : scaled) {
    for (glm::dvec3& p : t.p) p *= 0x1p-40;
  }
  std::vector<Box> own;
  for (const Triangle& t : scaled) own.push_back(padded_box(t, 0));
  expect_same(shapes.shape(scaled, 1).refit(own), triangle_shape(scaled, 1));
  EXPECT_EQ(shapes.built(), 2u);
  EXPECT_EQ(shapes.reused(), 1u);
  // A shape built in one phase (the plan) and found in a later one (the frame) is work
  // handed on, counted once.
  EXPECT_EQ(shapes.carried_seconds(), 0);
  shapes.set_phase(1);
  shapes.shape(tris, 4);
  const double carried = shapes.carried_seconds();
  EXPECT_GT(carried, 0);
  shapes.shape(tris, 4);
  shapes.shape(tris, 8);  // built in this phase: not carried
  shapes.set_phase(2);
  shapes.shape(tris, 4);
  EXPECT_EQ(shapes.carried_seconds(), carried);
  tris.pop_back();
  EXPECT_THROW(shapes.shape(tris, 1), std::logic_error);  // other triangles: not these shapes
}

// The shapes keep the last subsets' nodes and leaves by their keep: a kept one is only
// fitted again, and gives the hierarchy a new subset would, for every keep and boxes.
TEST(Hierarchy, KeptSubsetLayoutsGiveTheSameHierarchy) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris(300);
  for (Triangle& t : tris) {
    for (glm::dvec3& p : t.p) p = glm::dvec3(u(g), u(g), u(g));
  }
  // Keeps leaving out every m-th triangle (m = 0: none), renumbered in order.
  const auto keep_of = [&](size_t m) {
    std::vector<int> keep(tris.size(), -1);
    int next = 0;
    for (size_t k = 0; k < tris.size(); ++k) {
      if (m == 0 || k % m != 0) keep[k] = next++;
    }
    return std::make_pair(keep, static_cast<size_t>(next));
  };
  BvhShapes shapes;
  for (int round = 0; round < 3; ++round) {
    for (size_t m : {0, 2, 3, 5, 7, 11, 2, 0}) {  // more keeps than are kept, and repeats
      const auto [keep, kept] = keep_of(m);
      std::vector<Box> boxes(kept);
      std::vector<double> slack(kept);
      for (size_t k = 0; k < tris.size(); ++k) {
        if (keep[k] < 0) continue;
        boxes[static_cast<size_t>(keep[k])] = padded_box(tris[k], 0.01 * (round + 1) * std::abs(u(g)));
        slack[static_cast<size_t>(keep[k])] = 0.001 * round * (1 + u(g));
      }
      for (unsigned leaf : {1u, 4u}) {
        expect_same(shapes.subset(tris, leaf, keep, boxes, slack), triangle_shape(tris, leaf).subset(keep, boxes, slack));
      }
    }
  }
}

}  // namespace
}  // namespace fmpp::isect
