// fmpp-report precision, the measurements (precision.h). Errors are against the
// double-precision reference: per primary ray (intersect_fmpp on the camera's rays, once
// as the raw machine with cond_bits = 60 and once with the default host fallback), and
// per image (PSNR of the full Whitted render); leaks of the paper's form and the
// watertight one on a closed mesh around the eye. All on the golden model.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sw/fmpp/device.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "sw/report/precision.h"
#include "sw/render/render.h"
#include "backends/backend.h"

namespace fmpp::report::precision {
namespace {

using namespace fmpp::isect;

// The ways of running the kernel compared here: the paper's form with either multiply
// and the watertight form, ray-parallel (the renderer's mapping), and the paper's form
// object-parallel (for the primary rays; the render's other rays are ray-parallel).
struct Form {
  const char* name;
  MulMode mul;
  bool watertight;
  Mapping mapping;
};
const Form kForms[] = {{"generic", MulMode::kGeneric, false, Mapping::kRay},
                       {"const", MulMode::kConst, false, Mapping::kRay},
                       {"watertight", MulMode::kConst, true, Mapping::kRay},
                       {"object", MulMode::kConst, false, Mapping::kObject}};

KernelOptions kernel_options(const Form& f, unsigned n, int cond_bits) {
  KernelOptions o;
  o.mul = f.mul;
  o.n = n;
  o.watertight = f.watertight;
  o.mapping = f.mapping;
  o.cond_bits = cond_bits;
  return o;
}

// Rays answered by a form that certifies its results.
uint64_t certified_rays(const KernelStats& st) {
  uint64_t all = 0;
  for (int k = 0; k < KernelStats::kForms; ++k) all += st.form_rays[k];
  return all - std::min(all, st.uncertified_rays);
}

Errors errors(const std::vector<Hit>& got, const std::vector<Hit>& ref) {
  Errors e;
  std::vector<double> depth;
  size_t wrong = 0, hitmiss = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    if (got[i].hit() != ref[i].hit()) {
      ++hitmiss;
    } else if (got[i].tri != ref[i].tri) {
      ++wrong;
    } else if (ref[i].hit()) {
      depth.push_back(std::abs(got[i].t - ref[i].t) / ref[i].t);
    }
  }
  const double rays = static_cast<double>(std::max<size_t>(got.size(), 1));
  e.wrong = static_cast<double>(wrong) / rays;
  e.hitmiss = static_cast<double>(hitmiss) / rays;
  if (!depth.empty()) {
    std::sort(depth.begin(), depth.end());
    e.depth_median = depth[depth.size() / 2];
    e.depth_max = depth.back();
  }
  return e;
}

struct Run {
  std::vector<Hit> hits;
  KernelStats st;
};

Run run_kernel(const Config& machine, const std::vector<Ray>& rays, const std::vector<Triangle>& tris,
               const KernelOptions& o) {
  auto be = make_backend("cmodel", machine);
  Device dev(be->bus());
  Run r;
  r.hits = intersect_fmpp(dev, rays, tris, o, &r.st);
  return r;
}

struct RenderRun {
  rt::Image image{1, 1};
  KernelStats st;
};

RenderRun run_render(const Config& machine, const rt::Scene& s, int size, const KernelOptions& o) {
  auto be = make_backend("cmodel", machine);
  Device dev(be->bus());
  rt::FmppIntersector fi(dev, s.triangles, o);
  rt::RenderOptions ro;
  ro.width = ro.height = size;
  RenderRun r;
  r.image = rt::render(s, fi, ro, nullptr);
  r.st = fi.stats();
  return r;
}

// PSNR of the 8-bit images (all channels), in dB; +inf for identical images.
double psnr(const rt::Image& a, const rt::Image& b) {
  const std::vector<uint8_t> x = a.to_rgb8(), y = b.to_rgb8();
  double se = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double d = static_cast<double>(x[i]) - static_cast<double>(y[i]);
    se += d * d;
  }
  if (se == 0) return std::numeric_limits<double>::infinity();
  return 10 * std::log10(255.0 * 255.0 / (se / static_cast<double>(x.size())));
}

bool same_hits(const std::vector<Hit>& a, const std::vector<Hit>& b) {
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].tri != b[i].tri || (a[i].hit() && a[i].t != b[i].t)) return false;
  }
  return a.size() == b.size();
}

// One scene: for every n and form, the raw machine, the fallback and the render.
// Clears `consistent` where generic and const disagree.
SceneTable measure_scene(const Options& o, const Setup& setup, const char* name, bool& consistent) {
  const int size = setup.size;
  const Config& machine = setup.machine;
  const rt::Scene scene = rt::load_scene(o.scenes_dir + "/" + name + ".json");
  SceneTable table;
  table.name = name;
  table.triangles = scene.triangles.size();
  std::fprintf(stderr, "[precision] %s: %zu triangles, %d x %d pixels\n", name, scene.triangles.size(), size, size);
  const std::vector<Ray> rays = rt::primary_rays(scene.camera, size, size);
  const std::vector<Hit> ref = nearest_reference(rays, scene.triangles);
  rt::ReferenceIntersector ri(scene.triangles);
  rt::RenderOptions ro;
  ro.width = ro.height = size;
  const rt::Image ref_image = rt::render(scene, ri, ro, nullptr);
  std::vector<Row>& rows = table.rows;
  for (unsigned n : setup.bits) {
    std::vector<Hit> generic_hits;
    rt::Image generic_image(1, 1);
    for (const Form& f : kForms) {
      Row r;
      r.n = n;
      r.form = f.name;
      const Run raw = run_kernel(machine, rays, scene.triangles, kernel_options(f, n, policy::kRawCondBits));
      r.steps = raw.st.steps_per_broadcast();
      r.broadcasts = raw.st.broadcasts;
      r.raw_cycles = raw.st.cycles;
      r.raw = errors(raw.hits, ref);
      const Run fb = run_kernel(machine, rays, scene.triangles, kernel_options(f, n, -1));
      r.cycles = fb.st.cycles;
      r.fallback = errors(fb.hits, ref);
      r.host_triangles = fb.st.host_triangles;
      r.host_tests = fb.st.host_tests;
      r.overflow_rays = fb.st.overflow_rays;
      for (int k = 0; k < KernelStats::kForms; ++k) {
        r.flagged += fb.st.flagged_rays[k];
        r.t_redone += fb.st.t_bound_rays[k];
      }
      r.certified_rays = certified_rays(fb.st);
      const RenderRun rr = run_render(machine, scene, size, kernel_options(f, n, -1));
      r.render_cycles = rr.st.cycles;
      r.render_host_tests = rr.st.host_tests;
      for (int k = 0; k < KernelStats::kForms; ++k) {
        r.render_flagged += rr.st.flagged_rays[k];
        r.render_t_host += rr.st.t_bound_rays[k];
        r.render_rays += rr.st.form_rays[k];
      }
      r.render_certified = certified_rays(rr.st);
      r.psnr = psnr(rr.image, ref_image);
      r.pixels_off = rt::compare(rr.image, ref_image).pixels_over;
      // Generic and const must agree bit for bit (docs/intersection.md).
      if (f.mul == MulMode::kGeneric) {
        generic_hits = raw.hits;
        generic_image = rr.image;
      } else if (!f.watertight && f.mapping == Mapping::kRay &&
                 (!same_hits(generic_hits, raw.hits) || generic_image.to_rgb8() != rr.image.to_rgb8())) {
        std::fprintf(stderr, "[precision] %s n=%u: generic and const results differ\n", name, n);
        consistent = false;
      }
      rows.push_back(r);
    }
    std::fprintf(stderr, "[precision]   n=%u done (%.0f s so far)\n", n,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - setup.start).count());
  }
  return table;
}

}  // namespace

Setup make_setup(const Options& o) {
  Setup s;
  s.start = std::chrono::steady_clock::now();
  s.size = o.quick ? 8 : o.size;
  s.machine = o.quick ? kQuickMachine : kMachine;
  s.bits = o.quick ? std::vector<unsigned>{8, 24} : std::vector<unsigned>{8, 10, 12, 16, 20, 24, 32};
  return s;
}

SceneResults measure_scenes(const Options& o, const Setup& s) {
  SceneResults r;
  if (!o.only_scene.empty()) {
    r.tables.push_back(measure_scene(o, s, o.only_scene.c_str(), r.consistent));
    return r;
  }
  for (const char* name : kScenes) r.tables.push_back(measure_scene(o, s, name, r.consistent));
  if (!o.quick) r.tables.push_back(measure_scene(o, s, kScannedScene, r.consistent));
  return r;
}

Leaks measure_leaks(const Options& o, const Setup& s) {
  if (!o.only_scene.empty()) return Leaks{};  // one scene's section only
  std::fprintf(stderr, "[precision] leak rate on the closed sphere\n");
  const Config& machine = s.machine;
  const std::vector<Triangle> sphere = closed_sphere(SphereMeshOptions{});
  const std::vector<Ray> edge_rays = edge_and_vertex_rays(sphere, glm::dvec3(0));
  const std::vector<Ray> uniform = uniform_rays(glm::dvec3(0), o.quick ? 2000 : 20000, 3);
  const std::vector<unsigned> leak_bits =
      o.quick ? s.bits : std::vector<unsigned>{8, 10, 12, 16, 20, 24, 28, 32};
  Leaks leaks;
  leaks.sphere_triangles = sphere.size();
  leaks.edge_rays = edge_rays.size();
  leaks.uniform_rays = uniform.size();
  struct LeakForm {
    const char* name;
    bool watertight;
    int cond_bits;
  };
  for (unsigned n : leak_bits) {
    for (const LeakForm& lf : {LeakForm{"paper, raw", false, policy::kRawCondBits}, LeakForm{"paper, fallback", false, -1},
                               LeakForm{"watertight", true, -1}}) {
      KernelOptions ko;
      ko.n = n;
      ko.watertight = lf.watertight;
      ko.cond_bits = lf.cond_bits;
      const Run e = run_kernel(machine, edge_rays, sphere, ko);
      const Run u = run_kernel(machine, uniform, sphere, ko);
      LeakRow l;
      l.n = n;
      l.form = lf.name;
      l.steps = e.st.steps_per_broadcast();
      l.edge_rays = edge_rays.size();
      l.uniform_rays = uniform.size();
      for (const Hit& h : e.hits) l.edge_leaks += !h.hit();
      for (const Hit& h : u.hits) l.uniform_leaks += !h.hit();
      l.host_triangles = e.st.host_triangles;
      leaks.rows.push_back(l);
    }
  }
  return leaks;
}

}  // namespace fmpp::report::precision
