// Culling's geometry (see hierarchy.h): packets of rays, their tests against boxes and
// triangles' planes, padded boxes; the hierarchy itself is in bvh.cpp.
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

}  // namespace fmpp::isect
