// Stratified sampling (see sampling.h).
#include "sw/scene/sampling.h"

#include <algorithm>
#include <cmath>

namespace rt {

std::pair<int, int> strata_grid(int n) {
  n = std::max(1, n);
  int nx = static_cast<int>(std::sqrt(static_cast<double>(n)));
  while (nx > 1 && (nx * nx > n || n % nx != 0)) --nx;
  return {nx, n / nx};
}

glm::dvec2 stratified(int k, int n, double u1, double u2) {
  const auto [nx, ny] = strata_grid(n);
  const int cx = k % nx, cy = (k / nx) % ny;
  return glm::dvec2((cx + u1) / nx, (cy + u2) / ny);
}

}  // namespace rt
