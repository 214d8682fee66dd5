// fmpp-report paper, the measurements (paper.h): instructions and clocks of each Table 1
// operation on the Verilated RTL; steps per broadcast of both mappings and both
// multiplies over a scattered-triangle scene (RTL, and the golden model for the n
// sweep); the CPU baseline's ray-triangle tests per second.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "sw/report/cpu_baseline.h"
#include "sw/isect/pass/policy.h"
#include "sw/report/paper.h"
#include "backends/backend.h"

namespace fmpp::report::paper {
namespace {

using namespace fmpp::isect;

// The scene for the step counts: triangles of a tessellated-surface size scattered in
// front of the eye (the paper gives no scene; the counts depend on the constants only
// through their canonical signed digits).
std::vector<Triangle> paper_scene(unsigned m, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris(m);
  for (Triangle& t : tris) {
    const glm::dvec3 c(4 * u(rng), 4 * u(rng), 10 + 5 * u(rng));
    const double size = 0.05 + 0.1 * (u(rng) + 1);
    for (glm::dvec3& p : t.p) p = c + size * glm::dvec3(u(rng), u(rng), u(rng));
  }
  return tris;
}

std::vector<Ray> eye_rays(unsigned count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) r = Ray{glm::dvec3(0), glm::dvec3(u(rng), u(rng), 1)};
  return rays;
}

Run run_kernels(const std::string& backend, const Config& cfg, const std::vector<Ray>& rays,
                const std::vector<Triangle>& tris, Mapping m, MulMode mul, unsigned n) {
  auto be = make_backend(backend, cfg);
  Device dev(be->bus());
  KernelOptions o;
  o.mapping = m;
  o.mul = mul;
  o.n = n;
  // The paper's kernels: every triangle an FMPP broadcast (no culling: the leaf tests
  // would leave out the triangles no ray hits, and with them every broadcast of a
  // small workload; no host share for ill-conditioned triangles).
  o.cull = false;
  o.cond_bits = policy::kRawCondBits;
  Run r;
  const auto t0 = std::chrono::steady_clock::now();
  intersect_fmpp(dev, rays, tris, o, &r.st);
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  be->finish();
  return r;
}

// Clocks of one straight-line program pushed on the RTL.
uint64_t rtl_cycles(const std::string& config, const Program& p) {
  auto be = make_backend("rtl", named_config(config));
  Device dev(be->bus());
  const uint64_t c0 = dev.cycles();
  dev.push(p.code());
  return dev.cycles() - c0;
}

}  // namespace

Table1 measure_table1(const std::string& rtl_config, const Config& rcfg, unsigned n) {
  std::fprintf(stderr, "[paper] Table 1 on the RTL (%s)\n", rtl_config.c_str());
  Table1 t;
  Program tp;
  transfer(tp, rcfg.blocks - 1, 3, 0x12345678);
  t.transfer_instructions = tp.size();
  t.transfer_cycles = rtl_cycles(rtl_config, tp);
  std::mt19937_64 rng(7);
  for (unsigned k : {8u, 16u, 24u, 32u}) {
    Program p;
    mul(p, 3, 1, 2, k, 0, 3);
    t.mul_gen[k] = {p.size(), rtl_cycles(rtl_config, p)};
    double sum = 0, lo = 1e9, hi = 0;
    const int samples = 2000;
    for (int s = 0; s < samples; ++s) {
      const int64_t c =
          std::uniform_int_distribution<int64_t>(-(int64_t{1} << (k - 1)), (int64_t{1} << (k - 1)) - 1)(rng);
      Program q;
      mul_const(q, 3, c, 2, k, 0);
      sum += static_cast<double>(q.size());
      lo = std::min(lo, static_cast<double>(q.size()));
      hi = std::max(hi, static_cast<double>(q.size()));
    }
    t.mul_csd[k] = {sum / samples, lo, hi};
  }
  Program sp;
  nonneg(sp, 1, 0, 5);
  t.sign_instructions = sp.size();
  Program mp;
  max_search(mp, 1, 3, 5, n);
  t.max_instructions = mp.size();
  return t;
}

Workload make_workload(const Config& rcfg, unsigned scene_triangles, bool quick) {
  Workload w;
  w.scene_triangles = scene_triangles;
  w.scene = paper_scene(scene_triangles, 11);
  w.rays_rp = eye_rays(rcfg.blocks, 3);
  const unsigned op_tris = std::min(rcfg.blocks, scene_triangles);
  w.scene_op.assign(w.scene.begin(), w.scene.begin() + op_tris);
  w.rays_op = eye_rays(quick ? 64 : 512, 5);
  return w;
}

Broadcasts measure_broadcasts(const Config& rcfg, const Workload& w, unsigned n) {
  std::fprintf(stderr, "[paper] steps per broadcast, %u triangles\n", w.scene_triangles);
  Broadcasts b;
  b.rp_const = run_kernels("rtl", rcfg, w.rays_rp, w.scene, Mapping::kRay, MulMode::kConst, n);
  b.rp_gen = run_kernels("rtl", rcfg, w.rays_rp, w.scene, Mapping::kRay, MulMode::kGeneric, n);
  b.op_const = run_kernels("rtl", rcfg, w.rays_op, w.scene_op, Mapping::kObject, MulMode::kConst, n);
  b.op_gen = run_kernels("rtl", rcfg, w.rays_op, w.scene_op, Mapping::kObject, MulMode::kGeneric, n);
  const unsigned sbits = policy::object_search_bits(KernelOptions{});  // bits of S the maximum search scans
  b.op_search = 3.0 * sbits + 1;
  return b;
}

Sweep measure_sweep(const Config& rcfg, const Workload& w) {
  std::fprintf(stderr, "[paper] n sweep (golden model)\n");
  Sweep s;
  const std::vector<Triangle> sweep_scene(w.scene.begin(),
                                          w.scene.begin() + std::min(w.scene_triangles, 2000u));
  s.triangles = sweep_scene.size();
  const std::vector<Ray>& rays_rp = w.rays_rp;
  const std::vector<Ray>& rays_op = w.rays_op;
  const std::vector<Triangle>& scene_op = w.scene_op;
  for (unsigned k : {8u, 12u, 16u, 20u, 24u, 28u, 32u}) {
    const Config mc{rcfg.blocks, rcfg.words};
    const double a = run_kernels("cmodel", mc, rays_rp, sweep_scene, Mapping::kRay, MulMode::kGeneric, k).st.steps_per_broadcast();
    const double b = run_kernels("cmodel", mc, rays_rp, sweep_scene, Mapping::kRay, MulMode::kConst, k).st.steps_per_broadcast();
    const double c2 = run_kernels("cmodel", mc, rays_op, scene_op, Mapping::kObject, MulMode::kGeneric, k).st.steps_per_broadcast();
    const double d = run_kernels("cmodel", mc, rays_op, scene_op, Mapping::kObject, MulMode::kConst, k).st.steps_per_broadcast();
    s.rows.push_back(SweepRow{k, a, b, c2, d});
  }
  return s;
}

CpuRates measure_cpu(bool quick) {
  std::fprintf(stderr, "[paper] CPU baseline\n");
  CpuRates r;
  r.cpu = cpu_tests_per_second(quick ? 0.2 : 2.0);
  r.ref = reference_tests_per_second(quick ? 0.1 : 1.0);
  return r;
}

}  // namespace fmpp::report::paper
