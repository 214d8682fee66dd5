// The plan's exact frame (see pass_cost.h: FrameRecord, record_frame, add_reach): the
// frame rendered with the exact reference's hits, every batch kept as the kernels get it,
// and each ray's reach, the triangles whose boxes it crosses before its first hit.
#include <algorithm>
#include <utility>

#include "sw/isect/cull/order.h"
#include "sw/plan/pass_cost.h"

namespace rt {
namespace {

using fmpp::isect::Box;
using fmpp::isect::Bvh;
using fmpp::isect::Hit;
using fmpp::isect::Ray;

// Renders the frame with the exact reference's hits and keeps every batch of rays, each
// cut at its exact nearest hit: the rays the FMPP will get.
class Recorder : public Intersector {
 public:
  explicit Recorder(ReferenceIntersector& exact) : exact_(exact) {}
  void set_batch_kind(BatchKind k) override { kind_ = k; }
  // A shadow batch and the next depth's rays cast in one call (render.cpp): recorded as
  // two batches, the first's index kept (FrameRecord::pairs).
  std::pair<std::vector<Hit>, std::vector<Hit>> intersect_two(const std::vector<Ray>& a, BatchKind ka,
                                                              const std::vector<Ray>& b, BatchKind kb) override {
    if (ka == BatchKind::kShadow && kb == BatchKind::kSecondary) pairs.push_back(batches.size());
    return Intersector::intersect_two(a, ka, b, kb);
  }
  std::vector<Hit> intersect(const std::vector<Ray>& rays) override {
    std::vector<Hit> hits = exact_.intersect(rays);
    std::vector<Ray> cut = rays;
    for (size_t i = 0; i < cut.size(); ++i) {
      if (hits[i].hit()) cut[i].tmax = std::min(cut[i].tmax, hits[i].t * (1 + 1e-9));
    }
    batches.push_back({kind_, std::move(cut)});
    return hits;
  }
  double spawn_margin() const override { return exact_.spawn_margin(); }
  std::vector<std::pair<BatchKind, std::vector<Ray>>> batches;
  std::vector<size_t> pairs;

 private:
  ReferenceIntersector& exact_;
  BatchKind kind_ = BatchKind::kPrimary;
};

}  // namespace

BatchReach reach_of(const std::vector<Ray>& rays, const Bvh& bvh, const std::vector<Box>& boxes,
                    const std::vector<fmpp::isect::PlaneSlab>& planes) {
  BatchReach r;
  r.start.reserve(rays.size() + 1);
  r.start.push_back(0);
  std::vector<size_t> all(rays.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  for (const fmpp::isect::RayPacket& p : fmpp::isect::make_packets(rays, all, 0, all.size(), 1, 0)) {
    bvh.visit(p, [&](uint32_t k) {
      if (fmpp::isect::may_cross(p, boxes[k], planes[k])) r.tris.push_back(k);
    });
    r.start.push_back(static_cast<uint32_t>(r.tris.size()));
  }
  return r;
}

FrameRecord record_frame(const Scene& scene, ReferenceIntersector& exact, int width, int height, int max_depth) {
  Recorder rec(exact);
  RenderOptions ro;
  ro.width = width;
  ro.height = height;
  ro.max_depth = max_depth;
  FrameRecord f;
  f.picture = render(scene, rec, ro, nullptr);
  f.batches = std::move(rec.batches);
  f.pairs = std::move(rec.pairs);
  return f;
}

void add_reach(const Scene& scene, FrameRecord* frame) {
  std::vector<Box> boxes;
  std::vector<fmpp::isect::PlaneSlab> planes;
  for (const auto& t : scene.triangles) {
    boxes.push_back(fmpp::isect::padded_box(t, 0));
    planes.push_back(fmpp::isect::plane_slab(t));
  }
  const Bvh bvh(boxes, {}, 1);
  frame->reach.clear();
  for (const auto& batch : frame->batches) frame->reach.push_back(reach_of(batch.second, bvh, boxes, planes));
}

}  // namespace rt
