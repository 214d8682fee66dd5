// The slope compares of the FMPP's box test (see box_slopes.h).
#include "sw/isect/cull/box_slopes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "sw/isect/cull/tuning.h"
#include "sw/isect/forms/shared_origin_layout.h"

namespace fmpp::isect::slopes {
namespace {

using layout::ray::kPair;
using layout::ray::kV;

constexpr double kInf = std::numeric_limits<double>::infinity();

// The range of unit (a x_j + b x_k) / u over the triangle grown by a cube of half-side e:
// linear-fractional, so over a convex set with u > 0 its extremes lie at the set's
// vertices, the 24 points vertex +- e per axis. False where the set reaches u <= 0.
bool linear_range(const Triangle& tri, double e, const ClassAxes& ax, double a, double b, double* lo, double* hi) {
  const int i = ax.i, j = ax.j(), k = ax.k();
  double mn = kInf, mx = -kInf;
  for (const glm::dvec3& v : tri.p) {
    for (int m = 0; m < 8; ++m) {
      const glm::dvec3 q = v + e * glm::dvec3(m & 1 ? 1 : -1, m & 2 ? 1 : -1, m & 4 ? 1 : -1);
      const double u = ax.s * q[i];
      if (!(u > 0)) return false;
      const double x = (a * q[j] + b * q[k]) / u * ax.unit;
      mn = std::min(mn, x);
      mx = std::max(mx, x);
    }
  }
  *lo = mn;
  *hi = mx;
  return std::isfinite(mn) && std::isfinite(mx);
}

// The area of the rectangle [x0, x1] x [y0, y1] within the half-planes
// a_m x + b_m y >= c_m: Sutherland-Hodgman on its four corners.
struct HalfPlane {
  double a, b, c;  // a x + b y >= c
};
double clipped_area(double x0, double x1, double y0, double y1, const std::vector<HalfPlane>& hp) {
  std::vector<std::pair<double, double>> poly{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, next;
  for (const HalfPlane& h : hp) {
    next.clear();
    for (size_t m = 0; m < poly.size(); ++m) {
      const auto& p = poly[m];
      const auto& q = poly[(m + 1) % poly.size()];
      const double fp = h.a * p.first + h.b * p.second - h.c, fq = h.a * q.first + h.b * q.second - h.c;
      if (fp >= 0) next.push_back(p);
      if ((fp >= 0) != (fq >= 0)) {
        const double t = fp / (fp - fq);
        next.emplace_back(p.first + t * (q.first - p.first), p.second + t * (q.second - p.second));
      }
    }
    poly.swap(next);
    if (poly.empty()) return 0;
  }
  double area = 0;
  for (size_t m = 0; m < poly.size(); ++m) {
    const auto& p = poly[m];
    const auto& q = poly[(m + 1) % poly.size()];
    area += p.first * q.second - q.first * p.second;
  }
  return 0.5 * std::abs(area);
}

// The expected rays of the pass left by the compares on V_j and V_k (a rectangle) and
// the half-planes `planes`, in units of V: the area times the class's density (rays
// spread evenly over the pass's range of V_j and V_k), as in rays_through.
double expected_rays(const ClassAxes& ax, const Range& pass, const std::vector<Compare>& cmps,
                     const std::vector<HalfPlane>& planes) {
  const int j = ax.j(), k = ax.k();
  double x0 = static_cast<double>(pass.vmin[j]), x1 = static_cast<double>(pass.vmax[j]);
  double y0 = static_cast<double>(pass.vmin[k]), y1 = static_cast<double>(pass.vmax[k]);
  for (const Compare& m : cmps) {
    if (m.kind == Compare::kDist || m.made) continue;
    if (m.word != kV + static_cast<unsigned>(j) && m.word != kV + static_cast<unsigned>(k)) continue;
    const double v = static_cast<double>(m.c);
    double& lo = m.word == kV + static_cast<unsigned>(j) ? x0 : y0;
    double& hi = m.word == kV + static_cast<unsigned>(j) ? x1 : y1;
    if (m.kind == Compare::kLo) lo = std::max(lo, v);
    else hi = std::min(hi, v);
  }
  if (x1 < x0 || y1 < y0) return 0;
  const double span = (static_cast<double>(pass.vmax[j] - pass.vmin[j]) + 1) *
                      (static_cast<double>(pass.vmax[k] - pass.vmin[k]) + 1);
  return pass.count / span * clipped_area(x0 - 0.5, x1 + 0.5, y0 - 0.5, y1 + 0.5, planes);
}

// Whether compares that cut the region from `before` rays to `after` are worth their
// clocks: a box test that finds no ray saves a broadcast's head, and the chance of that
// is Poisson's (a guess: the results do not depend on it; tuning.h).
bool pays(double saves, double before, double after, double clocks) {
  return saves * (std::exp(-after) - std::exp(-before)) > clocks;
}

// The pair word (layout::ray::kPair) holding V_j + V_k (diff: V_j - V_k), j < k.
unsigned pair_word(int j, int k, bool diff) {
  const unsigned p = j == 0 ? (k == 1 ? 0u : 1u) : 2u;
  return kPair + 2 * p + (diff ? 1u : 0u);
}

// The diagonal compares, appended to *cmps where they cut into the pass's range and pay
// (*planes gets their half-planes then). (V_j +- V_k) is within 2 of 2^vbits (d_j +-
// d_k) / |d_i|, so the constants are rounded outward by 4 units (2 for a single
// component). False: no ray of the pass lies within them.
bool add_diagonals(const Triangle& tri, double e, const ClassAxes& ax, const Range& pass, std::vector<Compare>* cmps,
                   std::vector<HalfPlane>* planes, bool* diagonal) {
  const int j = ax.j(), k = ax.k();
  std::vector<Compare> diag;
  std::vector<HalfPlane> hp;
  for (int d = 0; d < 2; ++d) {
    const double sg = d == 0 ? 1.0 : -1.0;
    double smin, smax;
    if (!linear_range(tri, e, ax, 1.0, sg, &smin, &smax)) return true;
    const double cmin = std::floor(smin) - 4, cmax = std::ceil(smax) + 4;
    const double lo_v = static_cast<double>(pass.dmin[d]), hi_v = static_cast<double>(pass.dmax[d]);
    if (cmin > hi_v || cmax < lo_v) return false;
    // Both now lie within the pass's diagonals (|c| <= 2^29): exact as integers.
    const unsigned w = pair_word(j, k, d == 1);
    if (cmin > lo_v) {
      diag.push_back({Compare::kLo, w, static_cast<int64_t>(cmin)});
      hp.push_back({1.0, sg, cmin});
    }
    if (cmax < hi_v) {
      diag.push_back({Compare::kHi, w, static_cast<int64_t>(cmax)});
      hp.push_back({-1.0, -sg, -cmax});
    }
  }
  if (diag.empty()) return true;
  const double before = expected_rays(ax, pass, *cmps, *planes);
  std::vector<HalfPlane> with = *planes;
  with.insert(with.end(), hp.begin(), hp.end());
  if (pays(kDiagonalSaves, before, expected_rays(ax, pass, *cmps, with), static_cast<double>(diag.size()))) {
    cmps->insert(cmps->end(), diag.begin(), diag.end());
    *planes = std::move(with);
    *diagonal = true;
  }
  return true;
}

// A word the blocks can form with one ADD or SUB, (x >>> shr) +- y, and its
// coefficients on (V_j, V_k); lo and hi: its range over the pass's rays (exact: the
// shift floors, a monotone map).
struct EdgeWord {
  unsigned x, y, shr;
  bool sub;
  double a, b;
  double lo, hi;
};

// The coefficients (a, b) of a block's word on (V_j, V_k): V_j, V_k or a pair word; and
// those of the word an edge compare forms from two of them, (x >>> shr) +- y.
struct Coef {
  double a, b;
};
Coef coef_of(const ClassAxes& ax, unsigned word) {
  const int j = ax.j(), k = ax.k();
  if (word == kV + static_cast<unsigned>(j)) return {1, 0};
  if (word == kV + static_cast<unsigned>(k)) return {0, 1};
  return word == pair_word(j, k, false) ? Coef{1, 1} : Coef{1, -1};
}
Coef made_coef(Coef x, Coef y, unsigned shr, bool sub) {
  const double f = std::ldexp(1.0, -static_cast<int>(shr)), sg = sub ? -1.0 : 1.0;
  return {x.a * f + sg * y.a, x.b * f + sg * y.b};
}

// The words one such step can combine: V_j, V_k and, where the blocks hold them, the
// pair words; each with the pass's range of it. Then every word the step can form.
std::vector<EdgeWord> edge_words(const ClassAxes& ax, const Range& pass) {
  const int j = ax.j(), k = ax.k();
  struct Source {
    unsigned word;
    double lo, hi;
  };
  std::vector<Source> src{
      {kV + static_cast<unsigned>(j), static_cast<double>(pass.vmin[j]), static_cast<double>(pass.vmax[j])},
      {kV + static_cast<unsigned>(k), static_cast<double>(pass.vmin[k]), static_cast<double>(pass.vmax[k])}};
  if (ax.pairs) {
    src.push_back({pair_word(j, k, false), static_cast<double>(pass.dmin[0]), static_cast<double>(pass.dmax[0])});
    src.push_back({pair_word(j, k, true), static_cast<double>(pass.dmin[1]), static_cast<double>(pass.dmax[1])});
  }
  std::vector<EdgeWord> out;
  for (const Source& x : src) {
    for (const Source& y : src) {
      if (x.word == y.word) continue;
      for (unsigned shr = 1; shr <= kEdgeShifts; ++shr) {
        const double f = std::ldexp(1.0, -static_cast<int>(shr));
        const double xl = std::floor(x.lo * f), xh = std::floor(x.hi * f);
        for (bool sub : {false, true}) {
          const Coef c = made_coef(coef_of(ax, x.word), coef_of(ax, y.word), shr, sub);
          out.push_back({x.word, y.word, shr, sub, c.a, c.b, sub ? xl - y.hi : xl + y.lo, sub ? xh - y.lo : xh + y.hi});
        }
      }
    }
  }
  return out;
}

// The edge compares: for each edge of the triangle as the class's rays see it, the word
// whose direction (a, b) lies nearest its outward normal, and the triangle's extreme
// along it. A block's W = floor(X / 2^shr) +- Y lies within 1 below a V_j + b V_k, and
// that within |a| + |b| of unit (a d_j + b d_k) / |d_i| (each component within 1, as for
// the diagonals): the constants are rounded outward by 2 (|a| + |b|) + 1. Appended where
// each pays on top of the compares before it (kEdgeSaves). False: no ray of the pass.
bool add_edges(const Triangle& tri, double e, const ClassAxes& ax, const Range& pass, std::vector<Compare>* cmps,
               std::vector<HalfPlane>* planes, unsigned* edge_count) {
  const int i = ax.i, j = ax.j(), k = ax.k();
  double px[3], py[3];
  for (int v = 0; v < 3; ++v) {
    const double u = ax.s * tri.p[v][i];
    if (!(u > 0)) return true;
    px[v] = tri.p[v][j] / u;
    py[v] = tri.p[v][k] / u;
  }
  const std::vector<EdgeWord> words = edge_words(ax, pass);
  for (int m = 0; m < 3; ++m) {
    const int v0 = m, v1 = (m + 1) % 3, v2 = (m + 2) % 3;
    double nx = py[v1] - py[v0], ny = px[v0] - px[v1];
    if (nx * (px[v2] - px[v0]) + ny * (py[v2] - py[v0]) > 0) nx = -nx, ny = -ny;
    const double nn = std::hypot(nx, ny);
    if (!(nn > 0)) continue;
    const EdgeWord* best = nullptr;
    double best_cos = 0;
    for (const EdgeWord& w : words) {
      const double c = (w.a * nx + w.b * ny) / (std::hypot(w.a, w.b) * nn);
      if (std::abs(c) > std::abs(best_cos)) best_cos = c, best = &w;
    }
    if (best == nullptr) continue;
    double wl, wh;
    if (!linear_range(tri, e, ax, best->a, best->b, &wl, &wh)) return true;
    const double margin = std::ceil(2 * (std::abs(best->a) + std::abs(best->b))) + 1;
    Compare cmp{Compare::kHi, layout::ray::kS, 0, true, best->x, best->y, best->shr, best->sub};
    HalfPlane hp{};
    if (best_cos > 0) {  // the outward normal points up W: W <= the triangle's largest
      const double c = std::ceil(wh) + margin;
      if (c < best->lo) return false;
      if (c >= best->hi) continue;
      cmp.c = static_cast<int64_t>(c);
      hp = {-best->a, -best->b, -c};
    } else {
      const double c = std::floor(wl) - margin;
      if (c > best->hi) return false;
      if (c <= best->lo) continue;
      cmp.kind = Compare::kLo;
      cmp.c = static_cast<int64_t>(c);
      hp = {best->a, best->b, c};
    }
    const double before = expected_rays(ax, pass, *cmps, *planes);
    planes->push_back(hp);
    if (!pays(kEdgeSaves, before, expected_rays(ax, pass, *cmps, *planes), 2)) {
      planes->pop_back();
      continue;
    }
    cmps->push_back(cmp);
    ++*edge_count;
  }
  return true;
}

// The half-plane a x + b y >= c of a slope compare, in units of V (x = V_j, y = V_k).
HalfPlane half_plane(const Compare& m, const ClassAxes& ax) {
  const Coef w = m.made ? made_coef(coef_of(ax, m.x), coef_of(ax, m.y), m.shr, m.sub) : coef_of(ax, m.word);
  const double c = static_cast<double>(m.c);
  return m.kind == Compare::kLo ? HalfPlane{w.a, w.b, c} : HalfPlane{-w.a, -w.b, -c};
}

// The expected rays of the pass within the half-planes (its range of V_j and V_k clipped).
double rays_within(const ClassAxes& ax, const Range& pass, const std::vector<HalfPlane>& planes) {
  const int j = ax.j(), k = ax.k();
  const double x0 = static_cast<double>(pass.vmin[j]), x1 = static_cast<double>(pass.vmax[j]);
  const double y0 = static_cast<double>(pass.vmin[k]), y1 = static_cast<double>(pass.vmax[k]);
  const double span = (x1 - x0 + 1) * (y1 - y0 + 1);
  return pass.count / span * clipped_area(x0 - 0.5, x1 + 0.5, y0 - 0.5, y1 + 0.5, planes);
}

// With the edges, some compares of the rectangle and the diagonals cut nothing more:
// each slope compare whose removal lets in fewer than kPruneRays expected rays more is
// dropped (edges first, the costlier), one at a time.
void prune(const ClassAxes& ax, const Range& pass, std::vector<Compare>* cmps, unsigned* edge_count) {
  std::vector<HalfPlane> planes;
  std::vector<size_t> at;  // planes[n] is the compare cmps[at[n]]
  for (size_t n = 0; n < cmps->size(); ++n) {
    if ((*cmps)[n].kind == Compare::kDist) continue;
    planes.push_back(half_plane((*cmps)[n], ax));
    at.push_back(n);
  }
  std::vector<char> drop(cmps->size(), 0);
  double now = rays_within(ax, pass, planes);
  for (int pass_made = 1; pass_made >= 0; --pass_made) {
    for (size_t n = 0; n < planes.size(); ++n) {
      const Compare& m = (*cmps)[at[n]];
      if (m.made != (pass_made == 1) || drop[at[n]]) continue;
      std::vector<HalfPlane> without;
      for (size_t q = 0; q < planes.size(); ++q) {
        if (q != n && !drop[at[q]]) without.push_back(planes[q]);
      }
      const double r = rays_within(ax, pass, without);
      if (r - now < kPruneRays) {
        drop[at[n]] = 1;
        now = r;
        if (m.made) --*edge_count;
      }
    }
  }
  std::vector<Compare> kept;
  for (size_t n = 0; n < cmps->size(); ++n) {
    if (!drop[n]) kept.push_back((*cmps)[n]);
  }
  cmps->swap(kept);
}

}  // namespace

void narrow_to_triangle(const Triangle& tri, double e, const ClassAxes& ax, int j, double* smin, double* smax) {
  double lo, hi;
  if (!linear_range(tri, e, ax, j == ax.j() ? 1.0 : 0.0, j == ax.j() ? 0.0 : 1.0, &lo, &hi)) return;
  *smin = std::max(*smin, lo / ax.unit);
  *smax = std::min(*smax, hi / ax.unit);
}

bool add_leaf_compares(const Triangle& tri, double e, const ClassAxes& ax, const Range& pass, bool diagonals, bool edges,
                       std::vector<Compare>* cmps, bool* diagonal, unsigned* edge_count) {
  std::vector<HalfPlane> planes;
  if (diagonals && ax.pairs && !add_diagonals(tri, e, ax, pass, cmps, &planes, diagonal)) return false;
  if (!edges) return true;
  if (!add_edges(tri, e, ax, pass, cmps, &planes, edge_count)) return false;
  if (*edge_count > 0) prune(ax, pass, cmps, edge_count);
  return true;
}

}  // namespace fmpp::isect::slopes
