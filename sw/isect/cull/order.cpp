// Coherent ray order for the ray-parallel passes (see order.h).
#include "sw/isect/cull/order.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fmpp::isect {
namespace {

uint64_t spread2(uint32_t v) {  // 16 bits to the even bits of 32
  uint64_t x = v & 0xFFFFu;
  x = (x | (x << 8)) & 0x00FF00FFu;
  x = (x | (x << 4)) & 0x0F0F0F0Fu;
  x = (x | (x << 2)) & 0x33333333u;
  x = (x | (x << 1)) & 0x55555555u;
  return x;
}

uint64_t spread3(uint32_t v) {  // 10 bits to every third bit of 30
  uint64_t x = v & 0x3FFu;
  x = (x | (x << 16)) & 0x030000FFu;
  x = (x | (x << 8)) & 0x0300F00Fu;
  x = (x | (x << 4)) & 0x030C30C3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

// Quantizes v in [lo, lo + span] to [0, 2^bits - 1].
uint32_t quantize_unit(double v, double lo, double span, unsigned bits) {
  const double top = std::ldexp(1.0, static_cast<int>(bits)) - 1;
  if (!(span > 0)) return 0;
  return static_cast<uint32_t>(std::clamp((v - lo) / span * top, 0.0, top));
}

// 2-D coordinates of each unit direction, near for near directions (see order.h).
std::vector<glm::dvec2> direction_coords(const std::vector<glm::dvec3>& u) {
  glm::dvec3 sum(0);
  for (const glm::dvec3& d : u) sum += d;
  std::vector<glm::dvec2> out(u.size());
  bool gnomonic = glm::length(sum) > 0;
  const glm::dvec3 axis = gnomonic ? glm::normalize(sum) : glm::dvec3(0, 0, 1);
  for (const glm::dvec3& d : u) gnomonic = gnomonic && glm::dot(d, axis) >= 0.5;
  if (gnomonic) {
    const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(axis, helper)), e2 = glm::cross(axis, e1);
    for (size_t i = 0; i < u.size(); ++i) {
      const double z = glm::dot(u[i], axis);
      out[i] = glm::dvec2(glm::dot(u[i], e1) / z, glm::dot(u[i], e2) / z);
    }
    return out;
  }
  for (size_t i = 0; i < u.size(); ++i) {  // octahedral map
    const glm::dvec3& d = u[i];
    const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    glm::dvec2 p(d.x / l1, d.y / l1);
    if (d.z < 0) {
      p = glm::dvec2((1 - std::abs(p.y)) * (p.x >= 0 ? 1 : -1), (1 - std::abs(p.x)) * (p.y >= 0 ? 1 : -1));
    }
    out[i] = p;
  }
  return out;
}

// Morton codes of 2-D points, one scale for both axes (tiles stay square).
std::vector<uint32_t> morton_of(const std::vector<glm::dvec2>& p) {
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::dvec2& q : p) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  const double span = std::max(hi.x - lo.x, hi.y - lo.y);
  std::vector<uint32_t> out(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    out[i] = morton2(quantize_unit(p[i].x, lo.x, span, 16), quantize_unit(p[i].y, lo.y, span, 16));
  }
  return out;
}

// Where one coordinate of the points takes a few values (up to rounding: values closer
// than 2^-32 of its span are one) and each value the same number of points, at least
// two, a row of a grid: the Morton codes of (the point's rank in its row by the other
// coordinate, its row's rank). Otherwise empty.
std::vector<uint32_t> grid_morton_along(const std::vector<glm::dvec2>& p, int row_axis) {
  const size_t n = p.size();
  const int col_axis = 1 - row_axis;
  std::vector<size_t> by_row(n);
  for (size_t i = 0; i < n; ++i) by_row[i] = i;
  std::sort(by_row.begin(), by_row.end(), [&](size_t a, size_t b) { return p[a][row_axis] < p[b][row_axis]; });
  const double tol = std::ldexp(p[by_row.back()][row_axis] - p[by_row.front()][row_axis], -32);
  std::vector<uint32_t> out(n);
  size_t rows = 0, width = 0;
  for (size_t a = 0, e; a < n; a = e) {
    for (e = a + 1; e < n && p[by_row[e]][row_axis] - p[by_row[e - 1]][row_axis] <= tol;) ++e;
    if (a == 0) width = e - a;
    if (e - a != width || width < 2 || width > 0x10000u || ++rows > 0x10000u) return {};
    std::sort(by_row.begin() + static_cast<long>(a), by_row.begin() + static_cast<long>(e),
              [&](size_t x, size_t y) { return p[x][col_axis] < p[y][col_axis]; });
    for (size_t i = a; i < e; ++i) {
      const auto col = static_cast<uint32_t>(i - a), row = static_cast<uint32_t>(rows - 1);
      out[by_row[i]] = row_axis == 1 ? morton2(col, row) : morton2(row, col);
    }
  }
  return rows >= 2 ? out : std::vector<uint32_t>{};
}

}  // namespace

std::vector<uint32_t> grid_morton(const std::vector<glm::dvec2>& p) {
  if (p.size() < 4) return {};
  std::vector<uint32_t> out = grid_morton_along(p, 1);
  return out.empty() ? grid_morton_along(p, 0) : out;
}

uint32_t morton2(uint32_t x, uint32_t y) { return static_cast<uint32_t>(spread2(x) | (spread2(y) << 1)); }

uint32_t morton3(uint32_t x, uint32_t y, uint32_t z) {
  return static_cast<uint32_t>(spread3(x) | (spread3(y) << 1) | (spread3(z) << 2));
}

std::vector<size_t> coherent_order(const std::vector<Ray>& rays, const std::vector<size_t>& idx) {
  const size_t n = idx.size();
  if (n < 2) return idx;
  std::vector<glm::dvec3> u(n);
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  bool shared = true;
  for (size_t i = 0; i < n; ++i) {
    const Ray& r = rays[idx[i]];
    u[i] = glm::normalize(r.d);
    lo = glm::min(lo, r.o);
    hi = glm::max(hi, r.o);
    shared = shared && r.o == rays[idx[0]].o;
  }
  const std::vector<glm::dvec2> coords = direction_coords(u);
  std::vector<uint32_t> dir = shared ? grid_morton(coords) : std::vector<uint32_t>{};
  if (dir.empty()) dir = morton_of(coords);
  std::vector<uint64_t> key(n);
  const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  for (size_t i = 0; i < n; ++i) {
    if (shared) {
      key[i] = dir[i];
      continue;
    }
    const Ray& r = rays[idx[i]];
    const uint64_t octant = (r.d.x < 0 ? 1u : 0u) | (r.d.y < 0 ? 2u : 0u) | (r.d.z < 0 ? 4u : 0u);
    const uint64_t at = morton3(quantize_unit(r.o.x, lo.x, span, 10), quantize_unit(r.o.y, lo.y, span, 10),
                                quantize_unit(r.o.z, lo.z, span, 10));
    key[i] = (octant << 61) | (at << 31) | (dir[i] >> 1);  // 3 + 30 + 31 bits
  }
  std::vector<size_t> pos(n);
  for (size_t i = 0; i < n; ++i) pos[i] = i;
  std::stable_sort(pos.begin(), pos.end(), [&](size_t a, size_t b) { return key[a] < key[b]; });
  std::vector<size_t> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = idx[pos[i]];
  return out;
}

std::vector<size_t> largest_first(const std::vector<size_t>& size) {
  std::vector<size_t> order(size.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return size[a] > size[b]; });
  return order;
}

std::vector<size_t> passes_by_reach(const Bvh& bvh, size_t items, unsigned blocks, size_t broadcasts,
                                    const std::function<std::vector<RayPacket>(size_t, unsigned)>& packets) {
  const size_t passes = (items + blocks - 1) / blocks;
  std::vector<size_t> reached(passes, 0);
  std::vector<char> reach(broadcasts);
  uint64_t tests = 0;
  for (size_t p = 0; p < passes; ++p) {
    const size_t base = p * blocks;
    std::fill(reach.begin(), reach.end(), 0);
    bvh.reached(packets(base, static_cast<unsigned>(std::min<size_t>(blocks, items - base))), reach, &tests);
    reached[p] = static_cast<size_t>(std::count(reach.begin(), reach.end(), 1));
  }
  return largest_first(reached);
}

}  // namespace fmpp::isect
