// The pass size without the frame (see pass_cost.h, PassBound).
#include <sstream>

#include "sw/plan/pass_cost.h"

namespace rt {
namespace {

double passes_bound(size_t primary, int spp, size_t lights, unsigned smallest) {
  const double per_batch = static_cast<double>((primary + smallest - 1) / smallest) + spp;
  return (1 + static_cast<double>(lights)) * per_batch;
}

}  // namespace

bool pass_bound_may_hold(size_t primary, int spp, size_t lights, size_t triangles, unsigned smallest) {
  return smallest > 0 && passes_bound(primary, spp, lights, smallest) * static_cast<double>(triangles) * kBoundRatio <=
                             kPassSizeSlack * static_cast<double>(primary);
}

PassBound pass_bound(size_t primary, int spp, size_t lights, size_t triangles, unsigned smallest, double per_broadcast,
                     double per_ray, double object_per_ray) {
  PassBound b;
  const double passes = passes_bound(primary, spp, lights, smallest);
  b.broadcasts = passes * static_cast<double>(triangles) * per_broadcast;
  b.rays = static_cast<double>(primary) * per_ray;
  b.certain = smallest > 0 && per_ray > 0 && b.broadcasts <= kPassSizeSlack * b.rays && object_per_ray >= per_ray;
  std::ostringstream o;
  o << "every ray shares an origin, and the frame's broadcasts at " << smallest << " blocks cost at most "
    << static_cast<long>(passes) << " passes x " << triangles << (triangles == 1 ? " triangle" : " triangles") << " x "
    << static_cast<long>(per_broadcast + 0.5) << " clocks = " << static_cast<long>(b.broadcasts + 0.5)
    << " clocks, against " << static_cast<long>(b.rays + 0.5) << " clocks for loading and reading back its "
    << primary << " primary rays alone (" << static_cast<long>(per_ray + 0.5) << " a ray)";
  if (b.certain) {
    o << ": within " << 100 * kPassSizeSlack << " % of any candidate's estimate, so the fewest blocks, " << smallest
      << ", without tracing the frame (either pass order is within the same bound; no kind of batch can move to the "
         "object-parallel mapping, at " << static_cast<long>(object_per_ray + 0.5) << " clocks a ray, nor has a batch "
         "two origins to merge)";
  } else {
    o << ": not within " << 100 * kPassSizeSlack << " %, so the frame is traced and the sizes priced";
  }
  b.why = o.str();
  return b;
}

}  // namespace rt
