// Filtered exact ray-triangle predicates (see exact.h).
//
// Error bounds of the filter (eps = 2^-53, eta = 2^-1075 the largest rounding error of
// an underflowing product). A triple product x . (y x z) evaluated in double, with y
// and z themselves rounded differences, is the exact sum of its six terms x_i y_j z_k
// each times at most 7 factors (1 + delta), |delta| <= eps (y, z, the product, the
// difference, the product with x, two additions), so its error is at most
// gamma_7 sum |x_i y_j z_k| <= 2 gamma_7 |x|_1 |y|_inf |z|_inf, below 16 eps |x|_1 my mz
// with my, mz the computed max norms (the margin covers the rounding of the bound). A
// rounded x (a = A - O) adds one factor: 52 eps |a|_inf my mz covers 6 gamma_8. An
// underflowing product adds at most eta, carried through at most one product with x:
// (2 |x|_1 + 3) eta (1 + eps)^4 in all, below (4 |x|_1 + 8) 2^-1074. The bound itself
// never underflows because the filter only runs when every max norm is >= 2^-300 (|D|_1
// >= 1e-100 by the input limits); anything smaller goes to the exact evaluation.
#include "sw/isect/exact/exact.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

namespace fmpp::isect::exact {
namespace {

constexpr double kEps = 0x1p-53;
constexpr double kTiny = 0x1p-1074;
constexpr double kMinNorm = 0x1p-300;

double max_norm(const glm::dvec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }
double sum_norm(const glm::dvec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }

// x = m 2^e with m an integer of at most 53 bits (x != 0).
void split(double x, int64_t* m, int* e) {
  int ex;
  const double f = std::frexp(x, &ex);  // |f| in [0.5, 1)
  *m = static_cast<int64_t>(std::ldexp(f, 53));
  *e = ex - 53;
}

// Exponent of the lowest set bit of x != 0.
int low_bit(double x) {
  int64_t m;
  int e;
  split(x, &m, &e);
  return e + __builtin_ctzll(static_cast<uint64_t>(m < 0 ? -m : m));
}

// z = x 2^-s, an integer (s <= low_bit(x)).
void set_scaled(mpz_t z, double x, int s) {
  if (x == 0) {
    mpz_set_ui(z, 0);
    return;
  }
  int64_t m;
  int e;
  split(x, &m, &e);
  mpz_set_si(z, static_cast<long>(m));
  if (e - s >= 0) {
    mpz_mul_2exp(z, z, static_cast<mp_bitcnt_t>(e - s));
  } else {
    mpz_tdiv_q_2exp(z, z, static_cast<mp_bitcnt_t>(s - e));  // exact: s <= low bit
  }
}

// The largest power of two that divides every component of the given vectors (its
// exponent): scaled by its inverse, all are integers.
int common_scale(std::initializer_list<const glm::dvec3*> vs) {
  int s = std::numeric_limits<int>::max();
  for (const glm::dvec3* v : vs) {
    for (int k = 0; k < 3; ++k) {
      if ((*v)[k] != 0) s = std::min(s, low_bit((*v)[k]));
    }
  }
  return s == std::numeric_limits<int>::max() ? 0 : s;
}

// Integer vectors and scratch values, kept per thread so that the exact evaluations
// reuse their memory instead of allocating.
struct Workspace {
  mpz_class o[3], d[3], a[3], b[3], c[3], bc[3], ca[3], ab[3], u[3], x, y, q;

  void load(mpz_class* out, const glm::dvec3& v, int s) {
    for (int k = 0; k < 3; ++k) set_scaled(out[k].get_mpz_t(), v[k], s);
  }
  // out = v - o (v scaled into out first).
  void load_rel(mpz_class* out, const glm::dvec3& v, int s) {
    load(out, v, s);
    for (int k = 0; k < 3; ++k) mpz_sub(out[k].get_mpz_t(), out[k].get_mpz_t(), o[k].get_mpz_t());
  }
  static void cross(mpz_class* out, const mpz_class* p, const mpz_class* q) {
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      mpz_mul(out[k].get_mpz_t(), p[i].get_mpz_t(), q[j].get_mpz_t());
      mpz_submul(out[k].get_mpz_t(), p[j].get_mpz_t(), q[i].get_mpz_t());
    }
  }
  static void dot(mpz_class& out, const mpz_class* p, const mpz_class* q) {
    mpz_mul(out.get_mpz_t(), p[0].get_mpz_t(), q[0].get_mpz_t());
    mpz_addmul(out.get_mpz_t(), p[1].get_mpz_t(), q[1].get_mpz_t());
    mpz_addmul(out.get_mpz_t(), p[2].get_mpz_t(), q[2].get_mpz_t());
  }
};

Workspace& workspace() {
  thread_local Workspace w;
  return w;
}

// Sign of d . ((p - o) x (q - o)), exactly.
int triple_sign(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& p, const glm::dvec3& q) {
  Workspace& w = workspace();
  const int s = common_scale({&o, &d, &p, &q});
  w.load(w.o, o, s);
  w.load(w.d, d, s);
  w.load_rel(w.b, p, s);
  w.load_rel(w.c, q, s);
  Workspace::cross(w.bc, w.b, w.c);
  Workspace::dot(w.u[0], w.d, w.bc);
  return sgn(w.u[0]);
}

// The test's quantities, exactly: the signs of uA, uB, uC into su, and t = num / den
// with num = a . N, den = det (not yet made positive), scaled by one power of two.
void evaluate(const Ray& r, const Triangle& tri, int su[3], Ratio* t) {
  Workspace& w = workspace();
  const int s = common_scale({&r.o, &r.d, &tri.p[0], &tri.p[1], &tri.p[2]});
  w.load(w.o, r.o, s);
  w.load(w.d, r.d, s);
  w.load_rel(w.a, tri.p[0], s);
  w.load_rel(w.b, tri.p[1], s);
  w.load_rel(w.c, tri.p[2], s);
  Workspace::cross(w.bc, w.b, w.c);
  Workspace::cross(w.ca, w.c, w.a);
  Workspace::cross(w.ab, w.a, w.b);
  Workspace::dot(w.u[0], w.d, w.bc);
  Workspace::dot(w.u[1], w.d, w.ca);
  Workspace::dot(w.u[2], w.d, w.ab);
  for (int i = 0; i < 3; ++i) su[i] = sgn(w.u[i]);
  mpz_add(t->den.get_mpz_t(), w.u[0].get_mpz_t(), w.u[1].get_mpz_t());  // D . N
  mpz_add(t->den.get_mpz_t(), t->den.get_mpz_t(), w.u[2].get_mpz_t());
  Workspace::dot(t->num, w.a, w.bc);  // a . N
}

}  // namespace

bool degenerate(const Triangle& tri) {
  // N_k = e_i f_j - e_j f_i with e = B - A, f = C - A rounded (one rounding each): each
  // product carries at most 3 roundings (e, f, the product), the difference one more,
  // so |fl(N_k) - N_k| <= gamma_4 (|e_i f_j| + |e_j f_i|) + 2 eta; 8 eps of the sum of
  // the computed magnitudes, plus 8 tiny for underflow, covers it.
  const glm::dvec3 e = tri.p[1] - tri.p[0], f = tri.p[2] - tri.p[0];
  if (std::isfinite(max_norm(e)) && std::isfinite(max_norm(f))) {
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const double a = e[i] * f[j], b = e[j] * f[i];
      const double bound = 8 * kEps * (std::abs(a) + std::abs(b)) + 8 * kTiny;
      if (std::abs(a - b) > bound) return false;
    }
  }
  Workspace& w = workspace();
  const int s = common_scale({&tri.p[0], &tri.p[1], &tri.p[2]});
  w.load(w.o, tri.p[0], s);
  w.load_rel(w.b, tri.p[1], s);
  w.load_rel(w.c, tri.p[2], s);
  Workspace::cross(w.bc, w.b, w.c);
  return sgn(w.bc[0]) == 0 && sgn(w.bc[1]) == 0 && sgn(w.bc[2]) == 0;
}

void enclose(Candidate* c) {
  const double v = to_double(c->exact, -std::numeric_limits<double>::infinity());  // within 1 ulp
  c->lo = std::nextafter(v, -std::numeric_limits<double>::infinity());
  c->hi = std::nextafter(v, std::numeric_limits<double>::infinity());
}

int compare(const Ratio& a, const Ratio& b) {
  Workspace& w = workspace();
  mpz_mul(w.x.get_mpz_t(), a.num.get_mpz_t(), b.den.get_mpz_t());
  mpz_mul(w.y.get_mpz_t(), b.num.get_mpz_t(), a.den.get_mpz_t());
  const int c = mpz_cmp(w.x.get_mpz_t(), w.y.get_mpz_t());
  return (c > 0) - (c < 0);
}

int compare(const Ratio& a, double b) {
  if (b == 0) return sgn(a.num);
  int64_t m;
  int e;
  split(b, &m, &e);
  mpz_class lhs = a.num, rhs = mpz_class(static_cast<long>(m)) * a.den;
  if (e >= 0) {
    mpz_mul_2exp(rhs.get_mpz_t(), rhs.get_mpz_t(), static_cast<mp_bitcnt_t>(e));
  } else {
    mpz_mul_2exp(lhs.get_mpz_t(), lhs.get_mpz_t(), static_cast<mp_bitcnt_t>(-e));
  }
  return sgn(lhs - rhs);
}

double to_double(const Ratio& a, double floor) {
  if (a.num == 0) return 0;
  // q = floor(|num| 2^s / den) has 64 or 65 bits; converting it truncates to 53 bits,
  // which truncates the exact quotient (the 53-bit grid of q is coarser than 1).
  const long s = 64 - (static_cast<long>(mpz_sizeinbase(a.num.get_mpz_t(), 2)) -
                       static_cast<long>(mpz_sizeinbase(a.den.get_mpz_t(), 2)));
  Workspace& w = workspace();
  mpz_class &n = w.x, &d = w.y, &q = w.q;
  mpz_abs(n.get_mpz_t(), a.num.get_mpz_t());
  mpz_set(d.get_mpz_t(), a.den.get_mpz_t());
  if (s >= 0) {
    mpz_mul_2exp(n.get_mpz_t(), n.get_mpz_t(), static_cast<mp_bitcnt_t>(s));
  } else {
    mpz_mul_2exp(d.get_mpz_t(), d.get_mpz_t(), static_cast<mp_bitcnt_t>(-s));
  }
  mpz_fdiv_q(q.get_mpz_t(), n.get_mpz_t(), d.get_mpz_t());
  // ldexp is exact unless the result is subnormal, where it rounds to the subnormal
  // grid: still within one of its ulps.
  double v = std::ldexp(mpz_get_d(q.get_mpz_t()), static_cast<int>(-s));
  if (a.num < 0) v = -v;
  if (v <= floor && compare(a, floor) > 0) v = std::nextafter(floor, std::numeric_limits<double>::infinity());
  return v;
}

RayTest::RayTest(const Ray& r, bool filter) : r_(r), filter_(filter) {
  d1_ = sum_norm(r.d) * (1 + 4 * kEps);
  d_abs_ = (4 * d1_ + 8) * kTiny;
}

void RayTest::exact_t(const Triangle& tri, Ratio* t) {
  ++exact_evaluations;
  int su[3];
  evaluate(r_, tri, su, t);
  if (t->den < 0) {
    mpz_neg(t->num.get_mpz_t(), t->num.get_mpz_t());
    mpz_neg(t->den.get_mpz_t(), t->den.get_mpz_t());
  }
}

FromOrigin from_origin(const glm::dvec3& o, const Triangle& tri) {
  FromOrigin f;
  f.a = tri.p[0] - o;
  const glm::dvec3 b = tri.p[1] - o, c = tri.p[2] - o;
  f.ma = max_norm(f.a);
  const double mb = max_norm(b), mc = max_norm(c);
  f.usable = std::min({f.ma, mb, mc}) >= kMinNorm;
  f.bc = glm::cross(b, c);
  f.ca = glm::cross(c, f.a);
  f.ab = glm::cross(f.a, b);
  f.m[0] = mb * mc;
  f.m[1] = mc * f.ma;
  f.m[2] = f.ma * mb;
  return f;
}

namespace {

// The signs of uA, uB, uC as the filter sees them (0: not settled).
struct Signs {
  int sign[3] = {0, 0, 0};
  int n = 0;
  bool pos = false, neg = false, unsure = false;
  // Adds the next; true once two are certainly of opposite signs (outside, whatever det is).
  bool add(double u, double bound) {
    int& sg = sign[n++];
    if (u > bound) {
      sg = 1;
      pos = true;
    } else if (u < -bound) {
      sg = -1;
      neg = true;
    } else {
      unsure = true;
    }
    return pos && neg;
  }
  // Settles the unsettled signs exactly; false when the ray misses (opposite signs, or
  // all three 0: det = 0).
  bool settle(const Ray& r, const Triangle& t) {
    for (int i = 0; i < 3; ++i) {
      if (sign[i] != 0) continue;
      sign[i] = triple_sign(r.o, r.d, t.p[(i + 1) % 3], t.p[(i + 2) % 3]);
      pos |= sign[i] > 0;
      neg |= sign[i] < 0;
    }
    unsure = false;
    return pos != neg;
  }
};

}  // namespace

bool RayTest::hits(const Triangle& tri, Candidate* c) {
  c->have_exact = false;
  if (!filter_) return exact_hit(tri, c);
  // As from_origin, but each cross product only when it is needed.
  const glm::dvec3 a = tri.p[0] - r_.o, b = tri.p[1] - r_.o, cc = tri.p[2] - r_.o;
  const double ma = max_norm(a), mb = max_norm(b), mc = max_norm(cc);
  if (std::min({ma, mb, mc}) < kMinNorm) return exact_hit(tri, c);
  const double k = 16 * kEps * d1_;
  Signs s;
  if (s.add(glm::dot(r_.d, glm::cross(b, cc)), k * (mb * mc) + d_abs_) ||
      s.add(glm::dot(r_.d, glm::cross(cc, a)), k * (mc * ma) + d_abs_) ||
      s.add(glm::dot(r_.d, glm::cross(a, b)), k * (ma * mb) + d_abs_)) {
    ++filtered;
    return false;
  }
  if (s.unsure) {
    ++exact_signs;
    if (!s.settle(r_, tri)) return false;
  }
  return inside(tri, a, ma, s.pos, c);
}

bool RayTest::hits(const Triangle& tri, const FromOrigin& f, Candidate* c) {
  c->have_exact = false;
  if (!filter_ || !f.usable) return exact_hit(tri, c);
  const double k = 16 * kEps * d1_;
  Signs s;
  if (s.add(glm::dot(r_.d, f.bc), k * f.m[0] + d_abs_) || s.add(glm::dot(r_.d, f.ca), k * f.m[1] + d_abs_) ||
      s.add(glm::dot(r_.d, f.ab), k * f.m[2] + d_abs_)) {
    ++filtered;
    return false;
  }
  if (s.unsure) {
    ++exact_signs;
    if (!s.settle(r_, tri)) return false;
  }
  return inside(tri, f.a, f.ma, s.pos, c);
}

bool RayTest::inside(const Triangle& tri, const glm::dvec3& a, double ma, bool positive, Candidate* c) {
  // Inside, and det has the sign of the u's. Now t = (a . N) / (D . N).
  const double k = 16 * kEps * d1_;
  const glm::dvec3 e1 = tri.p[1] - tri.p[0], e2 = tri.p[2] - tri.p[0];
  const double m1 = max_norm(e1), m2 = max_norm(e2);
  const glm::dvec3 nrm = glm::cross(e1, e2);
  const double det = glm::dot(r_.d, nrm), num = glm::dot(a, nrm);
  const double bd = k * m1 * m2 + d_abs_;
  const double bn = 52 * kEps * ma * m1 * m2 + (12 * ma + 8) * kTiny;
  const double sign = positive ? 1 : -1;
  if (!(std::min(m1, m2) >= kMinNorm && std::abs(det) > bd && std::abs(num) > bn && det * sign > 0)) {
    return exact_hit(tri, c);
  }
  ++filtered;
  if (num * sign < 0) return false;  // behind the origin
  const double an = std::abs(num), ad = std::abs(det);
  c->lo = std::max(0.0, (an - bn) / (ad + bd) * (1 - 4 * kEps) - kTiny);
  c->hi = (an + bn) / (ad - bd) * (1 + 4 * kEps) + kTiny;
  if (c->lo > r_.tmin) return true;
  if (c->hi <= r_.tmin) return false;
  exact_t(tri, &c->exact);  // t near tmin: decide exactly
  c->have_exact = true;
  if (compare(c->exact, r_.tmin) <= 0) return false;
  enclose(c);
  return true;
}

bool RayTest::exact_hit(const Triangle& tri, Candidate* c) {
  c->have_exact = false;
  ++exact_evaluations;
  int su[3];
  Ratio& t = c->exact;
  evaluate(r_, tri, su, &t);
  const int sd = sgn(t.den);
  if (sd == 0) return false;  // the ray is parallel to the plane, or the triangle is degenerate
  for (int s : su) {
    if (s == -sd) return false;
  }
  if (sd < 0) {
    mpz_neg(t.num.get_mpz_t(), t.num.get_mpz_t());
    mpz_neg(t.den.get_mpz_t(), t.den.get_mpz_t());
  }
  if (compare(t, r_.tmin) <= 0) return false;
  c->have_exact = true;
  enclose(c);
  return true;
}

int RayTest::compare_hits(const Triangle& ta, Candidate* a, const Triangle& tb, Candidate* b) {
  if (a->have_exact && b->have_exact) return compare(a->exact, b->exact);
  if (a->hi < b->lo) return -1;
  if (a->lo > b->hi) return 1;
  if (!a->have_exact) {
    exact_t(ta, &a->exact);
    a->have_exact = true;
  }
  if (!b->have_exact) {
    exact_t(tb, &b->exact);
    b->have_exact = true;
  }
  return compare(a->exact, b->exact);
}

}  // namespace fmpp::isect::exact
