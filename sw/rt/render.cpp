// Whitted ray tracing with batched intersection (see render.h).
#include "sw/rt/render.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "sw/isect/reference.h"
#include "sw/rt/shade.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

std::vector<Hit> ReferenceIntersector::intersect(const std::vector<Ray>& rays) {
  return fmpp::isect::nearest_reference(rays, tris_);
}

std::vector<Hit> FmppIntersector::intersect(const std::vector<Ray>& rays) {
  return fmpp::isect::intersect_fmpp(dev_, rays, tris_, opt_, &stats_);
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::vector<Ray> primary_rays(const Camera& cam, int width, int height) {
  // Row by row from the top, so a pass of the ray-parallel FMPP is a band of rows and
  // its culling frustum is thin.
  const glm::dvec3 fwd = glm::normalize(cam.look_at - cam.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, cam.up));
  const glm::dvec3 upv = glm::cross(right, fwd);
  const double th = std::tan(glm::radians(cam.fov_y_deg) / 2), aspect = double(width) / height;
  std::vector<Ray> rays;
  rays.reserve(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double u = (2 * (x + 0.5) / width - 1) * th * aspect, v = (1 - 2 * (y + 0.5) / height) * th;
      rays.push_back(Ray{cam.eye, fwd + u * right + v * upv});
    }
  }
  return rays;
}

Image render(const Scene& sc, Intersector& isect, const RenderOptions& opt, RenderStats* stats) {
  if (opt.width < 1 || opt.height < 1 || opt.width > 16384 || opt.height > 16384) {
    throw std::invalid_argument("rt::render: resolution " + std::to_string(opt.width) + "x" +
                                std::to_string(opt.height) + " outside 1..16384");
  }
  RenderStats local;
  RenderStats& st = stats ? *stats : local;
  Image img(opt.width, opt.height);
  const int depth = opt.max_depth > 0 ? opt.max_depth : sc.max_depth;
  const Shader shader(sc);

  // Primary rays through pixel centres.
  std::vector<Ray> rays = primary_rays(sc.camera, opt.width, opt.height);
  std::vector<Path> paths;
  for (size_t i = 0; i < rays.size(); ++i) paths.push_back(Path{static_cast<uint32_t>(i), glm::dvec3(1), RayKind::kPrimary});

  uint64_t traced = 0;
  for (int level = 0; level < depth && !rays.empty(); ++level) {
    auto t0 = std::chrono::steady_clock::now();
    const std::vector<Hit> hits = isect.intersect(rays);
    st.intersect_seconds += seconds_since(t0);
    ++st.batches;
    for (const Path& p : paths) ++st.rays[static_cast<int>(p.kind)];
    traced += rays.size();
    if (opt.progress) opt.progress(traced, "depth " + std::to_string(level) + ": " + std::to_string(rays.size()) + " rays");

    t0 = std::chrono::steady_clock::now();
    ShadeOutput out;
    for (size_t i = 0; i < rays.size(); ++i) shader.shade(rays[i], paths[i], hits[i], level + 1 < depth, img, out);
    st.shade_seconds += seconds_since(t0);

    const std::vector<Ray>& shadow_rays = out.shadow_rays;
    if (!shadow_rays.empty()) {
      t0 = std::chrono::steady_clock::now();
      const std::vector<Hit> sh = isect.intersect(shadow_rays);
      st.intersect_seconds += seconds_since(t0);
      ++st.batches;
      st.rays[static_cast<int>(RayKind::kShadow)] += shadow_rays.size();
      traced += shadow_rays.size();
      if (opt.progress) {
        opt.progress(traced, "depth " + std::to_string(level) + ": " + std::to_string(shadow_rays.size()) + " shadow rays");
      }
      Shader::add_unshadowed(out.shadows, sh, img);
    }
    rays.swap(out.next);
    paths.swap(out.next_paths);
  }
  return img;
}

}  // namespace rt
