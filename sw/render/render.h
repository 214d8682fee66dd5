// The Whitted ray tracer. The host generates rays, shades hits and spawns new rays;
// every intersection goes to an Intersector: the exact reference, or the
// FMPP over any Bus (golden model, Verilated RTL, lockstep, SystemC).
//
// Rays travel in batches, one ray type per call, so the FMPP sees what suits it:
//  - primary rays share the eye as origin (the paper's inverse matrices);
//  - shadow rays are cast *from* each point light towards the shaded points, so they
//    share the light as origin too; a point is lit unless something lies between; an
//    area light's from points of its pool (shade.h), a directional light's from the
//    shaded points towards it;
//  - reflection and refraction rays have their own origins (the general formulation)
//    and exclude the triangle they leave.
// Each hit is shaded by shade.h's Shader; what a surface does with light is its
// material's (material.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/isect/exact/answer_check.h"
#include "sw/isect/exact/reference_bvh.h"
#include "sw/render/image.h"
#include "sw/scene/ray_kind.h"
#include "sw/scene/scene.h"

namespace rt {

// What a batch of rays is, for the statistics by kind: primary rays, shadow rays, and
// secondary rays (reflection and refraction travel together).
enum class BatchKind { kPrimary = 0, kShadow = 1, kSecondary = 2 };
inline constexpr int kNumBatchKinds = 3;
const char* to_string(BatchKind k);

class Intersector {
 public:
  virtual ~Intersector() = default;
  // The kind of the batches that follow (render() says it before each batch).
  virtual void set_batch_kind(BatchKind) {}
  // Nearest hit of every ray (see fmpp::isect::Ray for tmin, tmax, exclude).
  virtual std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) = 0;
  // Two independent batches, a of kind ka then b of kind kb: by default two calls in
  // that order; several FMPPs (sw/mpi/) share out the passes of both at once.
  virtual std::pair<std::vector<fmpp::isect::Hit>, std::vector<fmpp::isect::Hit>> intersect_two(
      const std::vector<fmpp::isect::Ray>& a, BatchKind ka, const std::vector<fmpp::isect::Ray>& b, BatchKind kb);
  // Distance a ray spawned at a hit must start off the surface beyond the hit point's own
  // error (spawn_offset, from the hit's t_err), for an intersector whose hits carry no
  // error bound: 0 for the reference and the FMPP (exact or certified t); Embree's float
  // arithmetic takes float_spawn_margin.
  virtual double spawn_margin() const { return 0; }
  // What the ray-level exact check (exact_check.h) allows the answers of a batch of kind
  // k: exact answers by default; a shadow batch under the shadow stop may name any
  // occluder, and certified t's may be off by their bound.
  virtual fmpp::isect::AnswerRules answer_rules(BatchKind) const { return {}; }
  // The machine and the options behind the answers, for the check's messages.
  virtual std::string describe() const { return "the exact reference"; }
};

class ReferenceIntersector : public Intersector {
 public:
  // The exact reference, through a hierarchy over the triangles (reference_bvh.h: the
  // same answers as nearest_reference, faster on large meshes).
  explicit ReferenceIntersector(const std::vector<fmpp::isect::Triangle>& tris) : ref_(tris) {}
  std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override;

 private:
  fmpp::isect::ReferenceBvh ref_;
};

// A spawn margin for an intersector in float arithmetic without error bounds (Embree,
// sw/embree/): 2e-5 of the half-diagonal of the triangles' bounding box (0 for none).
// The FMPP does not use it: its hits carry their certified error (Hit::t_err).
double float_spawn_margin(const std::vector<fmpp::isect::Triangle>& tris);

class FmppIntersector : public Intersector {
 public:
  FmppIntersector(fmpp::Device& dev, const std::vector<fmpp::isect::Triangle>& tris,
                  const fmpp::isect::KernelOptions& opt);
  std::vector<fmpp::isect::Hit> intersect(const std::vector<fmpp::isect::Ray>& rays) override;
  void set_batch_kind(BatchKind k) override { kind_ = k; }
  // Shadow batches run as occlusion queries (KernelOptions::occlusion: a shadow ray
  // whose own triangle is proven beyond its end stops at its first certified occluder;
  // the shading only asks whether the nearest hit before the end is another triangle),
  // unless this is off: then as nearest-hit queries like the others. The same image.
  void set_shadow_stop(bool on) { shadow_stop_ = on; }
  // The mapping of one kind of batch (initially the options' for every kind); rays the
  // mapping cannot take still go ray-parallel (fmpp::isect::route_rays).
  void set_mapping(BatchKind k, fmpp::isect::Mapping m) { mapping_[static_cast<int>(k)] = m; }
  // A shadow batch and the next depth's rays given together (intersect_two) go to the
  // kernels as one call, where this is on and the shadow rays are ray-parallel: their
  // rays of their own origins share passes. The same hits (a shadow ray's occlusion query
  // stops as before; the others have no tmax to stop at); the call's counters are kept
  // apart (stats_together), besides the totals.
  void set_kinds_together(bool on) { together_ = on; }
  std::pair<std::vector<fmpp::isect::Hit>, std::vector<fmpp::isect::Hit>> intersect_two(
      const std::vector<fmpp::isect::Ray>& a, BatchKind ka, const std::vector<fmpp::isect::Ray>& b,
      BatchKind kb) override;
  const fmpp::isect::KernelStats& stats_together() const { return together_stats_; }
  fmpp::isect::AnswerRules answer_rules(BatchKind k) const override;
  // "n = 24, 4096 blocks x 32 words, ..." with every kernel option and mapping choice.
  std::string describe() const override;
  const fmpp::isect::KernelStats& stats() const { return stats_; }
  const fmpp::isect::KernelStats& stats(BatchKind k) const { return by_kind_[static_cast<int>(k)]; }

 private:
  fmpp::Device& dev_;
  const std::vector<fmpp::isect::Triangle>& tris_;
  fmpp::isect::KernelOptions opt_;
  fmpp::isect::KernelStats stats_;
  fmpp::isect::KernelStats by_kind_[kNumBatchKinds];
  // One kernel call, its counters added to the totals and to *counters.
  std::vector<fmpp::isect::Hit> call(const std::vector<fmpp::isect::Ray>& rays, bool occlusion,
                                     fmpp::isect::Mapping mapping, fmpp::isect::KernelStats* counters);

  BatchKind kind_ = BatchKind::kPrimary;
  bool shadow_stop_ = true;
  fmpp::isect::Mapping mapping_[kNumBatchKinds];
  bool together_ = false;
  fmpp::isect::KernelStats together_stats_;
};

// One call of the intersector, for a progress display (sw/tools/render_progress.h).
struct BatchProgress {
  BatchKind kind = BatchKind::kPrimary;  // kShadow for the shadow rays of a merged call
  int level = 0;                         // 0: primary rays and their shadows
  int depth = 1;                         // the frame's recursion depth
  uint64_t rays = 0;                     // rays of this call (both kinds' in a merged call)
  uint64_t next_rays = 0;                // of them, the next level's (a merged call), else 0
  uint64_t traced = 0;                   // rays traced before this call (with it, when done)
  uint64_t primary_started = 0;          // primary rays of the bands begun so far
  uint64_t primary_total = 0;            // primary rays of the frame (pixels x samples)
  bool done = false;
};

struct RenderOptions {
  int width = 64;
  int height = 64;
  int max_depth = -1;  // -1: the scene's
  // Samples per pixel, 0: the scene's (Scene::spp). With n > 1, pixel (x, y) casts n
  // primary rays through the cells of strata_grid(n) over its square, each at a point
  // jittered within its cell, and takes their mean (a box filter over the pixel); with 1,
  // one ray through the centre.
  int spp = 0;
  // The seed of every random choice (jitter, area-light samples); unset: the scene's.
  std::optional<uint64_t> seed;
  // Empty: every pixel, and the image is the frame. Otherwise only these pixel indices
  // (y * width + x, each in the frame), traced exactly as in the whole frame, and the
  // image holds them alone, the k-th listed at index k (pixels.size() x 1): a sample of a
  // large frame costs no image of the frame.
  std::vector<uint32_t> pixels;
  // Called before (done false) and after (done true) each call of the intersector.
  std::function<void(const BatchProgress&)> progress;
};


struct RenderStats {
  uint64_t rays[kNumRayKinds] = {};
  // Per ray kind, the rays whose FMPP answer the host redid (Hit::redo): flagged
  // uncertain and redone exactly, t from the host, overflowed (docs/intersection.md,
  // "Certified results").
  uint64_t flagged[kNumRayKinds] = {}, t_from_host[kNumRayKinds] = {}, overflow[kNumRayKinds] = {};
  uint64_t batches = 0;
  double intersect_seconds = 0;
  double shade_seconds = 0;
};

// How far a secondary ray spawned at the point o + t d of ray r starts from the surface
// (along the unit face normal n): the bound on that point's own error - from the
// relative error t_err of t and the rounding of o + t d - projected on n and doubled (as
// pbrt-v4 does). It depends on this hit alone, not on the scene's size: the shader gives
// it the hit's own bound (Hit::t_err, at least 2^-40), and adds the intersector's
// spawn_margin() (0 but for Embree).
double spawn_offset(const fmpp::isect::Ray& r, double t, const glm::dvec3& n, double t_err);

// The pixels `want` of `image` as a render of them alone gives them (RenderOptions::pixels:
// the k-th at index k; want empty: the whole frame), where `image` is a render of the
// pixels `of` (of empty: of the whole frame). Throws std::invalid_argument for a pixel
// `image` does not hold.
Image listed_pixels(const Image& image, const std::vector<uint32_t>& of, const std::vector<uint32_t>& want);

// The camera's primary rays through the pixel centres, row by row from the top (pixel
// index y * width + x), exactly as render() casts them.
std::vector<fmpp::isect::Ray> primary_rays(const Camera& cam, int width, int height);
// The same rays for pixel indices first, first + step, ... below last only (step >= 1).
std::vector<fmpp::isect::Ray> primary_rays(const Camera& cam, int width, int height, size_t first, size_t last,
                                           size_t step = 1);

// True if some of the scene's shadow rays may take the arbitrary-origin form, which needs
// own_origin_words() per block: a directional light's (cast from their points), or an area
// light's (a pool point's rays are fewer than a shared-origin group needs on a small
// frame; without a pool, each ray has its own origin).
bool shadows_need_own_origins(const Scene& scene);

// Memory bounds of a render: rays travel in bands of at most kPrimaryBatch primary rays
// (each band traced to the full depth) and shadow rays in batches of at most
// kShadowBatch, so only the image grows with the resolution. The largest side is
// kMaxSide, and a resolution whose image (with its copies for output) needs more than
// kMaxRenderBytes is refused with the estimate.
inline constexpr size_t kPrimaryBatch = size_t{1} << 18;
inline constexpr size_t kShadowBatch = size_t{1} << 20;
inline constexpr int kMaxSide = 16384;
inline constexpr uint64_t kMaxRenderBytes = uint64_t{4} << 30;
// Bytes per render of width x height that do not depend on the batches.
uint64_t render_memory_estimate(int width, int height);
// Throws std::invalid_argument naming the resolution (and the estimate) if it is refused.
void check_resolution(int width, int height);

// Renders the scene; the image is linear radiance. Throws std::invalid_argument for a
// resolution check_resolution refuses.
Image render(const Scene& scene, Intersector& isect, const RenderOptions& opt, RenderStats* stats);

}  // namespace rt
