// The ray-level exact check (see answer_check.h).
#include "sw/isect/exact/answer_check.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "sw/isect/exact/reference.h"

namespace fmpp::isect {
namespace {

std::string num(double v) {
  char b[96];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string hex(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

std::string hit_words(const Hit& h) {
  if (!h.hit()) return "a miss";
  return "triangle " + std::to_string(h.tri) + " at t = " + num(h.t);
}

// Whether t lies within its bound t_err of the exact value `exact_t` (a few ulps of slack).
bool t_within(double t, double t_err, double exact_t) {
  const double slack = 4 * (std::nextafter(exact_t, std::numeric_limits<double>::infinity()) - exact_t);
  return std::fabs(t - exact_t) <= t_err * exact_t + slack;
}

// The t of `got` against the exact t of its own triangle: "" or why not.
std::string check_t(const Hit& got, double exact_t, const AnswerRules& rules) {
  if (!(got.t_err >= 0) || got.t_err > rules.max_t_err) {
    return "its t bound " + num(got.t_err) + " exceeds the requested accuracy " + num(rules.max_t_err);
  }
  if (!t_within(got.t, got.t_err, exact_t)) {
    return "its t = " + num(got.t) + " is off the exact " + num(exact_t) + " by " +
           num(std::fabs(got.t - exact_t) / exact_t) + " relative, beyond its bound " + num(got.t_err);
  }
  return "";
}

}  // namespace

std::string check_answer(const Ray& r, const Hit& got, const Hit& exact, const std::vector<Triangle>& tris,
                         const AnswerRules& rules) {
  const std::string both = "the answer is " + hit_words(got) + ", the exact nearest hit " + hit_words(exact);
  if (got.hit() && (got.tri >= static_cast<int>(tris.size()) || got.tri == r.exclude)) {
    return both + ": the answer names " + (got.tri == r.exclude ? "the excluded triangle" : "no triangle of the scene");
  }
  if (got.tri == exact.tri) {
    if (!got.hit()) return "";
    const std::string why = check_t(got, exact.t, rules);
    return why.empty() ? "" : both + ": " + why;
  }
  const bool needed = exact.hit() && exact.t < r.tmax;  // a hit before tmax exists
  if (!got.hit()) return needed ? both + ": a hit before the ray's tmax " + num(r.tmax) + " was missed" : "";
  if (needed && !rules.any_occluder) return both + ": another triangle than the nearest";
  const double te = intersect_reference(r, tris[static_cast<size_t>(got.tri)]);
  if (!(te < std::numeric_limits<double>::infinity())) return both + ": the ray does not meet the answer's triangle";
  if (needed && !(te < r.tmax)) {
    return both + ": an occluder was needed before tmax " + num(r.tmax) + ", the answer's lies at exact t = " + num(te);
  }
  if (needed && got.tri == r.hint) {
    return both + ": the occlusion query stopped at the ray's own surface (its hint), which its caller counts as "
                  "no occluder, while a nearer triangle occludes";
  }
  if (!needed && te < r.tmax) return both + ": the answer's triangle lies before the exact nearest hit";
  const std::string why = check_t(got, te, rules);
  return why.empty() ? "" : both + ": " + why;
}

std::string describe_ray(const Ray& r) {
  auto vec = [](const glm::dvec3& v, std::string (*f)(double)) {
    return "(" + f(v.x) + ", " + f(v.y) + ", " + f(v.z) + ")";
  };
  return "o = " + vec(r.o, hex) + " = " + vec(r.o, num) + ", d = " + vec(r.d, hex) + " = " + vec(r.d, num) +
         ", tmin = " + hex(r.tmin) + ", tmax = " + hex(r.tmax) + ", exclude = " + std::to_string(r.exclude) +
         ", hint = " + std::to_string(r.hint);
}

}  // namespace fmpp::isect
