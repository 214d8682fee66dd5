// Quantization helpers of the intersection kernels: how the host turns doubles into
// the FMPP's fixed-point words (a shared exponent and n-bit mantissas, or a per-ray
// scale), and back.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fmpp::isect {

// Largest component magnitude of a vector. For a direction: each ray's components are
// quantized with their own scale (the largest becomes the format's limit), so a short
// direction in a batch of long ones keeps all its bits; t is corrected per ray.
inline double max_component(const glm::dvec3& d) { return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}); }

// floor(x / 2^s) for a signed integer type (int64_t, __int128), the value the FMPP's
// arithmetic shift right gives, written so as never to shift a negative value (for x < 0,
// ~x = -x - 1 >= 0) nor to negate the type's least value.
template <class T>
constexpr T floor_shift(T x, unsigned s) {
  return x >= 0 ? x >> s : ~(~x >> s);
}

// Exponent e with max|v| < 2^e, and out[k] = round(v[k] 2^(bits - e)), all below 2^bits
// in magnitude.
int mantissas(const double* v, int count, unsigned bits, int64_t* out);

// round(v / scale) as a word; throws std::logic_error naming `what` if it exceeds
// `limit` (the scales are chosen so that it never does: a violation is a kernel bug).
int32_t quantize(double v, double scale, int64_t limit, const char* what);

}  // namespace fmpp::isect
