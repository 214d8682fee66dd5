// The exact reference through a hierarchy (see reference_bvh.h).
//
// The walk only chooses candidates; the answer is the exact comparisons among them (as
// nearest_reference_among makes them), so it can differ from nearest_reference only if
// the walk left out a triangle that the exact nearest hit needs: one the ray meets at a
// distance no greater than the best candidate's. It cannot, because (1) every box is
// padded by 2^-30 of its triangle's extent and largest coordinate, far beyond the
// rounding of the box and of the packet test (a few ulps of the coordinates), so a box
// the ray meets is entered; and (2) a leaf is left only when its entry distance exceeds
// an upper bound on the best hit's distance (the upper end of the filtered test's
// enclosure of its t, exact.h: Candidate::hi), times 1 + 2^-30, plus 2^-30 of the
// origin's largest coordinate: the rounding of the entry distance is far below that
// margin. tests/isect/reference_bvh_test.cpp compares it with nearest_reference on hard
// placements.
#include "sw/isect/exact/reference_bvh.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <thread>

#include "sw/isect/exact/exact.h"
#include "sw/isect/exact/reference.h"

namespace fmpp::isect {
namespace {

constexpr double kRel = 0x1p-30;

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

std::vector<Box> padded_boxes(const std::vector<Triangle>& tris) {
  std::vector<Box> boxes;
  boxes.reserve(tris.size());
  for (const Triangle& t : tris) {
    const double big = std::max({max_abs(t.p[0]), max_abs(t.p[1]), max_abs(t.p[2])});
    boxes.push_back(padded_box(t, kRel * (extent(t) + big) + std::numeric_limits<double>::min()));
  }
  return boxes;
}

}  // namespace

ReferenceBvh::ReferenceBvh(const std::vector<Triangle>& tris) : tris_(tris) {
  validate_input({}, tris);
  bvh_ = Bvh(padded_boxes(tris));
}

Hit ReferenceBvh::nearest(const Ray& r) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  RayPacket p = ray_packet(r, kRel);
  p.t1 = kInf;
  const double len = glm::length(r.d) * (1 + kRel);
  const double slack = kRel * max_abs(r.o);
  double bound = kInf;  // an upper bound on the best candidate's distance (length units)
  // The filtered test (exact.h) decides each hit exactly and encloses its t: the upper
  // end bounds the distance, and two hits are compared exactly only where their
  // enclosures overlap. The candidates are kept as nearest_reference_among keeps them, in
  // the same order: the nearest, ties to the lower index, with its exact t.
  exact::RayTest test(r);
  exact::Candidate best, next;
  bvh_.visit_near_first(p, [&](const uint32_t* items, uint32_t n, double entry) {
    if (entry > bound) return true;  // leaves come in order of entry: none further is nearer
    for (uint32_t i = 0; i < n; ++i) {
      const int tri = static_cast<int>(items[i]);
      if (tri == r.exclude || !test.hits(tris_[items[i]], &next)) continue;
      next.tri = tri;
      bound = std::min(bound, next.hi * len * (1 + kRel) + slack);
      if (best.tri >= 0) {
        const int c = test.compare_hits(tris_[items[i]], &next, tris_[static_cast<size_t>(best.tri)], &best);
        if (c > 0 || (c == 0 && tri > best.tri)) continue;
      }
      std::swap(best, next);
    }
    return false;
  });
  Hit h;
  if (best.tri < 0) return h;
  h.tri = best.tri;
  h.t = test.hit_t(tris_[static_cast<size_t>(best.tri)], &best);
  return h;
}

std::vector<Hit> ReferenceBvh::nearest(const std::vector<Ray>& rays) const {
  validate_input(rays, {});
  std::vector<Hit> out(rays.size());
  // Each ray's answer is its own (the exact arithmetic keeps its workspace per thread),
  // so the rays are shared among the machine's cores in chunks taken in turn: the same
  // answers in any order. The first chunk is traced here and timed: other threads start
  // only if the rest would take kRepays or more, since a thread may take milliseconds to
  // begin (measured on the 2-core VM the project is built on) and a join waits for a late
  // thread even if it finds no chunk left; a smaller batch runs here alone.
  constexpr size_t kChunk = 256;
  constexpr double kRepays = 2e-3;  // seconds of work left that repay a thread
  const size_t n = rays.size();
  const auto trace = [&](size_t b) {
    for (size_t i = b; i < std::min(n, b + kChunk); ++i) out[i] = nearest(rays[i]);
  };
  const auto t0 = std::chrono::steady_clock::now();
  trace(0);
  if (n <= kChunk) return out;
  const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double rest = first * static_cast<double>(n - kChunk) / static_cast<double>(kChunk);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads =
      rest < kRepays ? 1u
                     : static_cast<unsigned>(std::min<size_t>({cores, kMaxThreads, (n - 1) / kChunk}));  // chunks left
  std::atomic<size_t> next{kChunk};
  std::vector<std::exception_ptr> failed(std::max(1u, threads));
  const auto work = [&](unsigned t) {
    try {
      for (size_t b = next.fetch_add(kChunk); b < n; b = next.fetch_add(kChunk)) trace(b);
    } catch (...) {
      failed[t] = std::current_exception();
      next.store(n);  // the others stop at their next chunk
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
  return out;
}

}  // namespace fmpp::isect
