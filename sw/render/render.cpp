// Whitted ray tracing with batched intersection (see render.h).
#include "sw/render/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "sw/scene/sampling.h"
#include "sw/render/shade.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

namespace {

void count_redo(const Hit& h, int kind, RenderStats& st) {
  if (h.redo == fmpp::isect::HostRedo::kFlagged) ++st.flagged[kind];
  if (h.redo == fmpp::isect::HostRedo::kTFromHost) ++st.t_from_host[kind];
  if (h.redo == fmpp::isect::HostRedo::kOverflow) ++st.overflow[kind];
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The ray through the centre of pixel i = y * width + x.
class PixelRays {
 public:
  PixelRays(const Camera& cam, int width, int height)
      : eye_(cam.eye), width_(width), height_(height), fwd_(glm::normalize(cam.look_at - cam.eye)),
        right_(glm::normalize(glm::cross(fwd_, cam.up))), up_(glm::cross(right_, fwd_)),
        th_(std::tan(glm::radians(cam.fov_y_deg) / 2)), aspect_(double(width) / height) {}
  // Through the point (x + dx, y + dy) of the pixel's square, (dx, dy) in [0, 1)^2.
  Ray operator()(size_t i, double dx = 0.5, double dy = 0.5) const {
    const int y = static_cast<int>(i / static_cast<size_t>(width_)), x = static_cast<int>(i % static_cast<size_t>(width_));
    const double u = (2 * (x + dx) / width_ - 1) * th_ * aspect_, v = (1 - 2 * (y + dy) / height_) * th_;
    return Ray{eye_, fwd_ + u * right_ + v * up_};
  }

 private:
  glm::dvec3 eye_;
  int width_, height_;
  glm::dvec3 fwd_, right_, up_;
  double th_, aspect_;
};

}  // namespace

std::vector<Ray> primary_rays(const Camera& cam, int width, int height, size_t first, size_t last, size_t step) {
  // Row by row from the top, so a pass of the ray-parallel FMPP is a band of rows and
  // its culling frustum is thin.
  const PixelRays at(cam, width, height);
  last = std::min(last, static_cast<size_t>(width) * static_cast<size_t>(height));
  std::vector<Ray> rays;
  step = std::max<size_t>(step, 1);
  rays.reserve(last > first ? (last - first + step - 1) / step : 0);
  for (size_t i = first; i < last; i += step) rays.push_back(at(i));
  return rays;
}

std::vector<Ray> primary_rays(const Camera& cam, int width, int height) {
  return primary_rays(cam, width, height, 0, static_cast<size_t>(width) * static_cast<size_t>(height));
}

bool shadows_need_own_origins(const Scene& scene) {
  for (const Light& l : scene.lights) {
    if (l.type != LightType::kPoint) return true;
  }
  return false;
}

uint64_t render_memory_estimate(int width, int height) {
  // Per pixel: the image (3 doubles), its 8-bit copy, and the PNG encoder's filtered
  // rows and output (about 3 bytes each).
  return static_cast<uint64_t>(width) * static_cast<uint64_t>(height) * (sizeof(glm::dvec3) + 3 + 3 + 3);
}

void check_resolution(int width, int height) {
  if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide) {
    throw std::invalid_argument("resolution " + std::to_string(width) + "x" + std::to_string(height) + " outside 1.." +
                                std::to_string(kMaxSide));
  }
  const uint64_t need = render_memory_estimate(width, height);
  if (need > kMaxRenderBytes) {
    throw std::invalid_argument("resolution " + std::to_string(width) + "x" + std::to_string(height) + " needs about " +
                                std::to_string((need + (1u << 20) - 1) >> 20) + " MiB for the image alone, over the limit of " +
                                std::to_string(kMaxRenderBytes >> 20) + " MiB; render a smaller picture");
  }
}

namespace {

// The listed pixels checked against the frame; their count (the frame's without a list).
size_t checked_pixels(const RenderOptions& opt) {
  const size_t frame = static_cast<size_t>(opt.width) * static_cast<size_t>(opt.height);
  for (uint32_t i : opt.pixels) {
    if (i >= frame) {
      throw std::invalid_argument("pixel " + std::to_string(i) + " outside the " + std::to_string(opt.width) + "x" +
                                  std::to_string(opt.height) + " frame");
    }
  }
  const size_t pixels = opt.pixels.empty() ? frame : opt.pixels.size();
  if (pixels > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument("render: " + std::to_string(pixels) + " listed pixels, more than one image holds");
  }
  return pixels;
}

// The primary rays of pixels [first, last) of the list (else the frame), spp samples each,
// and their paths.
void band_rays(const PixelRays& at, const RenderOptions& opt, size_t first, size_t last, int spp, uint64_t seed,
               std::vector<Ray>* rays, std::vector<Path>* paths) {
  for (size_t k = first; k < last; ++k) {
    const uint32_t i = opt.pixels.empty() ? static_cast<uint32_t>(k) : opt.pixels[k];
    const auto slot = static_cast<uint32_t>(k);  // the pixel's place in the image
    if (spp == 1) {
      rays->push_back(at(i));
      paths->push_back(Path{slot, glm::dvec3(1), RayKind::kPrimary, i});
      continue;
    }
    // The pixel's samples share the eye, so they travel with the other primary rays in
    // the paper's form; each weighs 1 / spp (the box filter).
    for (int j = 0; j < spp; ++j) {
      SampleRng rng(seed, kPixelSample, i, static_cast<uint64_t>(j));
      const double u1 = rng.next(), u2 = rng.next();
      const glm::dvec2 d = stratified(j, spp, u1, u2);
      rays->push_back(at(i, d.x, d.y));
      paths->push_back(Path{slot, glm::dvec3(1.0 / spp), RayKind::kPrimary,
                            static_cast<uint64_t>(i) * static_cast<uint64_t>(spp) + static_cast<uint64_t>(j)});
    }
  }
}

// The tracing of a frame's bands: each band's rays to the full depth, level by level
// (intersect, count, shade), its shadow rays in batches; the progress told as it goes.
class FrameTracer {
 public:
  FrameTracer(Intersector& isect, const RenderOptions& opt, RenderStats& st, const Shader& shader, Image& img,
              int depth, uint64_t primary_total)
      : isect_(isect), opt_(opt), st_(st), shader_(shader), img_(img), depth_(depth) {
    bp_.depth = depth;
    bp_.primary_total = primary_total;
  }

  // One band, whose primary rays end the first `primary_started` of the frame's.
  void trace_band(std::vector<Ray> rays, std::vector<Path> paths, uint64_t primary_started) {
    bp_.primary_started = primary_started;
    ahead_.clear();
    have_ahead_ = false;
    for (int level = 0; level < depth_ && !rays.empty(); ++level) {
      const std::vector<Hit> hits = level_hits(level, rays, paths);
      ShadeOutput out;
      shade_level(level, rays, paths, hits, out);
      rays.swap(out.next);
      paths.swap(out.next_paths);
    }
  }

 private:
  void tell(BatchKind kind, int level, uint64_t n, uint64_t next, bool done) {
    if (!opt_.progress) return;
    bp_.kind = kind;
    bp_.level = level;
    bp_.rays = n;
    bp_.next_rays = next;
    bp_.traced = traced_;
    bp_.done = done;
    opt_.progress(bp_);
  }

  // The level's hits: intersected now, or found with the last level's last shadows.
  std::vector<Hit> level_hits(int level, const std::vector<Ray>& rays, const std::vector<Path>& paths) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Hit> hits;
    const bool from_merged = have_ahead_;  // traced with the last level's last shadows
    const BatchKind kind = level == 0 ? BatchKind::kPrimary : BatchKind::kSecondary;
    if (have_ahead_) {
      hits.swap(ahead_);
      have_ahead_ = false;
    } else {
      tell(kind, level, rays.size(), 0, false);
      isect_.set_batch_kind(kind);
      hits = isect_.intersect(rays);
    }
    st_.intersect_seconds += seconds_since(t0);
    ++st_.batches;
    for (size_t i = 0; i < paths.size(); ++i) {
      ++st_.rays[static_cast<int>(paths[i].kind)];
      count_redo(hits[i], static_cast<int>(paths[i].kind), st_);
    }
    if (!from_merged) {
      traced_ += rays.size();
      tell(kind, level, rays.size(), 0, true);
    }
    return hits;
  }

  // Shades the level's hits into the image and `out` (the next level's rays), casting the
  // shadow rays in batches of about kShadowBatch (many lights times many pixels would
  // otherwise be built at once); the level's last shadows go with the next level's rays.
  void shade_level(int level, const std::vector<Ray>& rays, const std::vector<Path>& paths,
                   const std::vector<Hit>& hits, ShadeOutput& out) {
    auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < rays.size(); ++i) {
      shader_.shade(rays[i], paths[i], hits[i], level + 1 < depth_, img_, out);
      if (out.shadow_rays.size() >= kShadowBatch) {
        st_.shade_seconds += seconds_since(t0);
        cast_shadows(level, out, false);
        t0 = std::chrono::steady_clock::now();
      }
    }
    st_.shade_seconds += seconds_since(t0);
    cast_shadows(level, out, level + 1 < depth_ && !out.next.empty());
  }

  // The shadow rays of `out`, and with_next: the level's last shadows, with the next
  // level's rays (independent of them) in the same call; their hits wait in ahead_. The
  // same calls, in the same order, as one after the other.
  void cast_shadows(int level, ShadeOutput& out, bool with_next) {
    if (out.shadow_rays.empty()) return;
    const auto ts = std::chrono::steady_clock::now();
    std::vector<Hit> sh;
    const uint64_t next = with_next ? out.next.size() : 0, n = out.shadow_rays.size() + next;
    tell(BatchKind::kShadow, level, n, next, false);
    if (with_next) {
      std::tie(sh, ahead_) = isect_.intersect_two(out.shadow_rays, BatchKind::kShadow, out.next, BatchKind::kSecondary);
      have_ahead_ = true;
    } else {
      isect_.set_batch_kind(BatchKind::kShadow);
      sh = isect_.intersect(out.shadow_rays);
    }
    st_.intersect_seconds += seconds_since(ts);
    ++st_.batches;
    st_.rays[static_cast<int>(RayKind::kShadow)] += out.shadow_rays.size();
    for (const Hit& h : sh) count_redo(h, static_cast<int>(RayKind::kShadow), st_);
    traced_ += n;
    tell(BatchKind::kShadow, level, n, next, true);
    Shader::add_unshadowed(out.shadows, sh, img_);
    out.shadow_rays.clear();
    out.shadows.clear();
  }

  Intersector& isect_;
  const RenderOptions& opt_;
  RenderStats& st_;
  const Shader& shader_;
  Image& img_;
  const int depth_;
  uint64_t traced_ = 0;
  BatchProgress bp_;
  std::vector<Hit> ahead_;  // the next level's hits, found with the last level's last shadows
  bool have_ahead_ = false;
};

}  // namespace

Image render(const Scene& sc, Intersector& isect, const RenderOptions& opt, RenderStats* stats) {
  check_resolution(opt.width, opt.height);
  RenderStats local;
  RenderStats& st = stats ? *stats : local;
  const int depth = opt.max_depth > 0 ? opt.max_depth : sc.max_depth;
  // Secondary rays start off the surface by the bound on the hit point's own error plus
  // what the intersector needs to tell a new hit from the surface it leaves.
  const uint64_t seed = opt.seed ? *opt.seed : sc.seed;
  const Shader shader(sc, isect.spawn_margin(), seed);
  const int spp = opt.spp > 0 ? opt.spp : sc.spp;
  if (spp < 1 || spp > kMaxSpp) {
    throw std::invalid_argument("samples per pixel " + std::to_string(spp) + " outside 1.." + std::to_string(kMaxSpp));
  }
  const size_t pixels = checked_pixels(opt);
  // The image: the frame, or the listed pixels alone (a path's pixel is then its slot).
  Image img = opt.pixels.empty() ? Image(opt.width, opt.height) : Image(static_cast<int>(pixels), 1);
  const PixelRays at(sc.camera, opt.width, opt.height);
  // Pixels in bands of at most kPrimaryBatch primary rays (all the samples of its
  // pixels), each traced to the full depth before the next: the rays, paths and hits in
  // memory stay bounded whatever the resolution (only the image grows with it).
  const size_t band = std::max<size_t>(1, kPrimaryBatch / static_cast<size_t>(spp));
  FrameTracer tracer(isect, opt, st, shader, img, depth, static_cast<uint64_t>(pixels) * static_cast<uint64_t>(spp));
  for (size_t first = 0; first < pixels; first += band) {
    const size_t last = std::min(pixels, first + band);
    std::vector<Ray> rays;
    std::vector<Path> paths;
    band_rays(at, opt, first, last, spp, seed, &rays, &paths);
    tracer.trace_band(std::move(rays), std::move(paths), static_cast<uint64_t>(last) * static_cast<uint64_t>(spp));
  }
  return img;
}

Image listed_pixels(const Image& image, const std::vector<uint32_t>& of, const std::vector<uint32_t>& want) {
  if (want.empty()) {
    if (!of.empty()) throw std::invalid_argument("listed_pixels: the whole frame wanted of an image of listed pixels");
    return image;
  }
  if (want == of) return image;  // the same pixels in the same order
  if (want.size() > static_cast<size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument("listed_pixels: " + std::to_string(want.size()) + " pixels, more than one image holds");
  }
  Image out(static_cast<int>(want.size()), 1);
  // Where each pixel of `of` lies in `image` (by a sorted copy: `of` may be in any order).
  std::vector<std::pair<uint32_t, size_t>> at;
  at.reserve(of.size());
  for (size_t k = 0; k < of.size(); ++k) at.emplace_back(of[k], k);
  std::sort(at.begin(), at.end());
  for (size_t k = 0; k < want.size(); ++k) {
    size_t slot = want[k];
    if (!of.empty()) {
      const auto it = std::lower_bound(at.begin(), at.end(), std::make_pair(want[k], size_t{0}));
      slot = it != at.end() && it->first == want[k] ? it->second : image.size();
    }
    if (slot >= image.size()) {
      throw std::invalid_argument("listed_pixels: pixel " + std::to_string(want[k]) + " is not in the image");
    }
    out[k] = image[slot];
  }
  return out;
}

}  // namespace rt
