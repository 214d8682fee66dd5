// The plan's samples (see decide.h): the primary rays measured per candidate n and
// the frame's pixels rendered whole.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "sw/isect/cull/order.h"
#include "sw/isect/geometry/hierarchy.h"
#include "sw/plan/decide.h"

namespace rt::decide {

using fmpp::isect::Ray;

std::vector<uint32_t> plan_pixels(size_t pixels, size_t count) {
  std::mt19937_64 rng(0x5eed);
  std::vector<uint32_t> all(pixels);
  std::iota(all.begin(), all.end(), 0u);
  for (size_t k = 0; k < count; ++k) {  // a partial Fisher-Yates shuffle
    std::uniform_int_distribution<size_t> pick(k, pixels - 1);
    std::swap(all[k], all[pick(rng)]);
  }
  all.resize(count);
  return sorted_subset(all, pixels);
}

std::vector<uint32_t> sorted_subset(const std::vector<uint32_t>& some, size_t pixels) {
  // Marked, then read in order: linear in the frame, where a sort of thousands of pixels
  // was a visible part of a small scene's plan.
  std::vector<char> in(pixels, 0);
  for (uint32_t i : some) in.at(i) = 1;
  std::vector<uint32_t> out;
  out.reserve(some.size());
  for (size_t i = 0; i < pixels; ++i) {
    if (in[i]) out.push_back(static_cast<uint32_t>(i));
  }
  return out;
}

PrimarySample primary_sample(const Scene& scene, const PlanRequest& req) {
  PrimarySample s;
  const size_t pixels = static_cast<size_t>(req.width) * static_cast<size_t>(req.height);
  // Every k-th primary ray of the frame.
  const size_t step = std::max<size_t>(1, pixels / static_cast<size_t>(std::max(1, req.sample_rays)));
  const std::vector<Ray> rays = primary_rays(scene.camera, req.width, req.height, 0, pixels, step);
  s.rays = rays.size();
  // Passes of 128 of the sample's rays, in the coherent order (image tiles): each pass
  // broadcasts only what its part of the frame needs (measured, the golden model's time
  // per candidate: one pass of the 1,024 rays 0.08 s on spheres_10k, 0.24 s on scans;
  // passes of 128 rays 0.03 s and 0.19 s; the same answers and redone rays).
  s.blocks = static_cast<unsigned>(std::min<size_t>(rays.size(), 128));
  std::vector<size_t> idx(rays.size());
  std::iota(idx.begin(), idx.end(), size_t{0});
  const std::vector<size_t> order = fmpp::isect::coherent_order(rays, idx);
  // The passes with the most rays that may reach the scene's box first: the rays that can
  // be redone or wrong are among those, so a candidate bound to be refused is refused
  // after fewer of them. The decision does not depend on the order (a candidate refused
  // part-way is, in any order, over its limits on the rays so far; an accepted one runs
  // every pass).
  fmpp::isect::Box box;
  for (const auto& t : scene.triangles) {
    for (const glm::dvec3& v : t.p) box.grow(v);
  }
  std::vector<std::pair<size_t, std::vector<Ray>>> reach;
  for (size_t b = 0; b < order.size(); b += s.blocks) {
    const size_t e = std::min(order.size(), b + s.blocks);
    std::vector<Ray> pass;
    for (size_t j = b; j < e; ++j) pass.push_back(rays[order[j]]);
    size_t count = 0;
    for (const auto& one : fmpp::isect::make_packets(rays, order, b, e, 1, 0.0)) count += fmpp::isect::may_enter(one, box);
    reach.emplace_back(count, std::move(pass));
  }
  std::stable_sort(reach.begin(), reach.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (auto& r : reach) s.passes.push_back(std::move(r.second));
  return s;
}

size_t fewest_to_show(const PlanRequest& req, size_t cap) {
  if (!(req.target_wrong_rate > 0)) return cap;  // no sample shows a zero target
  // With no pixel off the bound is 1 - (1 - confidence)^(1/k): start just below its k.
  const double k = std::floor(std::log1p(-req.confidence) / std::log1p(-req.target_wrong_rate)) - 1;
  size_t first = static_cast<size_t>(std::clamp(k, 0.0, static_cast<double>(cap)));
  while (first < cap && (first == 0 || upper_confidence_bound(0, first, req.confidence) > req.target_wrong_rate)) {
    first += 1;
  }
  return first;
}

FrameSample frame_sample(const PlanRequest& req, int depth) {
  FrameSample s;
  const size_t pixels = static_cast<size_t>(req.width) * static_cast<size_t>(req.height);
  s.frame.width = req.width;
  s.frame.height = req.height;
  s.frame.max_depth = depth;
  const size_t want = static_cast<size_t>(std::max(1, req.sample_pixels));
  if (want < pixels) s.frame.pixels = plan_pixels(pixels, want);
  s.sampled = s.frame.pixels.empty() ? pixels : s.frame.pixels.size();
  s.first = std::max(kPlanChunk, fewest_to_show(req, s.sampled));
  // The sample in random order, and the ends of its chunks (prefixes of that order); a
  // frame sampled whole is one chunk.
  s.order = s.frame.pixels;
  std::shuffle(s.order.begin(), s.order.end(), std::mt19937_64(0x5eed + 1));
  for (size_t e = s.first; e < s.sampled && !s.frame.pixels.empty(); e += kPlanChunk) s.ends.push_back(e);
  s.ends.push_back(s.sampled);
  return s;
}

RenderOptions FrameSample::chunk(size_t from, size_t to) const {
  RenderOptions part = frame;
  if (!frame.pixels.empty()) {
    const size_t pixels = static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height);
    part.pixels = sorted_subset(std::vector<uint32_t>(order.begin() + static_cast<std::ptrdiff_t>(from),
                                                      order.begin() + static_cast<std::ptrdiff_t>(to)),
                                pixels);
  }
  return part;
}

}  // namespace rt::decide
