// Quantization helpers of the intersection kernels (see fixed_point.h).
#include "sw/isect/pass/fixed_point.h"

#include <stdexcept>
#include <string>

namespace fmpp::isect {

int mantissas(const double* v, int count, unsigned bits, int64_t* out) {
  double m = 0;
  for (int k = 0; k < count; ++k) m = std::max(m, std::abs(v[k]));
  int e = (m > 0) ? static_cast<int>(std::floor(std::log2(m))) + 1 : 0;
  const int64_t lim = (int64_t{1} << bits) - 1;
  for (;;) {
    bool ok = true;
    // v 2^(bits - e): a product with the power of two rounds as ldexp does, once.
    const int shift = static_cast<int>(bits) - e;
    const double scale = std::ldexp(1.0, shift);
    const bool normal = shift >= -1022 && shift <= 1023;
    for (int k = 0; k < count; ++k) {
      out[k] = std::llround(normal ? v[k] * scale : std::ldexp(v[k], shift));
      ok = ok && std::llabs(out[k]) <= lim;
    }
    if (ok) return e;
    ++e;
  }
}

int32_t quantize(double v, double scale, int64_t limit, const char* what) {
  const double q = std::nearbyint(v / scale);
  if (!(std::abs(q) <= static_cast<double>(limit))) {
    throw std::logic_error(std::string("fmpp::isect: ") + what + " out of range after scaling");
  }
  return static_cast<int32_t>(q);
}

}  // namespace fmpp::isect
