// The comparison users make: the tracer's intersections answered by Embree (Debian's
// libembree-dev, Embree 3, one thread) behind the same Intersector interface as the
// FMPP, so a render hands Embree the primary, shadow and secondary rays it would hand
// the FMPP. Used by the benchmark fmpp-embree-bench (docs/perf.md, "Against Embree")
// and its test; nothing else in the project depends on it.
//
// Embree works in single precision: the triangles and rays are rounded to float, and
// its hits may differ from the exact reference's near edges and for nearly tied hits
// (hit_check.h counts them). The Ray fields map as: o, d -> org, dir (t keeps the
// units of d); tmin -> tnear; tmax -> tfar (a hit beyond tmax is of no interest to the
// caller, geometry.h, so Embree may cut the ray there); exclude -> an intersection
// filter that rejects that one triangle.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/render/render.h"

// Embree's handles, declared here so that its headers stay out of the callers'.
struct RTCDeviceTy;
struct RTCSceneTy;

namespace rt {

// Build settings of the Embree scene.
struct EmbreeOptions {
  // Embree's worker threads ("threads=N" of rtcNewDevice); the comparison uses 1.
  int threads = 1;
  // RTC_SCENE_FLAG_ROBUST: Embree's watertight mode (slower traversal, no cracks).
  bool robust = false;
  // Each batch as one ray stream (rtcIntersect1M, context flag COHERENT: Embree packs
  // neighbouring rays into SIMD packets) instead of one rtcIntersect1 call per ray.
  bool stream = false;
};

class EmbreeIntersector : public Intersector {
 public:
  // Builds Embree's BVH over `tris` (timed apart: build_seconds()). `spawn_margin` is
  // the distance secondary rays start off a surface beyond the hit point's own error:
  // Embree's float hits carry no bound, so callers pass float_spawn_margin (render.h).
  // Throws std::runtime_error with Embree's message if the device or scene fails.
  EmbreeIntersector(const std::vector<fmpp::isect::Triangle>& tris, double spawn_margin,
                    const EmbreeOptions& opt = EmbreeOptions());
  ~EmbreeIntersector() override;
  EmbreeIntersector(const EmbreeIntersector&) = delete;
  EmbreeIntersector& operator=(const EmbreeIntersector&) = delete;

  void set_batch_kind(BatchKind k) override { kind_ = k; }
  // Nearest hit of every ray: one rtcIntersect1 call per ray, or one rtcIntersect1M
  // call per batch (EmbreeOptions::stream). Only those calls are timed (seconds());
  // converting the rays to float and back is not.
  std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override;
  double spawn_margin() const override { return spawn_margin_; }

  double build_seconds() const { return build_seconds_; }
  // Rays traced and seconds spent in rtcIntersect1 per batch kind, since construction
  // or the last reset_counts().
  uint64_t rays(BatchKind k) const { return rays_[static_cast<int>(k)]; }
  double seconds(BatchKind k) const { return seconds_[static_cast<int>(k)]; }
  void reset_counts();
  // Embree's version string (RTC_DEVICE_PROPERTY_VERSION).
  std::string version() const;

 private:
  RTCDeviceTy* device_ = nullptr;
  RTCSceneTy* scene_ = nullptr;
  double spawn_margin_;
  bool stream_;
  double build_seconds_ = 0;
  BatchKind kind_ = BatchKind::kPrimary;
  uint64_t rays_[kNumBatchKinds] = {};
  double seconds_[kNumBatchKinds] = {};
};

}  // namespace rt
