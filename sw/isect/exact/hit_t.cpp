// A hit's distance as the reference reports it (RayTest::hit_t, exact.h): the exact t
// truncated toward zero to a double, first from a double-double evaluation with a
// rigorous bound on its error, exactly (GMP) only where that bound does not settle the
// truncation.
//
// t = (a . N) / (D . N) with a = A - O, N = (B - A) x (C - A). The differences are exact
// as double-doubles (two_sum). Each product and sum of double-doubles below has a
// relative error of at most 4 u^2 (u = 2^-53; the accurate sum and the product with FMA
// of Joldes, Muller and Popescu, "Tight and rigorous error bounds for basic building
// blocks of double-word arithmetic", 2017: 3 u^2 and 4 u^2); the bounds carried here use
// 2^-102 (8 u^2), and every operation adds 2^-1060 for a part that underflows. The
// quotient is only a candidate: the truncated t is the largest double c with t >= c, and
// t >= c iff num - c den >= 0 (den > 0), a residual evaluated with its bound, whose sign
// the bound settles unless t lies within it of c. The evaluation runs only when every nonzero
// component of a, B - A, C - A and D lies in [2^-300, 2^300], so no product of three
// overflows or loses its relative bound to underflow beyond that allowance.
#include <cmath>
#include <initializer_list>
#include <limits>

#include "sw/isect/exact/exact.h"

namespace fmpp::isect::exact {
namespace {

struct DD {
  double hi = 0, lo = 0;
};

DD two_sum(double a, double b) {
  const double s = a + b, bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
DD fast_two_sum(double a, double b) {  // |a| >= |b| or a = 0
  const double s = a + b;
  return {s, b - (s - a)};
}
DD two_prod(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}
DD dd_add(DD x, DD y) {
  const DD s = two_sum(x.hi, y.hi), t = two_sum(x.lo, y.lo);
  const DD v = fast_two_sum(s.hi, s.lo + t.hi);
  return fast_two_sum(v.hi, t.lo + v.lo);
}
DD dd_mul(DD x, DD y) {
  const DD c = two_prod(x.hi, y.hi);
  const double cl = std::fma(x.lo, y.hi, std::fma(x.hi, y.lo, x.lo * y.lo));
  return fast_two_sum(c.hi, c.lo + cl);
}
DD dd_div(DD x, DD y) {
  const double th = x.hi / y.hi;
  const DD r = dd_mul(y, DD{th, 0});
  const double d = (x.hi - r.hi) + (x.lo - r.lo);
  return fast_two_sum(th, d / y.hi);
}

constexpr double kRel = 0x1p-102;  // of a sum or a product
constexpr double kUnder = 0x1p-1060;
constexpr double kUp = 1 + 0x1p-40;  // covers the rounding of the bounds themselves

// A value with a bound on its absolute error.
struct Bounded {
  DD v;
  double e = 0;
};
double mag(const DD& x) { return std::abs(x.hi) * (1 + 0x1p-52); }
// Exact values (e = 0) that are single doubles, or exactly zero, stay exact where the
// operation is error-free: the sum and the product of two doubles (two_sum, two_prod,
// with no part below 2^-960, where the product's error could underflow), and anything
// plus or times zero. So an axis-aligned triangle's t, often exactly a double (which no
// bound can settle), is decided from exact values below.
bool exact_zero(const Bounded& x) { return x.e == 0 && x.v.hi == 0 && x.v.lo == 0; }
bool exact_double(const Bounded& x) {
  return x.e == 0 && x.v.lo == 0 && (x.v.hi == 0 || std::abs(x.v.hi) >= 0x1p-960);
}
Bounded diff(double a, double b) { return {two_sum(a, -b), 0}; }
Bounded add(const Bounded& x, const Bounded& y) {
  if (exact_zero(y)) return x;
  if (exact_zero(x)) return y;
  if (exact_double(x) && exact_double(y)) return {two_sum(x.v.hi, y.v.hi), 0};
  const DD v = dd_add(x.v, y.v);
  return {v, (x.e + y.e + kRel * mag(v) + kUnder) * kUp};
}
Bounded sub(const Bounded& x, const Bounded& y) { return add(x, Bounded{DD{-y.v.hi, -y.v.lo}, y.e}); }
Bounded mul(const Bounded& x, const Bounded& y) {
  if (exact_zero(x) || exact_zero(y)) return {};
  if (exact_double(x) && exact_double(y) && std::abs(x.v.hi * y.v.hi) >= 0x1p-960) {
    return {two_prod(x.v.hi, y.v.hi), 0};
  }
  const DD v = dd_mul(x.v, y.v);
  return {v, (mag(x.v) * y.e + mag(y.v) * x.e + x.e * y.e + kRel * mag(v) + kUnder) * kUp};
}

// The sign of a sum of doubles, exactly (an expansion grown term by term, its zero
// components dropped: the sign of its largest component). No term may overflow.
int sign_of_sum(std::initializer_list<double> terms) {
  double e[8];
  int n = 0;
  for (double b : terms) {
    double q = b;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const DD s = two_sum(q, e[i]);
      if (s.lo != 0) e[m++] = s.lo;
      q = s.hi;
    }
    if (q != 0) e[m++] = q;
    n = m;
  }
  return n == 0 ? 0 : (e[n - 1] > 0 ? 1 : -1);
}

// With num and den exact (den > 0), the sign of num - x den, exactly; 2 where a product
// could lose a part to underflow.
int sign_against(const DD& num, const DD& den, double x) {
  const DD p = two_prod(x, den.hi), p2 = two_prod(x, den.lo);
  if ((p2.hi != 0 && std::abs(p2.hi) < 0x1p-960) || std::abs(p.hi) < 0x1p-960) return 2;
  return sign_of_sum({num.lo, num.hi, -p.lo, -p2.lo, -p2.hi, -p.hi});
}

bool in_range(double x) {
  const double m = std::abs(x);
  return m == 0 || (m >= 0x1p-300 && m <= 0x1p300);
}
bool in_range(const DD& x) { return in_range(x.hi); }

// t truncated toward zero (t > floor >= 0), or NaN where the bound cannot settle it.
double filtered_t(const Ray& r, const Triangle& tri) {
  Bounded a[3], e1[3], e2[3], d[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = diff(tri.p[0][k], r.o[k]);
    e1[k] = diff(tri.p[1][k], tri.p[0][k]);
    e2[k] = diff(tri.p[2][k], tri.p[0][k]);
    d[k] = Bounded{DD{r.d[k], 0}, 0};
    // The low parts may be smaller (an exact difference's rounding error): the
    // allowance kUnder covers what their products lose.
    if (!in_range(a[k].v) || !in_range(e1[k].v) || !in_range(e2[k].v) || !in_range(r.d[k])) {
      return std::numeric_limits<double>::quiet_NaN();
    }
  }
  Bounded n[3];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    n[k] = sub(mul(e1[i], e2[j]), mul(e1[j], e2[i]));
  }
  Bounded num = add(add(mul(a[0], n[0]), mul(a[1], n[1])), mul(a[2], n[2]));
  Bounded den = add(add(mul(d[0], n[0]), mul(d[1], n[1])), mul(d[2], n[2]));
  if (den.v.hi < 0) {  // den > 0 below (negating is exact)
    num.v = DD{-num.v.hi, -num.v.lo};
    den.v = DD{-den.v.hi, -den.v.lo};
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(den.v.hi > 0 && num.v.hi > 0)) return nan;  // a hit has t > 0
  // The candidate: the quotient's approximation truncated (the double below q.hi where
  // its low part is negative). Then t >= c iff num - c den >= 0, a sign the bound on that
  // residual settles unless it is within it: 1, -1, or 0 for unsettled.
  const DD q = dd_div(num.v, den.v);
  const double x = q.lo < 0 ? std::nextafter(q.hi, 0.0) : q.hi;
  if (!(x >= 0x1p-1000)) return nan;
  const bool exact = num.e == 0 && den.e == 0;
  const auto at_least = [&](double c) {
    if (exact) {  // num and den exact: the sign exactly (2: a part could underflow)
      const int sg = sign_against(num.v, den.v, c);
      return sg == 2 ? 0 : (sg >= 0 ? 1 : -1);
    }
    const Bounded res = sub(num, mul(Bounded{DD{c, 0}, 0}, den));
    if (std::abs(res.v.hi) * (1 - 0x1p-50) <= res.e) return 0;
    return res.v.hi > 0 ? 1 : -1;
  };
  // t truncated is the largest double c with t >= c: x, or one of its neighbours.
  const double prev = std::nextafter(x, 0.0), next = std::nextafter(x, std::numeric_limits<double>::infinity());
  const int sx = at_least(x);
  if (sx == 0) return nan;
  if (sx > 0) {
    const int sn = at_least(next);
    if (sn < 0) return x;
    if (sn == 0) return nan;
    return at_least(std::nextafter(next, std::numeric_limits<double>::infinity())) < 0 ? next : nan;
  }
  return at_least(prev) > 0 ? prev : nan;
}

}  // namespace

double RayTest::hit_t(const Triangle& tri, Candidate* c) {
  if (!c->have_exact && filter_) {
    const double t = filtered_t(r_, tri);
    if (t > r_.tmin) {  // NaN is not: then exactly, with the floor's rule of to_double
      ++t_filtered;
      return t;
    }
  }
  if (!c->have_exact) {
    exact_t(tri, &c->exact);
    c->have_exact = true;
  }
  return to_double(c->exact, r_.tmin);
}

}  // namespace fmpp::isect::exact
