// Hard cases of shape: needles and slivers, tiny beside huge, rays of any length,
// behind the eye, duplicates, coplanar overlaps, interpenetration, grazing rays
// (fixture and tolerances: hardcases_common.h; instantiated in hardcases_placement_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <sstream>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/kernels.h"
#include "sw/isect/geometry/meshes.h"
#include "sw/isect/pass/policy.h"
#include "sw/isect/exact/reference.h"
#include "tests/support/hardcases_common.h"

namespace fmpp::isect {
namespace {

using namespace hardcases;

// ----------------------------------------------------------- needles and slivers
// Aspect ratio 1e4: a needle (one short edge) and a sliver (one tiny height), tilted in
// depth, in front of a wall. Rays at interior points and just beside the long edges:
// every form equals the reference. cond is 2e4 to 2e5, so n = 16 (limit 2^13) sends
// them to the host, n = 24 (limit 2^21) keeps them on the FMPP: the handling shows in
// host_triangles, which must count exactly the triangles above the limit, in both
// mappings (the limit follows the coarser operand: the n-bit ray components of the
// object-parallel mapping too).
// The watertight form takes the same triangles to the host (it uses the same measure)
// and equals the reference too.
TEST_P(HardCases, NeedlesAndSlivers) {
  const std::vector<Triangle> tris = {
      tri({-20, -20, 30}, {20, -20, 30}, {0, 20, 30}),
      tri({-0.5, -0.3, 5}, {0.5, -0.3, 5.3}, {0.5 - 1e-4, -0.3 + 1e-4, 5.3}),  // needle
      tri({-0.5, 0.3, 5}, {0.5, 0.3, 5.2}, {0.05, 0.3 + 1e-4, 5.1}),           // sliver
      tri({0.9, -0.5, 6}, {0.9 + 1e-4, 0.5, 6.3}, {0.9, 0.5, 6.3}),            // needle, tilted in depth
  };
  std::vector<Ray> rays;
  for (int k = 1; k <= 3; ++k) {
    const Triangle& t = tris[k];
    for (const dvec3& b : {dvec3(1.0 / 3, 1.0 / 3, 1.0 / 3), dvec3(0.45, 0.45, 0.1), dvec3(0.1, 0.2, 0.7)}) {
      rays.push_back(aim(dvec3(0), bary(t, b.x, b.y, b.z)));
    }
    // Beside the triangle, outside its long edges by one width: the wall.
    rays.push_back(aim(dvec3(0), bary(t, 1.5, -0.25, -0.25)));
    rays.push_back(aim(dvec3(0), bary(t, -0.5, 0.75, 0.75)));
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (unsigned n : {16u, 24u}) {
    for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
      const Result r = run(rays, tris, form, n);
      expect_reference(r.hits, ref, rays, tris, tolerance(form, n, tris, dvec3(0)), label(form, n));
      unsigned above = 0;
      for (const Triangle& t : tris) above += condition(t, dvec3(0)) > policy::paper_cond_limit(options(kRayForm, n));
      EXPECT_EQ(r.st.host_triangles, above) << label(form, n);
      EXPECT_EQ(above, n == 16 ? 3u : 0u) << "n = " << n;
    }
  }
}

// ------------------------------------------------------------ tiny and huge
// A tiny triangle (1e-6) at distance 1 (cond 7e6: the host's at n = 24), a tiny
// triangle right in front of the eye (1e-7 away, well conditioned), and a huge one (1e6
// wide, 1e5 away) behind a wall. Every form equals the reference, and the handling is
// visible in the counts:
// - ray-parallel: the near one's sums would overflow the common exponent, and the
//   bound of its compared sum, scaled by the same shift, is beyond what a comparison can
//   certify (certify::kMaxSumBound): it is a host triangle, and so is the far one;
// - object-parallel: one exponent serves every S, and the scene spans 1e-7 to 1e6; the
//   near one's column sums (1e7) are above the cap that keeps every hit 10 bits of S:
//   both tiny ones are host triangles;
// - watertight: as ray-parallel (its compared sum has the same common exponent), and
//   the far one is above the same condition limit.
// Unit directions: the lengths do not matter here (RaysOfVeryDifferentLengths).
TEST_P(HardCases, TinyAndHugeTriangles) {
  const dvec3 c = 1e-7 * dvec3(-0.6, 0.6, 1);
  const std::vector<Triangle> tris = {
      tri({-20, -20, 30}, {20, -20, 30}, {0, 20, 30}),
      tri({0.2, 0, 1}, {0.2 + 1e-6, 0, 1}, {0.2, 1e-6, 1}),
      tri(c + dvec3(-2e-8, -2e-8, 0), c + dvec3(2e-8, -2e-8, 0), c + dvec3(0, 3e-8, 0)),
      tri({-1e6, -1e6, 1e5}, {1e6, -1e6, 1e5}, {0, 1e6, 1e5}),
  };
  std::vector<Ray> rays;
  for (int k = 0; k < 4; ++k) {
    for (const dvec3& b : {dvec3(1.0 / 3, 1.0 / 3, 1.0 / 3), dvec3(0.6, 0.3, 0.1)}) {
      rays.push_back(Ray{dvec3(0), glm::normalize(bary(tris[k], b.x, b.y, b.z))});
    }
  }
  rays.push_back(Ray{dvec3(0), glm::normalize(dvec3(0.9, 0.5, 1))});  // beside the wall: the huge one
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    expect_reference(r.hits, ref, rays, tris, tolerance(form, 24, tris, dvec3(0)), form.name);
    EXPECT_EQ(r.st.host_triangles, 2u) << form.name;
    EXPECT_EQ(r.st.overflow_rays, 0u) << form.name;
  }
}

// ------------------------------------------------------------ ray lengths
// Ray directions of very different lengths in one call (rays aimed at points from 5 to
// 1e5 away: t is in units of each ray's own direction). Each ray keeps its precision:
// the hits equal the reference's, and t times |D| is the distance.
TEST_P(HardCases, RaysOfVeryDifferentLengths) {
  const std::vector<Triangle> tris = {
      tri({-20, -20, 30}, {20, -20, 30}, {0, 20, 30}),
      tri({-0.5, -0.3, 5}, {0.5, -0.3, 5.3}, {0.5 - 1e-3, -0.3 + 1e-3, 5.3}),
      tri({-1e6, -1e6, 1e5}, {1e6, -1e6, 1e5}, {0, 1e6, 1e5}),
  };
  std::vector<Ray> rays;
  for (int k = 0; k < 3; ++k) {
    for (const dvec3& b : {dvec3(1.0 / 3, 1.0 / 3, 1.0 / 3), dvec3(0.45, 0.45, 0.1), dvec3(0.1, 0.2, 0.7)}) {
      rays.push_back(aim(dvec3(0), bary(tris[k], b.x, b.y, b.z)));
    }
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    expect_reference(r.hits, ref, rays, tris, tolerance(form, 24, tris, dvec3(0)), form.name);
  }
}

// ------------------------------------------------------ behind and straddling
// Triangles behind the eye and straddling its plane, rays forward and backward through
// interior points: hits only in front (t > 0), as in the reference, in every form.
TEST_P(HardCases, BehindAndStraddlingTheEye) {
  const std::vector<Triangle> tris = {
      tri({-1, -1, -5}, {1, -1, -5}, {0, 1, -5}),     // behind
      tri({-1, -1, -2}, {1, -1, -2}, {0, 2, 6}),      // straddling, in front and behind
      tri({2, -1, -3}, {3, -1, 3}, {2.5, 1, 0.01}),   // straddling, beside the eye
  };
  std::vector<Ray> rays;
  for (const Triangle& t : tris) {
    for (const dvec3& b : {dvec3(0.3, 0.3, 0.4), dvec3(0.7, 0.2, 0.1), dvec3(0.15, 0.15, 0.7), dvec3(0.5, 0.1, 0.4)}) {
      const dvec3 p = bary(t, b.x, b.y, b.z);
      rays.push_back(Ray{dvec3(0), p});
      rays.push_back(Ray{dvec3(0), -p});
    }
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    expect_reference(r.hits, ref, rays, tris, tolerance(form, 24, tris, dvec3(0)), form.name);
  }
}

// --------------------------------------------------------------------- ties
// The same triangle listed six times, with its vertices in every order (groups of six
// random triangles): a ray meets all copies at the same point, a tie, which goes to the
// lowest index of the group, on the reference and on every FMPP form.
TEST_P(HardCases, DuplicatesTieToTheLowestIndexInAnyVertexOrder) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Triangle> tris;
  std::vector<Ray> rays;
  for (int k = 0; k < 6; ++k) {
    const dvec3 c(3 * u(rng), 3 * u(rng), 8 + 4 * u(rng));
    Triangle t;
    for (dvec3& p : t.p) p = c + 0.8 * dvec3(u(rng), u(rng), u(rng));
    const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    for (const auto& o : orders) tris.push_back(tri(t.p[o[0]], t.p[o[1]], t.p[o[2]]));
    for (int r = 0; r < 8; ++r) {
      const double a = 0.05 + 0.1 * r, b = 0.3 * (1 - a);
      rays.push_back(aim(dvec3(0), bary(t, 1 - a - b, a, b)));
    }
  }
  // A ray may meet another group first; whichever group it meets, the first copy wins.
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (size_t i = 0; i < rays.size(); ++i) {
    ASSERT_TRUE(ref[i].hit());
    EXPECT_EQ(ref[i].tri % 6, 0) << "reference, ray " << i << " hit copy " << ref[i].tri;
  }
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    for (size_t i = 0; i < rays.size(); ++i) {
      EXPECT_EQ(r.hits[i].tri, ref[i].tri - ref[i].tri % 6) << form.name << ", ray " << i;
    }
  }
}

// Coplanar overlapping triangles and z-fighting pairs.
// - Overlap in the plane z = 4 (exact coordinates): every copy is met at exactly the same
//   distance; the reference, the object-parallel form (one exponent for all S) and the
//   watertight form (certified: the near-ties are flagged and redone exactly) report
//   the lowest index.
//   The paper's ray-parallel form sums three separately rounded rows per triangle, so
//   two different triangles of one plane differ in the last unit of S: it reports one
//   of the overlapping triangles, at the same depth within its depth bound.
// - Parallel planes delta apart, the farther triangle first: where delta exceeds twice
//   the form's depth bound (`allowed`) every form reports the nearer one, like the
//   reference; below it, either one, at the right depth.
TEST_P(HardCases, CoplanarOverlapAndZFighting) {
  const std::vector<Triangle> tris = {
      tri({-20, -20, 30}, {20, -20, 30}, {0, 20, 30}),
      tri({-1, -1, 4}, {1, -1, 4}, {0, 1, 4}),
      tri({-0.5, -1.25, 4}, {1.5, -0.75, 4}, {0.25, 1, 4}),
      tri({-1.25, -0.5, 4}, {1, -0.5, 4}, {-0.25, 1.25, 4}),
  };
  std::vector<Ray> rays;
  for (double x : {-0.1, 0.05, 0.2}) {
    for (double y : {-0.3, 0.0, 0.25}) rays.push_back(Ray{dvec3(0), {x / 4, y / 4, 1}});
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(ref[i].tri, 1) << "reference, ray " << i;
  for (const Form& form : {kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    for (size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(r.hits[i].tri, 1) << form.name << ", ray " << i;
  }
  const Result p = run(rays, tris, kRayForm);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_TRUE(p.hits[i].tri >= 1 && p.hits[i].tri <= 3) << "ray-parallel, ray " << i << " hit " << p.hits[i].tri;
    EXPECT_NEAR(p.hits[i].t, 4.0, allowed(tolerance(kRayForm, 24, tris, dvec3(0)), rays[i], tris[1], 4.0));
  }

  for (double delta : {1e-2, 1e-3, 1e-9}) {
    // Tilted planes, the farther one listed first.
    const dvec3 off(0, 0, delta);
    const std::vector<Triangle> pair = {tri(dvec3(-1, -1, 4.5) + off, dvec3(1, -1, 5.5) + off, dvec3(0, 1, 5) + off),
                                        tri({-0.8, -1.1, 4.6}, {1.3, -0.9, 5.65}, {0.2, 1, 5.1})};
    std::vector<Ray> zr;
    for (double x : {-0.05, 0.03, 0.2}) {
      for (double y : {-0.3, 0.01, 0.3}) zr.push_back(Ray{dvec3(0), {x / 5, y / 5, 1}});
    }
    const std::vector<Hit> zref = nearest_reference(zr, pair);
    for (const Hit& h : zref) ASSERT_EQ(h.tri, 1) << "reference: the nearer one";
    for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
      const unsigned n = 24;
      const Result r = run(zr, pair, form, n);
      const Tol tl = tolerance(form, n, pair, dvec3(0));
      for (size_t i = 0; i < zr.size(); ++i) {
        // The depth resolution of the form here: below it the pair is a tie to it.
        const double res = allowed(tl, zr[i], pair[1], zref[i].t);
        if (delta > 2 * res || form.watertight) {  // certified: the nearer one, always
          EXPECT_EQ(r.hits[i].tri, 1) << form.name << ", delta " << delta << ", ray " << i;
        } else {
          EXPECT_TRUE(r.hits[i].hit()) << form.name << ", delta " << delta << ", ray " << i;
        }
        EXPECT_NEAR(r.hits[i].t, zref[i].t, res + delta) << form.name << ", delta " << delta << ", ray " << i;
      }
    }
  }
}

// Interpenetrating triangles crossing along the line y = 0 (z = 5): rays a margin away
// from the crossing report the nearer triangle, as the reference; rays on it either.
TEST_P(HardCases, InterpenetratingTriangles) {
  const std::vector<Triangle> tris = {tri({-1, -1, 4}, {1, -1, 4}, {0, 1, 6}), tri({-1, -1, 6}, {1, -1, 6}, {0, 1, 4})};
  std::vector<Ray> rays;
  std::vector<bool> on_line;
  for (double y : {-0.4, -0.05, 0.0, 0.05, 0.4}) {
    for (double x : {-0.15, 0.02, 0.12}) {
      rays.push_back(aim(dvec3(0), dvec3(x, y, 5 + y)));
      on_line.push_back(y == 0);
    }
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
    const Result r = run(rays, tris, form);
    for (size_t i = 0; i < rays.size(); ++i) {
      if (on_line[i]) {
        EXPECT_TRUE(r.hits[i].hit()) << form.name << ", ray " << i;
      } else {
        EXPECT_EQ(r.hits[i].tri, ref[i].tri) << form.name << ", ray " << i;
      }
      EXPECT_NEAR(r.hits[i].t, ref[i].t, allowed(tolerance(form, 24, tris, dvec3(0)), rays[i], tris[ref[i].tri], ref[i].t))
          << form.name << ", ray " << i;
    }
  }
}

// -------------------------------------------------------------------- grazing
// A floor of 8 x 8 tiles (2000 x 2000) one unit below the eye, rays at elevations down
// to 1e-3 (hits up to ~1900 away) aimed at points well inside its triangles, rays just
// above the horizon and rays that would meet the plane beyond the floor. The far tiles
// are seen almost edge-on (cond up to ~1e5): n = 16 sends many to the host, n = 24
// keeps them; either way the paper's forms and the watertight form equal the reference.
TEST_P(HardCases, GrazingRaysOnAFarFloor) {
  std::vector<Triangle> tris;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      const double x0 = -1000 + 250 * i, z0 = 250 * j;
      tris.push_back(tri({x0, -1, z0}, {x0 + 250, -1, z0}, {x0 + 250, -1, z0 + 250}));
      tris.push_back(tri({x0, -1, z0}, {x0 + 250, -1, z0 + 250}, {x0, -1, z0 + 250}));
    }
  }
  std::vector<Ray> rays;
  for (int k : {1, 6, 9, 14, 22, 30, 37, 45, 53, 58, 61, 67, 70, 77, 83, 90, 99, 103, 118, 127}) {
    const Triangle& t = tris[k];
    for (const dvec3& b : {dvec3(0.2, 0.3, 0.5), dvec3(0.5, 0.25, 0.25)}) rays.push_back(aim(dvec3(0), bary(t, b.x, b.y, b.z)));
  }
  for (double x : {-0.3, 0.01, 0.27}) {
    rays.push_back(Ray{dvec3(0), {x, 1e-4, 1}});     // above the horizon
    rays.push_back(Ray{dvec3(0), {x, -4.9e-4, 1}});  // meets the plane ~2040 away, past the floor
  }
  const std::vector<Hit> ref = nearest_reference(rays, tris);
  for (unsigned n : {16u, 24u}) {
    for (const Form& form : {kRayForm, kObjectForm, kWatertightForm}) {
      const Result r = run(rays, tris, form, n);
      // Depth: cond of the far tiles reaches ~1e5 (below the host limit at n = 24).
      expect_reference(r.hits, ref, rays, tris, tolerance(form, n, tris, dvec3(0)), label(form, n));
      if (form.mapping == Mapping::kRay && n == 16) {
        EXPECT_GT(r.st.host_triangles, 0u) << label(form, n);
      }
    }
  }
}

}  // namespace
}  // namespace fmpp::isect
