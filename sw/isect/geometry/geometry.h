// Value types of the intersection problem: triangles, rays, hits (double precision,
// GLM vectors), the input limits every entry point checks, and the closest-point query
// used to bound hit distances.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace fmpp::isect {

struct Triangle {
  glm::dvec3 p[3];
};

// A ray O + t D, t > tmin. D need not be normalized; t is in units of D. A secondary
// ray leaving a surface names its triangle in `exclude` so it cannot hit it again.
// Hits at t >= tmax are of no interest to the caller (a shadow ray only asks what lies
// before its point): the result may then report them or not, which lets the FMPP skip
// triangles out of reach. `hint` names a triangle whose plane the caller expects beyond
// tmax (a shadow ray's own surface): culling leaves it out for this ray where it can
// prove that (plane_beyond_reach, cull.h), and ignores the hint otherwise. It never
// changes a result (under KernelOptions::occlusion it decides which rays may stop at
// their first occluder: those whose hint is proven).
struct Ray {
  glm::dvec3 o;
  glm::dvec3 d;
  double tmin = 0;
  int exclude = -1;
  double tmax = std::numeric_limits<double>::infinity();
  int hint = -1;
};

// Input limits (docs/intersection.md): the intersection tests multiply up to three
// coordinates (cross products, determinants, t), which overflows double far below
// DBL_MAX, and a direction too short loses its inverse. Every vertex coordinate and ray
// origin component must be finite with |x| <= kMaxCoordinate; every ray direction
// finite, with its largest |component| in [kMinDirection, kMaxDirection].
constexpr double kMaxCoordinate = 1e100;
constexpr double kMaxDirection = 1e100;
constexpr double kMinDirection = 1e-100;

// Why `p` is not a valid vertex or ray origin ("is not finite", "is too far out: ..."),
// or "" if it is valid. Written to follow the name of the point.
std::string check_point(const glm::dvec3& p);
// Why `d` is not a valid ray direction ("is zero", "is too short: ...", ...), or "".
std::string check_direction(const glm::dvec3& d);

// The check of the library entry points (nearest_reference, intersect_fmpp):
// every vertex and ray origin by check_point, every direction by check_direction, and
// each ray's tmin finite and >= 0 and tmax not NaN. Throws std::invalid_argument naming
// the triangle or ray by index: "fmpp::isect: ray 3 direction is zero".
void validate_input(const std::vector<Ray>& rays, const std::vector<Triangle>& tris);

// How the host took part in an FMPP answer (docs/intersection.md, "Certified results"):
// the ray was flagged uncertain and redone exactly, its hit's t came from the host (its
// certified bound was looser than requested), or its block overflowed and it was redone.
enum class HostRedo : uint8_t { kNone, kFlagged, kTFromHost, kOverflow };

struct Hit {
  int tri = -1;  // index of the nearest triangle, -1 for a miss
  double t = std::numeric_limits<double>::infinity();
  // A bound on the relative error of t, |t - exact t| <= t_err t: 0 for an exact t (the
  // exact value rounded, within one ulp: the reference, and every t the host computed),
  // the certified bound of the kernel's own t otherwise (at most KernelOptions::
  // t_accuracy). The ray tracer offsets the rays it spawns from the hit by it.
  double t_err = 0;
  HostRedo redo = HostRedo::kNone;  // set by intersect_fmpp, for the per-ray-kind counts
  // The pass of its kernel call that held the ray (1, 2, ... in the call's order; the
  // ray-parallel mapping), 0 where no single pass answered it (the object-parallel
  // mapping, the host alone): for the diagnostics of the ray-level exact check.
  uint32_t pass = 0;
  bool hit() const { return tri >= 0; }
};

// Closest point of triangle `t` to point `q` (Voronoi-region walk over vertices, edges,
// face), without overflow for any input within the limits.
glm::dvec3 closest_point(const Triangle& t, const glm::dvec3& q);
// The walk itself, from vertex a: edges ab, ac and the point aq. Which region holds the
// closest point, and its ratios along the edge (u) or over the face (u on ab, v on ac).
struct ClosestRegion {
  enum Kind { kA, kB, kC, kAB, kAC, kBC, kFace } kind = kA;
  double u = 0, v = 0;
};
ClosestRegion closest_region(glm::dvec3 ab, glm::dvec3 ac, glm::dvec3 aq);

// Smallest and largest distance from q to any point of any triangle (0 if q touches one).
struct DistanceRange {
  double min = std::numeric_limits<double>::infinity();
  double max = 0;
  // The farthest of the triangles' farthest vertices once the farthest 1 % of the
  // triangles are left out (max with fewer than 101): what a distant speck does not move.
  double bulk = 0;
};
DistanceRange distance_range(const std::vector<Triangle>& tris, const glm::dvec3& q);

}  // namespace fmpp::isect
