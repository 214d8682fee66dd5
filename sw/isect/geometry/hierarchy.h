// Culling for the ray-parallel mapping (docs/intersection.md, "Culling"): per pass, only
// the triangles that some ray of the pass may hit are broadcast. The host keeps a
// bounding volume hierarchy over the triangles of a form; a pass's rays are cut into
// packets of consecutive rays (the pass order is coherent, order.h), each bounded by a
// box of origins, a box of unit directions and an interval of distances; a node is
// entered only if some packet may reach its box, and the triangles of the leaves
// reached are broadcast.
//
// Conservative by construction (cull_bounds.h): every triangle's box is padded by a
// bound on how far outside the triangle the form's fixed point can report a hit (per
// triangle, from its condition), the direction boxes by the rounding of the rays' own
// data, and the broadcasts that remain keep their order: results equal those without
// culling, ties included.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "sw/isect/geometry/geometry.h"

namespace fmpp::isect {

struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void grow(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  bool contains(const glm::dvec3& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
};

// Rays bounded together: o + t d with o in `o`, d a unit vector in `d`, t in [t0, t1].
struct RayPacket {
  Box o, d;
  double t0 = 0;
  double t1 = std::numeric_limits<double>::infinity();
};

// The packets of rays[order[begin..end)], `size` consecutive rays each. Directions are
// normalized (t in units of length); each direction box is widened by `margin` radians
// (clamped to [-1, 1]) and each t1 by the factor 1 + margin; t0 is 0 (no hit is culled
// for lying just before a ray's tmin).
std::vector<RayPacket> make_packets(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin,
                                    size_t end, size_t size, double margin);
// The packet of one ray, as make_packets makes it (without its vectors).
RayPacket ray_packet(const Ray& r, double margin);

// False only if no point o + t d of the packet (o, d in their boxes, t in [t0, t1])
// lies in the box. Interval arithmetic per axis, so a packet may pass that no single
// ray of it would: conservative.
bool may_enter(const RayPacket& p, const Box& b);
// The smallest t in [t0, t1] at which a point of the packet may lie in the box (the same
// interval arithmetic), or +infinity where may_enter is false.
double entry_distance(const RayPacket& p, const Box& b);

// A triangle's plane as culling bounds it: n (as computed, taken as exact) and [lo, hi],
// within which n . x lies for every point x of the triangle (the products' rounding
// allowed for). lo > hi: no slab (nothing is cut by it).
struct PlaneSlab {
  glm::dvec3 n{0};
  double lo = 1, hi = 0;
};
PlaneSlab plane_slab(const Triangle& t);
// False only if no ray of the packet crosses the slab (n . x in [lo, hi]) while inside
// box b at some t in [t0, t1]: each ray's n . (o + t d) is linear in t, so one that is
// above the slab (or below) where it enters the box and where it leaves has no point of
// the triangle there. Interval arithmetic over the packet, with a relative slack of
// 1e-9 for the roundings: conservative.
bool may_cross(const RayPacket& p, const Box& b, const PlaneSlab& s);

// A bounding volume hierarchy over items (each an index with a box), median split on
// the longest axis of the centroids, up to leaf_items items per leaf (kLeafItems unless
// told).
class Bvh {
 public:
  static constexpr unsigned kLeafItems = 4;
  struct Node {
    Box box;
    uint32_t first = 0;  // leaf: items_[first, first + count); inner: children first, first + 1
    uint32_t count = 0;  // 0 for an inner node
    double slack = 0;    // the largest slack of its items
  };

  Bvh() = default;
  // boxes[i] is item i's box (an empty box: the item is left out); slack[i] (empty: all
  // 0) stretches the packets' reach t1 to t1 (1 + slack[i]) for that item: the relative
  // error of the distance the FMPP reports for it.
  explicit Bvh(const std::vector<Box>& boxes, const std::vector<double>& slack = {}, unsigned leaf_items = kLeafItems);

  // The hierarchy of some of the items, in the same shape: item i becomes item keep[i]
  // (-1: left out; no two items may become one), a node left without items is removed
  // and one left with a single child is replaced by it, and each node's box and slack are
  // taken from `boxes` and `slack` (by the new items, as the constructor takes them; every
  // kept item needs a non-empty box). O(nodes), against the constructor's O(items log
  // items): culling's hierarchies are built once over all the triangles' own boxes and
  // taken for each form and batch (cull_bounds.h).
  Bvh subset(const std::vector<int>& keep, const std::vector<Box>& boxes, const std::vector<double>& slack = {}) const;
  // Every item kept as it is: the same nodes and leaves, with new boxes.
  Bvh refit(const std::vector<Box>& boxes, const std::vector<double>& slack = {}) const;

  // Sets reach[i] for every item of every leaf that some packet may enter (reach must
  // have one entry per item); adds the node-packet tests made to *tests.
  // planes (if given, one per item): an item of a leaf is reached only by a packet that
  // may cross its plane inside the leaf's box (may_cross), each such test counted too.
  void reached(const std::vector<RayPacket>& packets, std::vector<char>& reach, uint64_t* tests,
               const std::vector<PlaneSlab>* planes = nullptr) const;
  // Calls f(item) for every item of every leaf the packet may enter.
  template <class F>
  void visit(const RayPacket& p, F&& f) const;
  // Visits the leaves the packet may enter, the nearer child first, calling
  // leaf(items, count, entry distance) until it returns true.
  template <class F>
  void visit_near_first(const RayPacket& p, F&& leaf) const;
  // The general walk: nodes in increasing key(node) (+infinity: left out), each popped
  // node kept only if enter(node id) says so (asked in that order, so it may depend on
  // what the leaves before it did), calling leaf(items, count, key) until it returns true.
  template <class Key, class Enter, class Leaf>
  void walk_near_first(Key&& key, Enter&& enter, Leaf&& leaf) const;

  const std::vector<Node>& nodes() const { return nodes_; }
  size_t items() const { return items_.size(); }
  // Item i of the leaves' list (a leaf holds items first .. first + count - 1).
  uint32_t item(size_t i) const { return items_[i]; }
  // Whether packet p may enter node n, its reach stretched by the node's slack.
  static bool enters(const RayPacket& p, const Node& n) {
    if (n.slack == 0) return may_enter(p, n.box);
    RayPacket q = p;
    q.t1 *= 1 + n.slack;
    return may_enter(q, n.box);
  }

 private:
  // An item during the build: its centre beside its index, so that the splits read
  // memory in order rather than through the index.
  struct Entry {
    glm::dvec3 centre;
    uint32_t id;
  };
  void build(uint32_t self, std::vector<Entry>& items, size_t begin, size_t end);
  // Every node's box and slack from its items' `boxes` and `slack`.
  void fit(const std::vector<Box>& boxes, const std::vector<double>& slack);
  // subset(): node `from` of `src` (which has kept items) into node `self` of this one.
  void take(const Bvh& src, uint32_t from, uint32_t self, const std::vector<int>& keep, const std::vector<char>& alive);
  std::vector<Node> nodes_;
  std::vector<uint32_t> items_;
  unsigned leaf_items_ = kLeafItems;
};

template <class F>
void Bvh::visit(const RayPacket& p, F&& f) const {
  if (nodes_.empty()) return;
  uint32_t stack[128];
  unsigned top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (!enters(p, n)) continue;
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) f(items_[i]);
    } else {
      stack[top++] = n.first;
      stack[top++] = n.first + 1;
    }
  }
}

template <class F>
void Bvh::visit_near_first(const RayPacket& p, F&& leaf) const {
  walk_near_first([&](const Node& n) { return entry_distance(p, n.box); }, [](uint32_t) { return true; },
                  std::forward<F>(leaf));
}

template <class Key, class Enter, class Leaf>
void Bvh::walk_near_first(Key&& key, Enter&& enter, Leaf&& leaf) const {
  if (nodes_.empty()) return;
  // A min-heap on the key (ties: the lower node first): leaves come strictly in order.
  std::vector<std::pair<double, uint32_t>> heap;
  const auto later = [](const std::pair<double, uint32_t>& a, const std::pair<double, uint32_t>& b) {
    return a.first > b.first || (a.first == b.first && a.second > b.second);
  };
  const auto push = [&](uint32_t id) {
    const double k = key(nodes_[id]);
    if (!(k < std::numeric_limits<double>::infinity())) return;
    heap.emplace_back(k, id);
    std::push_heap(heap.begin(), heap.end(), later);
  };
  push(0);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const auto [k, id] = heap.back();
    heap.pop_back();
    if (!enter(id)) continue;
    const Node& n = nodes_[id];
    if (n.count > 0) {
      if (leaf(&items_[n.first], n.count, k)) return;
      continue;
    }
    push(n.first);
    push(n.first + 1);
  }
}

// True only if the ray certainly has no point on the plane of t with tmin <= t < tmax (the
// plane is crossed beyond tmax or before tmin, and the ray is far from parallel to it),
// with a margin far above double's rounding: then no hit of t in the ray's interval
// exists, and culling may leave t out for the ray (Ray::hint).
bool plane_beyond_reach(const Ray& r, const Triangle& t);
// r.hint where plane_beyond_reach proves it (a valid index of tris), else -1.
int proven_hint(const Ray& r, const std::vector<Triangle>& tris);

// The box of triangle t padded by `pad` on every side.
Box padded_box(const Triangle& t, double pad);
// The largest side of the triangle's bounding box.
double extent(const Triangle& t);

}  // namespace fmpp::isect
