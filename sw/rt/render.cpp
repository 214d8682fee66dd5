// Whitted ray tracing with batched intersection (see render.h).
#include "sw/rt/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sw/isect/reference.h"

namespace rt {

using fmpp::isect::Hit;
using fmpp::isect::Ray;

const char* to_string(RayKind k) {
  switch (k) {
    case RayKind::kPrimary: return "primary";
    case RayKind::kShadow: return "shadow";
    case RayKind::kReflection: return "reflection";
    case RayKind::kRefraction: return "refraction";
  }
  return "?";
}

std::vector<Hit> ReferenceIntersector::intersect(const std::vector<Ray>& rays) {
  return fmpp::isect::nearest_reference(rays, tris_);
}

FmppIntersector::FmppIntersector(fmpp::Device& dev, const std::vector<fmpp::isect::Triangle>& tris,
                                 const fmpp::isect::KernelOptions& opt)
    : dev_(dev), tris_(tris), opt_(opt) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const auto& t : tris) {
    for (const auto& p : t.p) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  // Half-extents first: the diagonal of a box near the coordinate limit would overflow.
  margin_ = tris.empty() ? 0 : 2e-5 * glm::length(0.5 * hi - 0.5 * lo);
}

std::vector<Hit> FmppIntersector::intersect(const std::vector<Ray>& rays) {
  return fmpp::isect::intersect_fmpp(dev_, rays, tris_, opt_, &stats_);
}

namespace {

// A ray's path back to its pixel: what its light is worth there.
struct Path {
  uint32_t pixel;
  glm::dvec3 weight;
  RayKind kind;
};

// A shadow query: the light's contribution if nothing lies between light and point.
struct Shadow {
  uint32_t pixel;
  glm::dvec3 contribution;
  int own;  // the shaded triangle: the shadow ray may end on it
};

glm::dvec3 barycentric(const fmpp::isect::Triangle& t, const glm::dvec3& p) {
  const glm::dvec3 v0 = t.p[1] - t.p[0], v1 = t.p[2] - t.p[0], v2 = p - t.p[0];
  const double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
  const double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (den == 0) return glm::dvec3(1.0 / 3);
  const double b1 = (d11 * d20 - d01 * d21) / den, b2 = (d00 * d21 - d01 * d20) / den;
  return glm::dvec3(1 - b1 - b2, b1, b2);
}

double max_abs(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

// v / |v|, or `fallback` for a zero vector; a vector whose squared length overflows
// (edges near the input limit) or underflows is scaled by its largest component first.
glm::dvec3 unit_or(glm::dvec3 v, const glm::dvec3& fallback) {
  const double len = glm::length(v);
  if (len > 0 && std::isfinite(len) && len > 1e-150) return glm::normalize(v);
  const double m = max_abs(v);
  if (!(m > 0) || !std::isfinite(m)) return fallback;
  return glm::normalize(v / m);
}

// Relative error bound of a double-precision t (a ratio of determinants, a few ulps for
// any hit that is not grazing); 2^-40 leaves a wide margin.
constexpr double kDoubleTError = 0x1p-40;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

double spawn_offset(const Ray& r, double t, const glm::dvec3& n, double t_err) {
  // p = o + t d: each component is off by at most |t d| t_err (the intersector's error
  // of t) plus the rounding of the multiply and add, a few units of 2^-53 of |o| + |t d|.
  // As pbrt-v4 does, the bound of the error box projected on the normal, doubled.
  const double td = std::abs(t) * max_abs(r.d);
  const double e = td * t_err + 4 * std::ldexp(1.0, -53) * (max_abs(r.o) + td);
  return 2 * e * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
}

std::vector<Ray> primary_rays(const Camera& cam, int width, int height, size_t first, size_t last) {
  // Row by row from the top, so a pass of the ray-parallel FMPP is a band of rows and
  // its culling frustum is thin.
  const glm::dvec3 fwd = glm::normalize(cam.look_at - cam.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, cam.up));
  const glm::dvec3 upv = glm::cross(right, fwd);
  const double th = std::tan(glm::radians(cam.fov_y_deg) / 2), aspect = double(width) / height;
  last = std::min(last, static_cast<size_t>(width) * static_cast<size_t>(height));
  std::vector<Ray> rays;
  rays.reserve(last > first ? last - first : 0);
  for (size_t i = first; i < last; ++i) {
    const int y = static_cast<int>(i / static_cast<size_t>(width)), x = static_cast<int>(i % static_cast<size_t>(width));
    const double u = (2 * (x + 0.5) / width - 1) * th * aspect, v = (1 - 2 * (y + 0.5) / height) * th;
    rays.push_back(Ray{cam.eye, fwd + u * right + v * upv});
  }
  return rays;
}

std::vector<Ray> primary_rays(const Camera& cam, int width, int height) {
  return primary_rays(cam, width, height, 0, static_cast<size_t>(width) * static_cast<size_t>(height));
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

Image render(const Scene& sc, Intersector& isect, const RenderOptions& opt, RenderStats* stats) {
  check_resolution(opt.width, opt.height);
  RenderStats local;
  RenderStats& st = stats ? *stats : local;
  Image img(opt.width, opt.height);
  const int depth = opt.max_depth > 0 ? opt.max_depth : sc.max_depth;

  // Pixels in bands of at most kPrimaryBatch primary rays, each traced to the full
  // depth before the next: the rays, paths and hits in memory stay bounded whatever the
  // resolution (only the image grows with it).
  const size_t pixels = static_cast<size_t>(opt.width) * static_cast<size_t>(opt.height);
  uint64_t traced = 0;
  for (size_t first = 0; first < pixels; first += kPrimaryBatch) {
    const size_t last = std::min(pixels, first + kPrimaryBatch);
    std::vector<Ray> rays = primary_rays(sc.camera, opt.width, opt.height, first, last);
    std::vector<Path> paths;
    for (size_t i = first; i < last; ++i) paths.push_back(Path{static_cast<uint32_t>(i), glm::dvec3(1), RayKind::kPrimary});

    for (int level = 0; level < depth && !rays.empty(); ++level) {
      auto t0 = std::chrono::steady_clock::now();
      const std::vector<Hit> hits = isect.intersect(rays);
      st.intersect_seconds += seconds_since(t0);
      ++st.batches;
      for (const Path& p : paths) ++st.rays[static_cast<int>(p.kind)];
      traced += rays.size();
      if (opt.progress) opt.progress(traced, "depth " + std::to_string(level) + ": " + std::to_string(rays.size()) + " rays");

      t0 = std::chrono::steady_clock::now();
      std::vector<Ray> next, shadow_rays;
      std::vector<Path> next_paths;
      std::vector<Shadow> shadows;
      // Shadow rays go out in batches of at most kShadowBatch (many lights times many
      // pixels would otherwise be built at once).
      auto cast_shadows = [&]() {
        if (shadow_rays.empty()) return;
        const auto ts = std::chrono::steady_clock::now();
        const std::vector<Hit> sh = isect.intersect(shadow_rays);
        st.intersect_seconds += seconds_since(ts);
        ++st.batches;
        st.rays[static_cast<int>(RayKind::kShadow)] += shadow_rays.size();
        traced += shadow_rays.size();
        if (opt.progress) {
          opt.progress(traced, "depth " + std::to_string(level) + ": " + std::to_string(shadow_rays.size()) + " shadow rays");
        }
        for (size_t i = 0; i < sh.size(); ++i) {
          // Lit unless the first thing from the light is something other than the point's
          // own triangle, before the point (t < 1; 1e-4 absorbs the fixed-point error).
          const bool lit = !sh[i].hit() || sh[i].tri == shadows[i].own || sh[i].t >= 1 - 1e-4;
          if (lit) img[shadows[i].pixel] += shadows[i].contribution;
        }
        shadow_rays.clear();
        shadows.clear();
      };
      for (size_t i = 0; i < rays.size(); ++i) {
        const Ray& r = rays[i];
        const Path& path = paths[i];
        const Hit& h = hits[i];
        if (!h.hit()) {
          img[path.pixel] += path.weight * sc.background;
          continue;
        }
        const auto& tri = sc.triangles[h.tri];
        const Material& m = sc.materials[sc.material_of[h.tri]];
        const glm::dvec3 p = r.o + h.t * r.d;
        const glm::dvec3 b = barycentric(tri, p);
        const auto& vn = sc.normals[h.tri];
        glm::dvec3 n = b.x * vn[0] + b.y * vn[1] + b.z * vn[2];
        glm::dvec3 nf = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
        nf = unit_or(nf, glm::dvec3(0, 0, 1));
        n = glm::length(n) > 0 ? glm::normalize(n) : nf;
        const glm::dvec3 dir = glm::normalize(r.d);
        const bool entering = glm::dot(dir, nf) < 0;
        if (!entering) nf = -nf;             // both normals face the side the ray came from
        if (glm::dot(n, nf) < 0) n = -n;
        const double local = 1 - m.reflectivity - m.transparency;
        img[path.pixel] += path.weight * local * m.diffuse * sc.ambient;
        for (const Light& light : sc.lights) {
          const glm::dvec3 l = light.position - p;
          const double len = glm::length(l);
          if (len == 0 || glm::dot(nf, l) <= 0 || glm::dot(n, l) <= 0) continue;  // light behind the surface
          const glm::dvec3 ld = l / len;
          const glm::dvec3 hv = glm::normalize(ld - dir);
          const glm::dvec3 c = path.weight * (local * m.diffuse * glm::dot(n, ld) +
                                              m.specular * std::pow(std::max(0.0, glm::dot(n, hv)), m.shininess)) *
                               light.color;
          // Cast from the light: every shadow ray of one light shares its origin.
          Ray s{light.position, p - light.position};
          s.tmax = 1;
          shadow_rays.push_back(s);
          shadows.push_back(Shadow{path.pixel, c, h.tri});
          if (shadow_rays.size() >= kShadowBatch) {
            st.shade_seconds += seconds_since(t0);
            cast_shadows();
            t0 = std::chrono::steady_clock::now();
          }
        }
        if (level + 1 >= depth) continue;
        // Secondary rays start off the surface by the bound on this hit point's own error,
        // plus what the intersector needs to tell a new hit from the surface it leaves
        // (0 for the double-precision reference).
        const double off = spawn_offset(r, h.t, nf, kDoubleTError) + isect.spawn_margin();
        if (m.reflectivity > 0) {
          glm::dvec3 rd = glm::reflect(dir, n);
          if (glm::dot(rd, nf) <= 0) rd = glm::reflect(dir, nf);
          Ray rr{p + off * nf, rd};
          rr.exclude = h.tri;
          next.push_back(rr);
          next_paths.push_back(Path{path.pixel, path.weight * m.reflectivity, RayKind::kReflection});
        }
        if (m.transparency > 0) {
          const double eta = entering ? 1.0 / m.ior : m.ior;
          glm::dvec3 td = glm::refract(dir, n, eta);
          glm::dvec3 origin = p - off * nf;
          if (glm::length(td) == 0) {  // total internal reflection
            td = glm::reflect(dir, n);
            origin = p + off * nf;
          }
          Ray tr{origin, td};
          tr.exclude = h.tri;
          next.push_back(tr);
          next_paths.push_back(Path{path.pixel, path.weight * m.transparency, RayKind::kRefraction});
        }
      }
      st.shade_seconds += seconds_since(t0);
      cast_shadows();
      rays.swap(next);
      paths.swap(next_paths);
    }
  }
  return img;
}

}  // namespace rt
