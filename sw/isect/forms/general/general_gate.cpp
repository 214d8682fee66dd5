// The arbitrary-origin form's gate on the host (see general_gate.h).
#include "sw/isect/forms/general/general_gate.h"

#include "sw/isect/pass/fixed_point.h"
#include "sw/isect/pass/policy.h"

namespace fmpp::isect {
namespace {

// floor(sum_j c_j y_j / 2^n), exactly (|c| < 2^31, |y| < 2^31: the sum within 2^64).
int64_t row(const int64_t* c, const int64_t* y, unsigned count, unsigned n) {
  __int128 s = 0;
  for (unsigned j = 0; j < count; ++j) s += static_cast<__int128>(c[j]) * y[j];
  return static_cast<int64_t>(floor_shift(s, n));
}

}  // namespace

bool GeneralGate::affects(const int64_t v[3], const int64_t l[3], const int64_t o[3]) const {
  const int64_t e0 = row(xa + 3, l, 3, n), e1 = row(xa + 9, l, 3, n);
  int64_t a[3] = {row(xa + 0, v, 3, n) + e0, row(xa + 6, v, 3, n) + e1, row(xa + 12, v, 3, n) - e0 - e1};
  const int64_t od[4] = {o[0], o[1], o[2], int64_t{1} << policy::kGeneralRayBits};
  int64_t det = row(xd, od, 4, n);
  if (det < 0) {
    det = -det;
    for (int64_t& ai : a) ai = -ai;
  }
  const int64_t k = int64_t{1} << ka;
  bool gate = true, none_positive = true;
  for (int64_t ai : a) {
    gate = gate && ai >= -k;
    none_positive = none_positive && ai < k;
  }
  // The head's flag: det within its bound of 0 and no A_i certainly positive.
  const bool flags = det < (int64_t{1} << kd) && none_positive;
  return gate || flags;
}

}  // namespace fmpp::isect
