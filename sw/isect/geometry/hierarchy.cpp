// Culling for the ray-parallel mapping (see cull.h).
#include "sw/isect/geometry/hierarchy.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace fmpp::isect {

namespace {

// A packet is grown ray by ray from an empty one (t1 0), then its directions widened by
// the margin: make_packets and ray_packet share these steps, so one ray's packet is the
// same from either.
void add_ray(RayPacket& p, const Ray& r, double margin) {
  const double len = glm::length(r.d);
  p.o.grow(r.o);
  p.d.grow(r.d / len);
  p.t1 = std::max(p.t1, r.tmax * len * (1 + margin));  // inf stays inf
}

void widen(RayPacket& p, double margin) {
  p.d.lo = glm::max(p.d.lo - margin, glm::dvec3(-1));
  p.d.hi = glm::min(p.d.hi + margin, glm::dvec3(1));
}

}  // namespace

std::vector<RayPacket> make_packets(const std::vector<Ray>& rays, const std::vector<size_t>& order, size_t begin,
                                    size_t end, size_t size, double margin) {
  if (size == 0) throw std::invalid_argument("fmpp::isect::make_packets: packet size 0");
  std::vector<RayPacket> out;
  for (size_t b = begin; b < end; b += size) {
    RayPacket p;
    p.t1 = 0;
    for (size_t k = b; k < std::min(end, b + size); ++k) add_ray(p, rays[order[k]], margin);
    widen(p, margin);
    out.push_back(p);
  }
  return out;
}

RayPacket ray_packet(const Ray& r, double margin) {
  RayPacket p;
  p.t1 = 0;
  add_ray(p, r, margin);
  widen(p, margin);
  return p;
}

bool may_enter(const RayPacket& p, const Box& b) { return entry_distance(p, b) < std::numeric_limits<double>::infinity(); }

namespace {

// The packet's interval of t within box b, as entry_distance finds it (before its slack).
void box_interval(const RayPacket& p, const Box& b, double* lo_out, double* hi_out);

}  // namespace

double entry_distance(const RayPacket& p, const Box& b) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo, hi;
  box_interval(p, b, &lo, &hi);
  // The quotients are rounded: a relative slack of 1e-9 keeps a grazing packet in.
  return lo <= hi + 1e-9 * std::abs(hi) ? lo : kInf;
}

namespace {

void box_interval(const RayPacket& p, const Box& b, double* lo_out, double* hi_out) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo = p.t0, hi = p.t1;
  for (int a = 0; a < 3; ++a) {
    // The packet's points at t span [o.lo + t d.lo, o.hi + t d.hi] on this axis (t >= 0).
    const double below = b.hi[a] - p.o.lo[a];  // need t d.lo <= below
    if (p.d.lo[a] > 0) {
      hi = std::min(hi, below / p.d.lo[a]);
    } else if (p.d.lo[a] < 0) {
      lo = std::max(lo, below / p.d.lo[a]);
    } else if (below < 0) {
      *lo_out = kInf, *hi_out = hi;  // this axis alone rules the box out
      return;
    }
    const double above = b.lo[a] - p.o.hi[a];  // need t d.hi >= above
    if (p.d.hi[a] > 0) {
      lo = std::max(lo, above / p.d.hi[a]);
    } else if (p.d.hi[a] < 0) {
      hi = std::min(hi, above / p.d.hi[a]);
    } else if (above > 0) {
      *lo_out = kInf, *hi_out = hi;
      return;
    }
  }
  *lo_out = lo;
  *hi_out = hi;
}

}  // namespace

PlaneSlab plane_slab(const Triangle& t) {
  PlaneSlab s;
  s.n = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, mag = 0;
  for (const glm::dvec3& v : t.p) {
    const double h = glm::dot(s.n, v);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
    mag = std::max(mag, glm::dot(glm::abs(s.n), glm::abs(v)));
  }
  // Each dot product within 3 units of 2^-53 of its terms' magnitudes (taken as 1e-12);
  // a triangle point is a convex combination of the vertices: its n . x lies in [lo, hi].
  s.lo = lo - 1e-12 * mag;
  s.hi = hi + 1e-12 * mag;
  if (!(std::isfinite(s.lo) && std::isfinite(s.hi) && std::isfinite(mag))) return PlaneSlab{};
  return s;
}

bool may_cross(const RayPacket& p, const Box& b, const PlaneSlab& s) {
  if (!(s.lo <= s.hi)) return true;
  double lo, hi;
  box_interval(p, b, &lo, &hi);
  if (!(lo < std::numeric_limits<double>::infinity() && lo <= hi + 1e-9 * std::abs(hi))) {
    return false;  // entry_distance's own verdict: the packet misses the box
  }
  const bool open = !(hi < std::numeric_limits<double>::infinity());  // no end: the sign of n . d decides
  if (open) hi = lo;
  // The quotients' rounding: t anywhere in the widened interval.
  const double w = 1e-9 * (std::abs(lo) + std::abs(hi));
  lo -= w;
  hi += w;
  // n . o and n . d over the packet's boxes (interval arithmetic), and their magnitude.
  double a_lo = 0, a_hi = 0, d_lo = 0, d_hi = 0, mag = std::abs(s.lo) + std::abs(s.hi), dmag = 0;
  const double tmax = std::max(std::abs(lo), std::abs(hi));
  for (int k = 0; k < 3; ++k) {
    const double n = s.n[k];
    a_lo += n * (n >= 0 ? p.o.lo[k] : p.o.hi[k]);
    a_hi += n * (n >= 0 ? p.o.hi[k] : p.o.lo[k]);
    d_lo += n * (n >= 0 ? p.d.lo[k] : p.d.hi[k]);
    d_hi += n * (n >= 0 ? p.d.hi[k] : p.d.lo[k]);
    mag += std::abs(n) * (std::max(std::abs(p.o.lo[k]), std::abs(p.o.hi[k])) +
                          tmax * std::max(std::abs(p.d.lo[k]), std::abs(p.d.hi[k])));
    dmag += std::abs(n) * std::max(std::abs(p.d.lo[k]), std::abs(p.d.hi[k]));
  }
  const double slack = 1e-9 * mag;
  // Over the packet, n . (o + t d) at t lies in [a_lo + t d_lo, a_hi + t d_hi] (t >= 0;
  // the bounds of d swap for t < 0).
  const auto low = [&](double t) { return a_lo + t * (t >= 0 ? d_lo : d_hi); };
  const auto high = [&](double t) { return a_hi + t * (t >= 0 ? d_hi : d_lo); };
  if (open) {  // from lo on, n . (o + t d) only moves away from the slab where n . d does
    if (low(lo) > s.hi + slack && d_lo >= 1e-9 * dmag) return false;
    if (high(lo) < s.lo - slack && d_hi <= -1e-9 * dmag) return false;
    return true;
  }
  if (low(lo) > s.hi + slack && low(hi) > s.hi + slack) return false;    // above the slab throughout
  if (high(lo) < s.lo - slack && high(hi) < s.lo - slack) return false;  // below it throughout
  return true;
}

namespace {

// At least |v| (sqrt(3) max |v_k| <= 2 max |v_k|), with no square to underflow.
double length_bound(const glm::dvec3& v) {
  return 2 * std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
}

}  // namespace

bool plane_beyond_reach(const Ray& r, const Triangle& t) {
  const glm::dvec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0], w = t.p[0] - r.o;
  const glm::dvec3 n = glm::cross(e1, e2);
  const double nd = glm::dot(n, r.d), dl = glm::length(r.d), nl = glm::length(n);
  // Rounding: each component of n is within 2^-50 |e1| |e2| of the exact cross product,
  // each dot product within 2^-50 of its terms' magnitudes; 1e-12 is far above both.
  // Those are relative bounds, for results in double's normal range: a product that
  // underflows loses up to 2^-1075 outright (and eps itself may underflow), so each
  // dot product also gets 8 2^-1074 times (1 + the other factor's length), above the
  // three products' and n's own losses. The lengths are bounded by 2 max |component|,
  // whose squares cannot underflow to 0 as glm::length's do for edges below 2^-537.
  const double eps = 1e-12 * length_bound(e1) * length_bound(e2), wl = length_bound(w);
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double num_err = eps * wl + 8 * tiny * (1 + wl), den_err = eps * dl + 8 * tiny * (1 + dl);
  // Far from parallel (the hit's own angle of incidence is then not tiny either), and the
  // denominator's sign certain.
  if (!(std::abs(nd) >= 1e-6 * nl * dl) || !(std::abs(nd) > 2 * den_err)) return false;
  const double tp = glm::dot(n, w) / nd;
  const double dt = (num_err + std::abs(tp) * den_err) / (std::abs(nd) - den_err) + 1e-12 * std::abs(tp);
  if (!std::isfinite(tp) || !std::isfinite(dt)) return false;
  return tp - dt >= r.tmax || tp + dt < r.tmin;
}

int proven_hint(const Ray& r, const std::vector<Triangle>& tris) {
  if (r.hint < 0 || static_cast<size_t>(r.hint) >= tris.size()) return -1;
  return plane_beyond_reach(r, tris[static_cast<size_t>(r.hint)]) ? r.hint : -1;
}

Box padded_box(const Triangle& t, double pad) {
  Box b;
  for (const glm::dvec3& p : t.p) b.grow(p);
  b.lo -= glm::dvec3(pad);
  b.hi += glm::dvec3(pad);
  return b;
}

double extent(const Triangle& t) {
  Box b;
  for (const glm::dvec3& p : t.p) b.grow(p);
  const glm::dvec3 s = b.hi - b.lo;
  return std::max({s.x, s.y, s.z});
}

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
