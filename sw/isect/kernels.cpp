// Ray-triangle intersection kernels for the FMPP (see kernels.h, docs/intersection.md).
#include "sw/isect/kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

#include "sw/fmpp/program.h"
#include "sw/isect/reference.h"

namespace fmpp::isect {

using namespace ins;

Mapping parse_mapping(const std::string& s) {
  if (s == "ray") return Mapping::kRay;
  if (s == "object") return Mapping::kObject;
  throw std::invalid_argument("mapping '" + s + "' is not one of ray, object");
}
MulMode parse_mul_mode(const std::string& s) {
  if (s == "generic") return MulMode::kGeneric;
  if (s == "const") return MulMode::kConst;
  throw std::invalid_argument("multiply '" + s + "' is not one of generic, const");
}
Origins parse_origins(const std::string& s) {
  if (s == "auto") return Origins::kAuto;
  if (s == "group") return Origins::kGroup;
  if (s == "general") return Origins::kGeneral;
  throw std::invalid_argument("origins '" + s + "' is not one of auto, group, general");
}
const char* to_string(Origins o) { return o == Origins::kAuto ? "auto" : o == Origins::kGroup ? "group" : "general"; }
const char* to_string(Mapping m) { return m == Mapping::kRay ? "ray" : "object"; }
const char* to_string(MulMode m) { return m == MulMode::kGeneric ? "generic" : "const"; }

void KernelStats::add(const KernelStats& o) {
  cycles += o.cycles;
  load_cycles += o.load_cycles;
  compute_cycles += o.compute_cycles;
  readback_cycles += o.readback_cycles;
  instructions += o.instructions;
  broadcasts += o.broadcasts;
  passes += o.passes;
  groups += o.groups;
  general_rays += o.general_rays;
  broadcast_steps += o.broadcast_steps;
  test_steps += o.test_steps;
  overflow_rays += o.overflow_rays;
  overflow_triangles += o.overflow_triangles;
  host_triangles += o.host_triangles;
  host_tests += o.host_tests;
  culled += o.culled;
  snapped_degenerate += o.snapped_degenerate;
}

namespace {

// Flags.
constexpr unsigned kSel = 0, kHit = 1, kWin = 2, kTmp = 3, kLoaded = 4;

// Ray-parallel words.
// kRCnt counts the broadcasts of a pass (the best's ordinal is copied from it, so no
// WRITES and no mask change is needed per broadcast); kROne holds 1.
constexpr unsigned kRV = 0, kRT = 3, kRS = 6, kRBest = 7, kRIdx = 8, kRD = 9, kRCnt = 10, kROne = 11, kRX = 12;
// Object-parallel words.
constexpr unsigned kOX = 0, kOY = 9, kOT = 12, kOS = 15, kOV = 16;

constexpr double kInf = std::numeric_limits<double>::infinity();

// The relative error of T is about cond(P) times that of the coarser of the two
// operands of its products: the n-bit multiplier and the other one (ray components,
// vbits, ray-parallel; matrix mantissas, mbits, object-parallel). Beyond 2^(bits - 3)
// the test could be wrong by more than an eighth.
unsigned effective_cond_bits(const KernelOptions& o) {
  if (o.cond_bits >= 0) return static_cast<unsigned>(o.cond_bits);
  return std::min(o.n, o.mapping == Mapping::kRay ? o.vbits : o.mbits) - 3;
}

double inf_norm(const glm::dmat3& a) {
  double m = 0;
  for (int r = 0; r < 3; ++r) m = std::max(m, std::abs(a[0][r]) + std::abs(a[1][r]) + std::abs(a[2][r]));
  return m;
}

// P^-1 for the triangle seen from `o`, with T_i = sum_j m[i][j] V_j. False if the
// triangle is singular or too ill-conditioned from o for the fixed-point format.
bool inverse_from(const Triangle& t, const glm::dvec3& o, double cond_limit, double m[3][3]) {
  const glm::dmat3 P(t.p[0] - o, t.p[1] - o, t.p[2] - o);  // columns
  const double det = glm::determinant(P);
  if (det == 0 || !std::isfinite(det)) return false;
  const glm::dmat3 M = glm::inverse(P);
  const double cond = inf_norm(P) * inf_norm(M);
  if (!std::isfinite(cond) || cond > cond_limit) return false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[i][j] = M[j][i];  // glm is column-major: M[col][row]
  }
  return true;
}

// Exponent e with max|v| < 2^e, and mantissas round(v * 2^(bits - e)) below 2^bits.
int mantissas(const double* v, int count, unsigned bits, int64_t* out) {
  double m = 0;
  for (int k = 0; k < count; ++k) m = std::max(m, std::abs(v[k]));
  int e = (m > 0) ? static_cast<int>(std::floor(std::log2(m))) + 1 : 0;
  const int64_t lim = (int64_t{1} << bits) - 1;
  for (;;) {
    bool ok = true;
    for (int k = 0; k < count; ++k) {
      out[k] = std::llround(std::ldexp(v[k], static_cast<int>(bits) - e));
      ok = ok && std::llabs(out[k]) <= lim;
    }
    if (ok) return e;
    ++e;
  }
}

// Largest component magnitude of a vector. For a direction: each ray's components are
// quantized with their own scale (the largest becomes the format's limit), so a short direction in a
// batch of long ones keeps all its bits; t is corrected per ray on the host.
double max_component(const glm::dvec3& d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); }

int32_t quantize(double v, double scale, int64_t limit, const char* what) {
  const double q = std::nearbyint(v / scale);
  if (!(std::abs(q) <= static_cast<double>(limit))) {
    throw std::logic_error(std::string("fmpp::isect: ") + what + " out of range after scaling");
  }
  return static_cast<int32_t>(q);
}

// Merges host-side results for some triangles into `hit` (nearest wins, ties to the lower index).
void merge_host(const Ray& r, const std::vector<Triangle>& tris, const std::vector<int>& host, Hit* hit,
                KernelStats* st) {
  for (int k : host) {
    if (k == r.exclude) continue;
    const double t = intersect_reference(r, tris[k]);
    ++st->host_tests;
    if (t <= r.tmin) continue;
    if (t < hit->t || (t == hit->t && k < hit->tri)) {
      hit->t = t;
      hit->tri = k;
    }
  }
}

// Counts one triangle broadcast of `steps` instructions, `test_steps` of them up to the
// inside test.
void count_broadcast(KernelStats* st, size_t steps, size_t test_steps) {
  st->broadcast_steps += steps;
  st->test_steps += test_steps;
  ++st->broadcasts;
}

// Reads back one ray-parallel pass of `count` blocks: the overflow flags, then the best
// word of every block without overflow and, when it is not `none`, the 1-based number of
// the broadcast that set it (idx_word). Calls on_hit(block, best, position in the pass)
// for each hit; returns the overflow flag of each block.
template <class OnHit>
std::vector<bool> read_pass(Device& dev, unsigned count, unsigned best_word, unsigned idx_word, uint32_t none,
                            size_t broadcasts, OnHit&& on_hit) {
  std::vector<bool> ovf(count, false);
  if (dev.overflow()) {
    const std::vector<bool> v = dev.read_flag_all(map::kFlagV);
    for (unsigned b = 0; b < count; ++b) ovf[b] = v[b];
  }
  for (unsigned b = 0; b < count; ++b) {
    if (ovf[b]) continue;
    const uint32_t best = dev.read_word(b, best_word);
    if (best == none) continue;
    const uint32_t ordinal = dev.read_word(b, idx_word);
    if (ordinal < 1 || ordinal > broadcasts) {
      throw std::logic_error("fmpp::isect: block " + std::to_string(b) + " holds broadcast number " +
                             std::to_string(ordinal) + " of " + std::to_string(broadcasts));
    }
    on_hit(b, best, ordinal - 1);
  }
  return ovf;
}

// ------------------------------------------------------------------- culling
struct Sphere {
  glm::dvec3 c;
  double r;
};

std::vector<Sphere> bounding_spheres(const std::vector<Triangle>& tris) {
  std::vector<Sphere> out;
  for (const Triangle& t : tris) {
    const glm::dvec3 c = (t.p[0] + t.p[1] + t.p[2]) / 3.0;
    double r = 0;
    for (const glm::dvec3& p : t.p) r = std::max(r, glm::length(p - c));
    out.push_back(Sphere{c, r});
  }
  return out;
}

// The region the rays of a pass can reach: a cone of their directions, with its apex
// fattened to a ball holding all their origins, cut at the farthest tmax.
struct Cone {
  bool all = true;  // no useful bound
  glm::dvec3 apex{0};
  double apex_r = 0;
  glm::dvec3 axis{0};
  double half_angle = 0;
  double reach = kInf;
};

Cone pass_cone(const std::vector<Ray>& rays, const std::vector<size_t>& idx, size_t begin, size_t end) {
  Cone c;
  glm::dvec3 lo(kInf), hi(-kInf), sum(0);
  for (size_t k = begin; k < end; ++k) {
    const Ray& r = rays[idx[k]];
    lo = glm::min(lo, r.o);
    hi = glm::max(hi, r.o);
    sum += glm::normalize(r.d);
  }
  if (glm::length(sum) < 1e-9) return c;
  c.all = false;
  c.apex = 0.5 * (lo + hi);
  c.apex_r = 0.5 * glm::length(hi - lo);
  c.axis = glm::normalize(sum);
  double reach = 0;
  for (size_t k = begin; k < end; ++k) {
    const Ray& r = rays[idx[k]];
    c.half_angle = std::max(c.half_angle, std::acos(std::clamp(glm::dot(glm::normalize(r.d), c.axis), -1.0, 1.0)));
    reach = std::max(reach, glm::length(r.o - c.apex) + r.tmax * glm::length(r.d));
  }
  c.reach = reach;
  return c;
}

// Conservative: false only if no point of the sphere is within the cone (plus an
// angular margin far above the fixed-point error, so no false hit is culled either).
bool may_hit(const Cone& c, const Sphere& s, double margin) {
  if (c.all) return true;
  const glm::dvec3 d = s.c - c.apex;
  const double dist = glm::length(d), rr = s.r + c.apex_r;
  if (dist <= rr) return true;
  if (dist - rr > c.reach) return false;
  const double phi = std::acos(std::clamp(glm::dot(d, c.axis) / dist, -1.0, 1.0));
  return phi <= c.half_angle + std::asin(std::min(1.0, rr / dist)) + margin;
}

double cull_margin(const KernelOptions& o) { return 1e-3 + std::ldexp(1.0, 12 - static_cast<int>(o.n)); }

class Group {
 public:
  Group(Device& dev, const KernelOptions& opt, const std::vector<Triangle>& tris, const glm::dvec3& origin,
        KernelStats* st)
      : dev_(dev), opt_(opt), tris_(tris), o_(origin), st_(st), cfg_(dev.config()) {}

  // Results for rays[idx[k]] go to out[idx[k]].
  void run(const std::vector<Ray>& rays, const std::vector<size_t>& idx, std::vector<Hit>& out) {
    if (opt_.mapping == Mapping::kRay) {
      run_ray_parallel(rays, idx, out);
    } else {
      run_object_parallel(rays, idx, out);
    }
  }

 private:
  uint64_t push(const Program& p) {
    const uint64_t c0 = dev_.cycles();
    dev_.push(p.code());
    st_->instructions += p.size();
    return dev_.cycles() - c0;
  }

  // ---------------------------------------------------------------- ray-parallel
  void run_ray_parallel(const std::vector<Ray>& rays, const std::vector<size_t>& idx, std::vector<Hit>& out) {
    const unsigned n = opt_.n;
    const double cond_limit = std::ldexp(1.0, static_cast<int>(effective_cond_bits(opt_)));
    // Scale of each ray's components: its largest becomes 2^vbits (sv_i = max_i / 2^vbits),
    // so every ray's V_q has the same magnitude whatever the length of its direction.
    double vq_len = 0;  // largest |V_q|
    for (size_t i : idx) {
      const glm::dvec3& d = rays[i].d;
      vq_len = std::max(vq_len, glm::length(d) / max_component(d) * std::ldexp(1.0, static_cast<int>(opt_.vbits)));
    }
    auto ray_scale = [&](const glm::dvec3& d) { return max_component(d) / std::ldexp(1.0, static_cast<int>(opt_.vbits)); };
    // Common exponent E for the compared sums: S = 1/lambda <= |V_q| / dmin (lambda in
    // units of V_q), and S_c = S / 2^(E+1) must stay below 2^29.
    const DistanceRange dr = distance_range(tris_, o_);
    const double dmin = std::max(dr.min, dr.max * std::ldexp(1.0, -20));
    const double e_real = std::ceil(std::log2(vq_len / (dmin * std::ldexp(1.0, 29))));
    if (!std::isfinite(e_real)) throw std::logic_error("fmpp::isect: no finite scale for the compared sums");
    const int E = static_cast<int>(e_real) - 1;

    // Per-triangle programs (the same in every pass).
    std::vector<Program> progs;
    std::vector<size_t> test_sizes;
    std::vector<int> host;
    std::vector<int> fmpp_tris;
    double t_scale = std::ldexp(1.0, E + 1);  // 1/t = S_c * t_scale * sv_i for ray i
    if (opt_.watertight) {
      t_scale = watertight_programs(&progs, &test_sizes, &fmpp_tris, &host);
    }
    for (size_t k = 0; k < tris_.size() && !opt_.watertight; ++k) {
      double m[3][3];
      int64_t x[9];
      if (!inverse_from(tris_[k], o_, cond_limit, m)) {
        host.push_back(static_cast<int>(k));
        continue;
      }
      const int e = mantissas(&m[0][0], 9, n - 1, x);
      size_t test_size = 0;
      progs.push_back(ray_program(x, e - E, &test_size));
      test_sizes.push_back(test_size);
      fmpp_tris.push_back(static_cast<int>(k));
    }
    st_->host_triangles += host.size();

    const std::vector<Sphere> spheres = bounding_spheres(tris_);
    const unsigned B = cfg_.blocks;
    const uint64_t planned = (idx.size() + B - 1) / B;
    for (size_t base = 0; base < idx.size(); base += B) {
      const unsigned count = static_cast<unsigned>(std::min<size_t>(B, idx.size() - base));
      ++st_->passes;
      // The triangles this pass broadcasts.
      std::vector<size_t> pass_order;
      const Cone cone = opt_.cull ? pass_cone(rays, idx, base, base + count) : Cone{};
      for (size_t k = 0; k < progs.size(); ++k) {
        if (may_hit(cone, spheres[fmpp_tris[k]], cull_margin(opt_))) {
          pass_order.push_back(k);
        } else {
          ++st_->culled;
        }
      }
      // Load: ray components into words 0..2, then select the blocks holding rays.
      uint64_t c0 = dev_.cycles();
      for (unsigned b = 0; b < count; ++b) {
        const glm::dvec3& d = rays[idx[base + b]].d;
        const int64_t lim = int64_t{1} << opt_.vbits;
        const double sv = ray_scale(d);
        dev_.write_word(b, kRV + 0, static_cast<uint32_t>(quantize(d.x, sv, lim, "ray component")));
        dev_.write_word(b, kRV + 1, static_cast<uint32_t>(quantize(d.y, sv, lim, "ray component")));
        dev_.write_word(b, kRV + 2, static_cast<uint32_t>(quantize(d.z, sv, lim, "ray component")));
      }
      Program init;
      select_below(init, count, B);
      init << flagop(map::kFlagV, 0, 0, lut::kZero);  // overflow is judged per pass
      init.mask(0);
      init << writes(kRBest, 0, kSel) << writes(kRIdx, 0, kSel) << writes(kRCnt, 0, kSel) << writes(kROne, 1, kSel);
      init.mask(0x7FFFFFFFu);  // the broadcasts keep this mask throughout
      push(init);
      st_->load_cycles += dev_.cycles() - c0;

      // Broadcast every triangle the pass can reach.
      c0 = dev_.cycles();
      for (size_t k : pass_order) {
        push(progs[k]);
        count_broadcast(st_, progs[k].size(), test_sizes[k]);
      }
      st_->compute_cycles += dev_.cycles() - c0;

      // Read back: overflow flags, then each block's best S (0: no hit) and index.
      c0 = dev_.cycles();
      for (unsigned b = 0; b < count; ++b) out[idx[base + b]] = Hit{};
      const std::vector<bool> ovf =
          read_pass(dev_, count, kRBest, kRIdx, 0, pass_order.size(), [&](unsigned b, uint32_t s, size_t pos) {
            Hit& h = out[idx[base + b]];
            h.tri = fmpp_tris[pass_order[pos]];
            h.t = 1.0 / (static_cast<double>(s) * t_scale * ray_scale(rays[idx[base + b]].d));
          });
      st_->readback_cycles += dev_.cycles() - c0;

      // Host work: overflowed rays completely, and the host triangles for every ray.
      for (unsigned b = 0; b < count; ++b) {
        const size_t i = idx[base + b];
        if (ovf[b]) {
          ++st_->overflow_rays;
          out[i] = Hit{};
          merge_host(rays[i], tris_, fmpp_tris, &out[i], st_);
        }
        merge_host(rays[i], tris_, host, &out[i], st_);
      }
      if (opt_.progress) opt_.progress(base / B + 1, planned);
    }
  }

  // One triangle broadcast: T = X V, inside test, S = T1+T2+T3 scaled by 2^shift to the
  // common exponent, compare with the block's best and keep the larger.
  // Watertight programs: vertices relative to the origin snapped to a grid of b-bit
  // integers (b = (n - 3) / 2, so that the edge constants c_i = P_j x P_k fit n bits),
  // rows A_i = floor(c_i . V / 2^n), whose signs are exact (floor(x / 2^n) >= 0 iff
  // x >= 0); c_i are negated for triangles seen clockwise, so a shared edge gets
  // complementary constants. The compared sum S comes from a fourth row, (sum c_i) / det
  // with one exponent for all triangles. Triangles the grid makes degenerate go to
  // `host`. Returns the scale with 1/t = S_c * scale * sv (sv: the ray's scale).
  double watertight_programs(std::vector<Program>* progs, std::vector<size_t>* test_sizes,
                             std::vector<int>* fmpp_tris, std::vector<int>* host) {
    const unsigned n = opt_.n;
    const int b = (static_cast<int>(n) - 3) / 2;
    double pmax = 0;
    for (const Triangle& t : tris_) {
      for (const glm::dvec3& p : t.p) pmax = std::max({pmax, std::abs(p.x - o_.x), std::abs(p.y - o_.y), std::abs(p.z - o_.z)});
    }
    if (!(pmax > 0)) pmax = 1;
    const double sp = pmax / std::ldexp(1.0, b);
    struct W {
      int index;
      int64_t c[3][3];
      double w[3];
    };
    std::vector<W> ws;
    double wmax = 0;
    for (size_t k = 0; k < tris_.size(); ++k) {
      int64_t q[3][3];
      for (int v = 0; v < 3; ++v) {
        for (int j = 0; j < 3; ++j) q[v][j] = std::llround((tris_[k].p[v][j] - o_[j]) / sp);
      }
      W w;
      w.index = static_cast<int>(k);
      for (int i = 0; i < 3; ++i) {
        const int64_t* a = q[(i + 1) % 3];
        const int64_t* c = q[(i + 2) % 3];
        w.c[i][0] = a[1] * c[2] - a[2] * c[1];
        w.c[i][1] = a[2] * c[0] - a[0] * c[2];
        w.c[i][2] = a[0] * c[1] - a[1] * c[0];
      }
      const __int128 det = static_cast<__int128>(q[0][0]) * w.c[0][0] + static_cast<__int128>(q[0][1]) * w.c[0][1] +
                           static_cast<__int128>(q[0][2]) * w.c[0][2];
      if (det == 0) {
        // Smaller than the grid (or seen edge-on from the origin once snapped): the grid
        // cannot represent it, but the reference may still hit it (a tiny triangle near
        // the eye covers many rays). The host tests the exact triangle; that only adds
        // hits, so no ray can leak through where the snapped mesh was closed.
        ++st_->snapped_degenerate;
        host->push_back(static_cast<int>(k));
        continue;
      }
      const int sign = det > 0 ? 1 : -1;
      for (auto& row : w.c) {
        for (auto& v : row) v *= sign;
      }
      for (int j = 0; j < 3; ++j) {
        w.w[j] = static_cast<double>(w.c[0][j] + w.c[1][j] + w.c[2][j]) / (static_cast<double>(det) * sign);
        wmax = std::max(wmax, std::abs(w.w[j]));
      }
      ws.push_back(w);
    }
    const int Ew = wmax > 0 ? static_cast<int>(std::floor(std::log2(wmax))) + 1 : 0;
    const double wscale = std::ldexp(1.0, static_cast<int>(n) - 1 - Ew);
    for (const W& w : ws) {
      Program p;
      p.assume_mask(0x7FFFFFFFu);
      p << add(kRCnt, kRCnt, kROne, kSel);
      std::vector<Row> rows(4);
      for (unsigned i = 0; i < 4; ++i) {
        rows[i].r = i < 3 ? kRT + i : kRS;
        for (unsigned j = 0; j < 3; ++j) {
          const int64_t c = i < 3 ? w.c[i][j] : std::llround(w.w[j] * wscale);
          rows[i].terms.push_back(Term{kRV + j, c, 0});
        }
      }
      dot_rows_const(p, rows, n, kSel);
      nonneg(p, kHit, kSel, kRT + 0);
      nonneg(p, kHit, kHit, kRT + 1);
      nonneg(p, kHit, kHit, kRT + 2);
      test_sizes->push_back(p.size());
      // win <- hit and S > best (best >= 0; S <= 0 never wins)
      p << sub(kRD, kRBest, kRS, kHit);
      p << ref(RefFn::kAnd, RefPart::kData, kRD, 0x80000000u, kWin, kHit);
      p << func(FuncFn::kOr, kRBest, kRS, kRS, kWin);
      p << func(FuncFn::kOr, kRIdx, kRCnt, kRCnt, kWin);
      progs->push_back(p);
      fmpp_tris->push_back(w.index);
    }
    // S_c = floor(sum w_q V_q / 2^n) = (w . V) / (2^(Ew+1) sv) in grid units; the grid
    // shrinks distances by sp, so 1/t = S_c 2^(Ew+1) sv / sp (sv: the ray's scale).
    return std::ldexp(1.0, Ew + 1) / sp;
  }

  // *test_size gets the instructions up to the inside test (the paper's count).
  Program ray_program(const int64_t x[9], int shift, size_t* test_size) const {
    Program p;
    p.assume_mask(0x7FFFFFFFu);  // set by the pass's init, and kept by every broadcast
    p << add(kRCnt, kRCnt, kROne, kSel);
    std::vector<Row> rows(3);
    for (unsigned i = 0; i < 3; ++i) {
      rows[i].r = kRT + i;
      for (unsigned j = 0; j < 3; ++j) rows[i].terms.push_back(Term{kRV + j, x[3 * i + j], kRX + 3 * i + j});
    }
    if (opt_.mul == MulMode::kGeneric) {
      p.mask(0);
      for (unsigned k = 0; k < 9; ++k) p << writes(kRX + k, static_cast<uint32_t>(x[k]), kSel);
      dot_rows(p, rows, opt_.n, kSel, kTmp);
    } else {
      p.mask(0x7FFFFFFFu);
      dot_rows_const(p, rows, opt_.n, kSel);
    }
    nonneg(p, kHit, kSel, kRT + 0);
    nonneg(p, kHit, kHit, kRT + 1);
    nonneg(p, kHit, kHit, kRT + 2);
    *test_size = p.size();
    p << add(kRS, kRT + 0, kRT + 1, kHit) << add(kRS, kRS, kRT + 2, kHit);
    for (int s = 0; s < shift; ++s) p << lshift(kRS, kRS, kHit);  // overflow sets V
    for (int s = 0; s > shift; --s) p << rshift(kRS, kRS, kHit);
    // win <- hit and best - S < 0 (S > best >= 0; a tie keeps the earlier, lower index)
    p << sub(kRD, kRBest, kRS, kHit);
    p.mask(0x7FFFFFFFu);
    p << ref(RefFn::kAnd, RefPart::kData, kRD, 0x80000000u, kWin, kHit);
    p << func(FuncFn::kOr, kRBest, kRS, kRS, kWin);
    p << func(FuncFn::kOr, kRIdx, kRCnt, kRCnt, kWin);
    return p;
  }

  // ------------------------------------------------------------- object-parallel
  void run_object_parallel(const std::vector<Ray>& rays, const std::vector<size_t>& idx, std::vector<Hit>& out) {
    const unsigned n = opt_.n, mb = opt_.mbits;
    const double cond_limit = std::ldexp(1.0, static_cast<int>(effective_cond_bits(opt_)));
    // Each ray's components get their own scale: the largest becomes vlim.
    const int64_t vlim = (int64_t{1} << (n - 1)) - 1;
    auto ray_scale = [&](const glm::dvec3& d) { return max_component(d) / static_cast<double>(vlim); };

    // Triangle data: X = mantissas of P^-1 (own exponent), Y = mantissas of its column
    // sums (S = sum_j s_j V_j) with one exponent for all triangles.
    struct Tri {
      int index;
      int64_t x[9];
      double s[3];
    };
    std::vector<Tri> data;
    std::vector<int> host;
    // The one exponent of Y is set by the largest column sums s_max, and a hit at distance
    // d has S_c ~ 2^(mb-2) / (s_max d) or more (S >= 1/d per unit of the ray's largest
    // component). Capping s_max at 2^(mb-12) / d_max (d_max: the farthest vertex) leaves
    // every possible hit 10 bits of S_c or more. A triangle above the cap has its plane
    // close to the eye (S of its hits is a small difference of large terms); on the FMPP
    // it would take the bits of S from every other triangle, silently (their hits compare
    // wrongly or vanish at S_c = 0), so it goes to the host like an ill-conditioned one.
    const double s_limit = std::ldexp(1.0, static_cast<int>(mb) - 12) / distance_range(tris_, o_).max;
    double smax = 0;
    for (size_t k = 0; k < tris_.size(); ++k) {
      double m[3][3];
      if (!inverse_from(tris_[k], o_, cond_limit, m)) {
        host.push_back(static_cast<int>(k));
        continue;
      }
      Tri t;
      t.index = static_cast<int>(k);
      mantissas(&m[0][0], 9, mb, t.x);
      double tmax = 0;
      for (int j = 0; j < 3; ++j) {
        t.s[j] = m[0][j] + m[1][j] + m[2][j];
        tmax = std::max(tmax, std::abs(t.s[j]));
      }
      if (!(tmax <= s_limit)) {
        host.push_back(static_cast<int>(k));
        continue;
      }
      smax = std::max(smax, tmax);
      data.push_back(t);
    }
    st_->host_triangles += host.size();
    const int Es = (smax > 0) ? static_cast<int>(std::floor(std::log2(smax))) + 1 : 0;
    const double yscale = std::ldexp(1.0, static_cast<int>(mb) - Es);
    // S_c = floor(sum v_j y_j / 2^n) = S * yscale / (sv * 2^n); S_c < 1.5 * 2^mb. (sv: the
    // ray's scale; S_c is only ever compared between triangles for one ray.)
    const unsigned sbits = mb + 1;

    std::vector<Hit> best(idx.size());
    std::vector<double> best_s(idx.size(), 0);
    const unsigned B = cfg_.blocks;
    for (size_t base = 0; base < data.size(); base += B) {
      const unsigned count = static_cast<unsigned>(std::min<size_t>(B, data.size() - base));
      ++st_->passes;
      uint64_t c0 = dev_.cycles();
      for (unsigned b = 0; b < count; ++b) {
        const Tri& t = data[base + b];
        for (unsigned k = 0; k < 9; ++k) dev_.write_word(b, kOX + k, static_cast<uint32_t>(t.x[k]));
        for (unsigned j = 0; j < 3; ++j) {
          const int64_t y = std::llround(t.s[j] * yscale);
          dev_.write_word(b, kOY + j, static_cast<uint32_t>(y));
        }
      }
      Program init;
      select_below(init, count, B);
      init << flagop(kLoaded, kSel, kSel, lut::kA) << flagop(map::kFlagV, 0, 0, lut::kZero);
      push(init);
      st_->load_cycles += dev_.cycles() - c0;

      std::vector<int32_t> v(3);
      for (size_t r = 0; r < idx.size(); ++r) {
        const glm::dvec3& d = rays[idx[r]].d;
        const double sv = ray_scale(d);
        v[0] = quantize(d.x, sv, vlim, "ray component");
        v[1] = quantize(d.y, sv, vlim, "ray component");
        v[2] = quantize(d.z, sv, vlim, "ray component");
        size_t test_size = 0;
        const Program p = object_program(v, sbits, &test_size);
        c0 = dev_.cycles();
        push(p);
        count_broadcast(st_, p.size(), test_size);
        st_->compute_cycles += dev_.cycles() - c0;
        c0 = dev_.cycles();
        const Responders resp = dev_.responders();
        if (resp.any) {
          const uint32_t s = dev_.read_word(resp.first, kOS);
          // Strictly larger: an earlier pass (lower triangle indices) keeps a tie.
          if (static_cast<double>(s) > best_s[r]) {
            best_s[r] = s;
            best[r].tri = data[base + resp.first].index;
          }
        }
        st_->readback_cycles += dev_.cycles() - c0;
      }
      // Overflow in a block taints that triangle: redo it on the host for every ray.
      c0 = dev_.cycles();
      if (dev_.overflow()) {
        const std::vector<bool> f = dev_.read_flag_all(map::kFlagV);
        for (unsigned b = 0; b < count; ++b) {
          if (!f[b]) continue;
          ++st_->overflow_triangles;
          host.push_back(data[base + b].index);
          for (size_t r = 0; r < idx.size(); ++r) {
            if (best[r].tri == data[base + b].index) {  // its win is not trusted: redo the ray
              best[r] = Hit{};
              best_s[r] = -1;  // recomputed below
            }
          }
        }
      }
      st_->readback_cycles += dev_.cycles() - c0;
    }
    const double s_to_inv_t = std::ldexp(1.0, static_cast<int>(n)) / yscale;  // times the ray's scale
    for (size_t r = 0; r < idx.size(); ++r) {
      const size_t i = idx[r];
      Hit h = best[r];
      if (best_s[r] < 0) {  // a tainted winner: redo the whole ray on the host
        ++st_->overflow_rays;
        h = Hit{};
        std::vector<int> all(tris_.size());
        for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
        merge_host(rays[i], tris_, all, &h, st_);
      } else {
        if (h.hit()) h.t = 1.0 / (best_s[r] * s_to_inv_t * ray_scale(rays[i].d));
        merge_host(rays[i], tris_, host, &h, st_);
      }
      out[i] = h;
    }
  }

  // One ray broadcast: T = X v and S = Y v in every loaded block, inside test, then the
  // maximum search; SEL ends as the blocks holding the nearest hit.
  Program object_program(const std::vector<int32_t>& v, unsigned sbits, size_t* test_size) const {
    Program p;
    std::vector<Row> rows(4);
    for (unsigned i = 0; i < 4; ++i) {
      rows[i].r = (i < 3) ? kOT + i : kOS;
      for (unsigned j = 0; j < 3; ++j) {
        const unsigned y = (i < 3) ? kOX + 3 * i + j : kOY + j;
        rows[i].terms.push_back(Term{y, v[j], kOV + j});
      }
    }
    if (opt_.mul == MulMode::kGeneric) {
      p.mask(0);
      for (unsigned j = 0; j < 3; ++j) p << writes(kOV + j, static_cast<uint32_t>(v[j]), kLoaded);
      dot_rows(p, rows, opt_.n, kLoaded, kTmp);
    } else {
      dot_rows_const(p, rows, opt_.n, kLoaded);
    }
    nonneg(p, kHit, kLoaded, kOT + 0);
    nonneg(p, kHit, kHit, kOT + 1);
    nonneg(p, kHit, kHit, kOT + 2);
    *test_size = p.size();
    nonneg(p, kHit, kHit, kOS);
    p.mask(0);
    p << ref(RefFn::kAnd, RefPart::kData, kOS, 0, kTmp, kHit);  // S = 0: not in front of the origin
    p << flagop(kHit, kHit, kTmp, lut::kAndNotB);
    max_search(p, kHit, kTmp, kOS, sbits);
    p << flagop(kSel, kHit, kHit, lut::kA);
    return p;
  }

  Device& dev_;
  const KernelOptions& opt_;
  const std::vector<Triangle>& tris_;
  glm::dvec3 o_;
  KernelStats* st_;
  Config cfg_;
};

// ---------------------------------------------------------- arbitrary origins
// Ray-parallel with a different origin in every block (docs/intersection.md, "Rays
// with their own origins"). With A = P1 - O etc., T_i det(P - O) = c_i . V + e_i . L,
// where c_i = P_j x P_k and e_i = P_k - P_j depend on the triangle only and L = O x V
// (the ray's Pluecker moment) on the ray only. The hit needs the three A_i and their sum
// nv = n . V to share the sign of det = n . (P1 - O); its distance is t = det / nv,
// which each hitting block computes by restoring division into a q-bit quotient.
class General {
 public:
  General(Device& dev, const KernelOptions& opt, const std::vector<Triangle>& tris, KernelStats* st)
      : dev_(dev), opt_(opt), tris_(tris), st_(st), cfg_(dev.config()) {}

  void run(const std::vector<Ray>& rays, const std::vector<size_t>& idx, std::vector<Hit>& out) {
    const unsigned n = opt_.n, q = opt_.qbits;
    st_->general_rays += idx.size();
    // Work relative to the scene's centre: smaller coordinates, less cancellation.
    glm::dvec3 lo(kInf), hi(-kInf);
    for (const Triangle& t : tris_) {
      for (const glm::dvec3& p : t.p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    const glm::dvec3 c = 0.5 * (lo + hi);
    double vmax = 0, lmax = 0, omax = 0, lambda_max = 0, o_reach = 0;
    for (size_t i : idx) {
      const Ray& r = rays[i];
      const glm::dvec3 o = r.o - c, l = glm::cross(o, r.d);
      o_reach = std::max(o_reach, glm::length(o));
      vmax = std::max(vmax, max_component(r.d));
      lmax = std::max(lmax, max_component(l));
      omax = std::max(omax, max_component(o));
      // No hit is farther than the farthest corner of the scene box.
      double far = 0;
      for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        far = std::max(far, glm::length(corner - r.o));
      }
      lambda_max = std::max(lambda_max, 1.25 * far / glm::length(r.d));
    }
    const double unit = std::ldexp(1.0, kBits);
    // A batch whose moments (or origins) are all 0 still needs scales of their natural
    // size: a far larger one would crowd the triangle's other coefficients out of the
    // shared exponent (rays along a line through the centre would all miss).
    const double span = std::max(max_component(hi - lo), std::numeric_limits<double>::min());
    const double sv = vmax / unit, sl = (lmax > 0 ? lmax : vmax * span) / unit, so = (omax > 0 ? omax : span) / unit;
    const double u = lambda_max / std::ldexp(1.0, static_cast<int>(q));  // quotient unit

    std::vector<Program> progs;
    std::vector<size_t> test_sizes, excl_pos;
    std::vector<int> order;  // triangle of each program
    std::vector<int> host;   // ill-conditioned triangles, tested on the host
    const double cond_limit =
        std::ldexp(1.0, opt_.cond_bits >= 0 ? opt_.cond_bits : static_cast<int>(n) - 4);
    for (size_t k = 0; k < tris_.size(); ++k) {
      const glm::dvec3 p1 = tris_[k].p[0] - c, p2 = tris_[k].p[1] - c, p3 = tris_[k].p[2] - c;
      const glm::dvec3 cc[3] = {glm::cross(p2, p3), glm::cross(p3, p1), glm::cross(p1, p2)};
      const glm::dvec3 ee[3] = {p3 - p2, p1 - p3, p2 - p1};
      const glm::dvec3 nrm = cc[0] + cc[1] + cc[2];
      if (nrm == glm::dvec3(0)) continue;  // degenerate: no ray can hit it, nor can the reference
      // Conditioning of the edge tests: A_i is quantized with one step for the triangle's
      // 18 coefficients, about 2^-(n-1) of |V| e_max max(R, O) (R: the farthest vertex
      // from the centre, O: the farthest origin), while a ray through the triangle has
      // |A_i| of about |V| e_i h / 3 (h: the smallest altitude). Beyond cond_limit the
      // signs near the middle of the triangle are no longer reliable: host.
      double emax = 0, emin = kInf;
      for (const glm::dvec3& e : ee) {
        emax = std::max(emax, glm::length(e));
        emin = std::min(emin, glm::length(e));
      }
      const double reach = std::max({glm::length(p1), glm::length(p2), glm::length(p3), o_reach});
      const double cond = emax * emax * reach / (emin * glm::length(nrm));  // (e_max/e_min) reach / h_min
      if (!(cond <= cond_limit)) {
        host.push_back(static_cast<int>(k));
        continue;
      }
      double a[18];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          a[6 * i + j] = cc[i][j] * sv;
          a[6 * i + 3 + j] = ee[i][j] * sl;
        }
      }
      int64_t xa[18];
      const int ea = mantissas(a, 18, n - 1, xa);
      // det row, pre-scaled so that its value N makes floor(N 2^(q-1) / nv) = t / u.
      const double K = std::ldexp(1.0, 1 - static_cast<int>(q) - (1 + ea)) / u;
      const double d[4] = {-nrm.x * so * K, -nrm.y * so * K, -nrm.z * so * K, glm::dot(nrm, p1) / unit * K};
      int64_t xd[4];
      const int ed = mantissas(d, 4, n - 1, xd);
      order.push_back(static_cast<int>(k));
      size_t test_size = 0, pos = 0;
      progs.push_back(program(xa, xd, ed + 1, &test_size, &pos));
      test_sizes.push_back(test_size);
      excl_pos.push_back(pos);
    }

    st_->host_triangles += host.size();
    const std::vector<Sphere> spheres = bounding_spheres(tris_);
    const unsigned B = cfg_.blocks;
    const uint64_t planned = (idx.size() + B - 1) / B;
    const int64_t lim = int64_t{1} << kBits;
    for (size_t base = 0; base < idx.size(); base += B) {
      const unsigned count = static_cast<unsigned>(std::min<size_t>(B, idx.size() - base));
      ++st_->passes;
      std::vector<size_t> pass_order;  // programs this pass broadcasts
      std::vector<uint32_t> ordinal_of(progs.size(), 0);
      const Cone cone = opt_.cull ? pass_cone(rays, idx, base, base + count) : Cone{};
      for (size_t k = 0; k < progs.size(); ++k) {
        if (may_hit(cone, spheres[order[k]], cull_margin(opt_))) {
          pass_order.push_back(k);
          ordinal_of[k] = static_cast<uint32_t>(pass_order.size());
        } else {
          ++st_->culled;
        }
      }
      uint64_t c0 = dev_.cycles();
      for (unsigned b = 0; b < count; ++b) {
        const Ray& r = rays[idx[base + b]];
        const glm::dvec3 o = r.o - c, l = glm::cross(o, r.d);
        for (int j = 0; j < 3; ++j) {
          dev_.write_word(b, kV + j, static_cast<uint32_t>(quantize(r.d[j], sv, lim, "ray direction")));
          dev_.write_word(b, kL + j, static_cast<uint32_t>(quantize(l[j], sl, lim, "ray moment")));
          dev_.write_word(b, kO + j, static_cast<uint32_t>(quantize(o[j], so, lim, "ray origin")));
        }
        const double qmin = std::ceil(r.tmin / u);
        dev_.write_word(b, kQmin, static_cast<uint32_t>(std::min(qmin, std::ldexp(1.0, 30))));
        uint32_t excl = 0;  // broadcast number of the excluded triangle in this pass, 0 for none
        for (size_t k = 0; k < order.size(); ++k) {
          if (order[k] == r.exclude) excl = ordinal_of[k];
        }
        dev_.write_word(b, kExcl, excl);
      }
      Program init;
      select_below(init, count, B);
      init << flagop(map::kFlagV, 0, 0, lut::kZero);
      init.mask(0);
      init << writes(kBest, 0x7FFFFFFFu, kSel) << writes(kIdx, 0, kSel) << writes(kCnt, 0, kSel)
           << writes(kOne, 1, kSel) << writes(kZero, 0, kSel) << writes(kUnit, 1u << kBits, kSel);
      init.mask(0x7FFFFFFFu);
      push(init);
      st_->load_cycles += dev_.cycles() - c0;

      c0 = dev_.cycles();
      std::vector<uint64_t> code;
      for (size_t k : pass_order) {
        // The exclusion test compares with this broadcast's number in the pass.
        code = progs[k].code();
        code[excl_pos[k]] = (code[excl_pos[k]] & ~uint64_t{0xFFFFFFFF}) | ordinal_of[k];
        dev_.push(code);
        st_->instructions += code.size();
        count_broadcast(st_, code.size(), test_sizes[k]);
      }
      st_->compute_cycles += dev_.cycles() - c0;

      c0 = dev_.cycles();
      for (unsigned b = 0; b < count; ++b) out[idx[base + b]] = Hit{};
      const std::vector<bool> ovf =
          read_pass(dev_, count, kBest, kIdx, 0x7FFFFFFFu, pass_order.size(), [&](unsigned b, uint32_t qv, size_t pos) {
            Hit& h = out[idx[base + b]];
            h.tri = order[pass_order[pos]];
            h.t = (qv + 0.5) * u;
          });
      st_->readback_cycles += dev_.cycles() - c0;
      // Host work: overflowed rays completely, and the host triangles for every ray.
      std::vector<int> all;
      for (unsigned b = 0; b < count; ++b) {
        const size_t i = idx[base + b];
        if (!ovf[b]) {
          merge_host(rays[i], tris_, host, &out[i], st_);
          continue;
        }
        ++st_->overflow_rays;
        if (all.empty()) {
          for (size_t k = 0; k < tris_.size(); ++k) all.push_back(static_cast<int>(k));
        }
        out[i] = Hit{};
        merge_host(rays[i], tris_, all, &out[i], st_);
      }
      if (opt_.progress) opt_.progress(base / B + 1, planned);
    }
  }

 private:
  static constexpr int kBits = 25;  // ray data magnitudes: 6-term rows stay below 2^31
  // Words.
  static constexpr unsigned kV = 0, kL = 3, kO = 6, kA = 9, kDet = 12, kNv = 13, kTmp = 14, kQ = 15, kBest = 16,
                            kIdx = 17, kCnt = 18, kOne = 19, kZero = 20, kUnit = 21, kQmin = 22, kExcl = 23;
  // Flags (kSel, kHit, kWin, kTmp from the file scope; 4 = det < 0).
  static constexpr unsigned kNeg = 4;
  static_assert(kExcl < kGeneralWords, "the kernel's words fit the advertised count");

  uint64_t push(const Program& p) {
    const uint64_t c0 = dev_.cycles();
    dev_.push(p.code());
    st_->instructions += p.size();
    return dev_.cycles() - c0;
  }

  // *excl_pos gets the index of the REF whose key must be set to the broadcast's number.
  Program program(const int64_t xa[18], const int64_t xd[4], int dshift, size_t* test_size, size_t* excl_pos) const {
    const unsigned flag_tmp = isect::kTmp;
    Program p;
    p.assume_mask(0x7FFFFFFFu);
    p << add(kCnt, kCnt, kOne, kSel);
    std::vector<Row> rows(4);
    for (unsigned i = 0; i < 3; ++i) {
      rows[i].r = kA + i;
      for (unsigned j = 0; j < 3; ++j) {
        rows[i].terms.push_back(Term{kV + j, xa[6 * i + j], 0});
        rows[i].terms.push_back(Term{kL + j, xa[6 * i + 3 + j], 0});
      }
    }
    rows[3].r = kDet;
    for (unsigned j = 0; j < 3; ++j) rows[3].terms.push_back(Term{kO + j, xd[j], 0});
    rows[3].terms.push_back(Term{kUnit, xd[3], 0});
    dot_rows_const(p, rows, opt_.n, kSel);
    p << add(kNv, kA + 0, kA + 1, kSel) << add(kNv, kNv, kA + 2, kSel);
    // Where det < 0, negate det, the A_i and nv: then det > 0, A_i >= 0 and nv > 0 mean a hit.
    p << ref(RefFn::kAnd, RefPart::kData, kDet, 0x80000000u, kNeg, kSel);
    for (unsigned w : {kDet, kA + 0, kA + 1, kA + 2, kNv}) p << sub(w, kZero, w, kNeg);
    nonneg(p, kHit, kSel, kA + 0);
    nonneg(p, kHit, kHit, kA + 1);
    nonneg(p, kHit, kHit, kA + 2);
    *test_size = p.size();
    for (unsigned w : {kDet, kNv}) {  // strictly positive: w - 1 >= 0
      p << sub(kTmp, w, kOne, kHit);
      nonneg(p, kHit, kHit, kTmp);
    }
    // The ray's own triangle (a secondary ray leaving its surface) never counts.
    p.mask(0);
    *excl_pos = p.size();
    p << ref(RefFn::kAnd, RefPart::kData, kExcl, 0, flag_tmp, kHit);
    p << flagop(kHit, kHit, flag_tmp, lut::kAndNotB);
    p.mask(0x7FFFFFFFu);
    for (int k = 0; k < dshift; ++k) p << lshift(kDet, kDet, kHit);
    for (int k = 0; k > dshift; --k) p << rshift(kDet, kDet, kHit);
    // t must be below the range of the quotient: det < 2 nv. Otherwise flag the ray (V) for the host.
    p << sub(kTmp, kDet, kNv, kHit) << sub(kTmp, kTmp, kNv, kHit);
    nonneg(p, flag_tmp, kHit, kTmp);
    p << flagop(map::kFlagV, map::kFlagV, flag_tmp, lut::kOr) << flagop(kHit, kHit, flag_tmp, lut::kAndNotB);
    // Restoring division: Q = floor(det 2^(q-1) / nv), the remainder in det.
    p << func(FuncFn::kXor, kQ, kQ, kQ, kHit);
    for (int j = static_cast<int>(opt_.qbits) - 1; j >= 0; --j) {
      p << sub(kTmp, kDet, kNv, kHit);
      nonneg(p, flag_tmp, kHit, kTmp);
      p << func(FuncFn::kOr, kDet, kTmp, kTmp, flag_tmp);
      p << lshift(kQ, kQ, kHit) << add(kQ, kQ, kOne, flag_tmp);
      if (j > 0) p << lshift(kDet, kDet, kHit);
    }
    // Beyond the ray's tmin, and nearer than the best so far.
    p << sub(kTmp, kQ, kQmin, kHit);
    nonneg(p, kHit, kHit, kTmp);
    p << sub(kTmp, kQ, kBest, kHit);
    p << ref(RefFn::kAnd, RefPart::kData, kTmp, 0x80000000u, kWin, kHit);
    p << func(FuncFn::kOr, kBest, kQ, kQ, kWin) << func(FuncFn::kOr, kIdx, kCnt, kCnt, kWin);
    return p;
  }

  Device& dev_;
  const KernelOptions& opt_;
  const std::vector<Triangle>& tris_;
  KernelStats* st_;
  Config cfg_;
};

}  // namespace

void KernelOptions::validate(const Config& cfg) const {
  if (n < 2 || n > 32) throw std::invalid_argument("multiplier bits n = " + std::to_string(n) + " outside [2, 32]");
  if (vbits < 2 || vbits > 28) throw std::invalid_argument("vbits = " + std::to_string(vbits) + " outside [2, 28]");
  if (mbits < 2 || mbits > 28) throw std::invalid_argument("mbits = " + std::to_string(mbits) + " outside [2, 28]");
  if (cond_bits > 60) throw std::invalid_argument("cond_bits = " + std::to_string(cond_bits) + " above 60");
  if (cfg.words < words_needed(*this)) {
    throw std::invalid_argument(std::string(to_string(mapping)) + "-parallel " + to_string(mul) + " needs " +
                                std::to_string(words_needed(*this)) + " words per block; the FMPP has " +
                                std::to_string(cfg.words));
  }
}

unsigned words_needed(const KernelOptions& opt) {
  if (opt.mapping == Mapping::kRay) return opt.mul == MulMode::kGeneric ? kRX + 9 : kRX;
  return opt.mul == MulMode::kGeneric ? kOV + 3 : kOV;
}

RayRoutes route_rays(const std::vector<Ray>& rays, const KernelOptions& opt, unsigned blocks) {
  RayRoutes rr;
  // Group rays by origin: a group shares one set of inverse matrices (the paper's method).
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    // Rays with tmin or an excluded triangle take the general (ray-parallel) kernel in
    // either mapping: the object-parallel maximum search has no per-ray exclusion.
    const bool special = r.tmin > 0 || r.exclude >= 0;
    if (special || (opt.mapping == Mapping::kRay && opt.origins == Origins::kGeneral)) {
      rr.general.push_back(i);
    } else {
      rr.groups[{r.o.x, r.o.y, r.o.z}].push_back(i);
    }
  }
  if (opt.mapping == Mapping::kRay && opt.origins == Origins::kAuto) {
    // Small groups would leave most blocks idle: send them through the general kernel.
    const size_t min_group = std::max<size_t>(16, blocks / 8);
    const bool several = rr.groups.size() > 1 || !rr.general.empty();
    for (auto it = rr.groups.begin(); it != rr.groups.end();) {
      if (it->second.size() < min_group && several) {
        rr.general.insert(rr.general.end(), it->second.begin(), it->second.end());
        it = rr.groups.erase(it);
      } else {
        ++it;
      }
    }
  }
  return rr;
}

std::vector<Hit> intersect_fmpp(Device& dev, const std::vector<Ray>& in_rays, const std::vector<Triangle>& tris,
                                const KernelOptions& opt, KernelStats* stats) {
  opt.validate(dev.config());
  KernelStats local;
  KernelStats& st = stats ? *stats : local;
  const uint64_t c0 = dev.cycles();
  std::vector<Hit> out(in_rays.size());
  validate_input(in_rays, tris);
  // Every direction is scaled by a power of two to a largest component in [1, 2), and its
  // parameters (tmin, tmax, the hit's t) by the inverse: exact, and the kernels' scales
  // then never see a direction's magnitude, only its shape.
  std::vector<Ray> rays(in_rays);
  std::vector<int> t_exp(rays.size(), 0);  // t = t' 2^t_exp
  for (size_t i = 0; i < rays.size(); ++i) {
    Ray& r = rays[i];
    t_exp[i] = -std::ilogb(max_component(r.d));
    r.d = glm::dvec3(std::ldexp(r.d.x, t_exp[i]), std::ldexp(r.d.y, t_exp[i]), std::ldexp(r.d.z, t_exp[i]));
    r.tmin = std::ldexp(r.tmin, -t_exp[i]);
    r.tmax = std::ldexp(r.tmax, -t_exp[i]);
  }
  // No triangle: every ray misses. (The scales below are derived from the scene's
  // extent, which an empty scene does not have.)
  if (tris.empty()) return out;
  const auto [groups, general] = route_rays(rays, opt, dev.config().blocks);
  for (const auto& [origin, idx] : groups) {
    ++st.groups;
    Group g(dev, opt, tris, glm::dvec3(std::get<0>(origin), std::get<1>(origin), std::get<2>(origin)), &st);
    g.run(rays, idx, out);
  }
  if (!general.empty()) {
    if (dev.config().words < kGeneralWords) {
      throw std::invalid_argument("rays with their own origins need " + std::to_string(kGeneralWords) +
                                  " words per block; the FMPP has " + std::to_string(dev.config().words));
    }
    General g(dev, opt, tris, &st);
    g.run(rays, general, out);
  }
  for (size_t i = 0; i < out.size(); ++i) out[i].t = std::ldexp(out[i].t, t_exp[i]);
  st.cycles += dev.cycles() - c0;
  return out;
}

}  // namespace fmpp::isect
