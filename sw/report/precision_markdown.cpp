// fmpp-report precision, the Markdown (precision.h): one function per section of
// docs/precision.md, each formatting figures measured or chosen before; the prose that
// reads the full run's numbers and the hard-case list are fixed text.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sw/report/precision.h"

namespace fmpp::report::precision {
namespace {

// A rate in percent, "0" when exactly zero.
std::string pct(double v) {
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, v >= 0.01 ? "%.2f" : "%.3f", 100 * v);
  return buf;
}

std::string sci(double v) {
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

std::string big(uint64_t v) {
  char buf[64];
  if (v >= 1000000) {
    std::snprintf(buf, sizeof buf, "%.3gM", static_cast<double>(v) / 1e6);
  } else if (v >= 10000) {
    std::snprintf(buf, sizeof buf, "%.1fk", static_cast<double>(v) / 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(v));
  }
  return buf;
}

std::string db(double v) { return std::isfinite(v) ? fmt(v, 1) : "identical"; }

// How to read the tables (written for the full run's numbers).
const char* kReading = R"(**What the numbers mean for choosing n** (read from the tables above):

- **The paper's form needs n = 20 for the machine alone, n = 24 for images.** At
  n = 20 the raw machine gets every primary ray of every scene right and the fallback
  sends at most 21 triangles to the host; the full renders reach 35.2 (spheres_10k) to
  73 dB. At n = 24, the default, every render is within one level of the reference on
  at most a few pixels (77 to 83 dB, or identical). Below 16 the raw error grows about
  4x per 2 bits (spheres_10k: 0.6 % of the rays wrong at n = 16, 3.5 % at 12, 17 % at
  10), as the error analysis predicts (cond 2^-n).
- **The fallback keeps results right, but below n = 16 it is the host doing the work.**
  Its condition limit (2^(n-3): 32 at n = 8, 128 at 10) is below the condition number
  of ordinary triangles seen from the eye (tens to hundreds), so at n = 8 all but two
  triangles of each sphere scene are host triangles: their primary rays come out right, for 10.5
  million host tests per frame on spheres_10k, as many as the brute-force reference
  does, and the secondary rays' arbitrary-origin kernel (limit 2^(n-4)) sends most
  triangles to the host too; the sphere images come out at 31 to 33 dB (4 pixels more
  than 8 levels off). The Cornell box keeps 6 of its triangles on the FMPP, whose
  cracks at n = 8 cost 5 % of the primary rays (17 dB).
  At n = 10 and 12 the fallback takes most or half of the triangles and still leaves
  errors (spheres_1k: 5 % of the rays at n = 10). From n = 16 the cost of correctness is
  small (at most 4 % of the triangles), from 24 nil.
- **Clocks grow linearly with n.** The constant (CSD) multiply costs about 6n + 16
  steps per broadcast (64 at n = 8, 159 at 24, 209 at 32) and the generic one 22n + 31,
  3.2 to 3.6 times more on the larger scenes, for bit-identical results (checked on
  every ray and image here). From n = 16 to 24 a broadcast costs 43 % more, from 24 to
  32 another 30 %. Whole renders gain less from the constant multiply (1.8 to 2.3
  times from n = 16 on the three larger scenes, near 1 below, where the host does most
  of the work) because loads, readback and the arbitrary-origin kernel of the secondary
  rays weigh the same in both. Use the constant multiply at every n.
- **n = 32 buys depth, not hits.** The ray components have 28 bits, so past 28 the
  triangle test hardly improves (no primary ray changes between n = 24 and 32 here),
  while the depth error falls about 3 times (median 1.3e-6 to 4.1e-7 on spheres_10k).
- **The watertight form never leaks, but its grid is coarse.** On the closed sphere it
  lets no ray through at any n (0 of 23,456), where the paper's form loses 18 to 24 %
  of the rays aimed exactly at edges for n = 8..28 (the sign of a rounded T decides
  them; 5 % at 32) and, of rays in all directions, 1.7 % at n = 8, falling about 4x per
  2 bits to none of 20,000 from n = 16. But it snaps vertices to a grid of (n-3)/2 bits
  of the scene's extent, moving them by up to 2^-(n-1)/2 of it: on the sphere scenes it
  needs n = 32 to get as few rays wrong as the paper's form at n = 16 to 20, and even
  there its sphere images are 45 to 68 dB (its depth comes from one n-bit row). Its clocks per
  broadcast are close to the paper's form's at equal n (fewer at small n, up to 22 %
  more at 24-32). So: the paper's form at n = 24 for the most accurate image per clock;
  the watertight form at n = 32 where a closed surface must never leak (shadow rays
  toward closed objects, inside tests).)";

const char* kHardCases = R"(## Hard cases

`tests/hardcases_test.cpp` runs every case below on the reference, on the golden model
(`Model/HardCases.*`, ctest label `unit`) and on the Verilated RTL in lockstep with the
model (`Rtl/HardCases.*`, label `rtl`, configuration `small`), in the ray-parallel and
object-parallel paper forms and the watertight form (n = 24, some also n = 16), and
checks after every run that an overflow left in the machine was counted. "Equals the
reference" means: the same triangle for every ray, and the distance within the form's
depth bound (below).

| case | behaviour asserted | bound, where the exact behaviour cannot hold |
| --- | --- | --- |
| rays exactly through the shared vertex and the shared edges of a closed fan of 7 triangles | reference and watertight: every ray hits (no crack), and reports one triangle, one of those sharing the edge or vertex (either is right: the ray meets both at one point); paper forms: any hit is such a triangle, at the right depth | the paper's form decides an exact edge by the sign of a rounded T, so it may crack there (counted, not bounded); rays 8 cond 2^-min(n,28) of the triangle's height inside a triangle hit exactly that triangle, as the reference does |
| closed perturbed sphere (288 triangles) around the eye, rays aimed exactly at its edges and vertices | every ray hits in the reference; the watertight form never leaks (n = 12, 16, 24) | the paper's form leaks on exact edges at a rate that does not fall with n (table above): asserted below 35 %; rays a margin (as above) inside every triangle never leak and hit that triangle, in both mappings |
| the same sphere, 12,000 uniformly random directions | the watertight form never leaks | the paper's form leaks only within the crack width of an edge (about cond 2^-n of a triangle's height): asserted at most 16 x 2^-n (measured 4.3-5.5 x 2^-n for n = 8..12, none from 16) |
| eye exactly in a triangle's plane, inside a triangle, and 1e-12, 1e-6, 1e-3 off the plane, with a wall behind | every form equals the reference (n = 16, 24), never a garbage hit; the singular triangle (det = 0) is a host triangle even with cond_bits = 60; nearly singular ones are counted host triangles | - |
| degenerate triangles: collinear vertices (exact integers and dyadic), a repeated vertex, three equal vertices; rays aimed exactly at them | never hit: the rays hit the wall behind, in the reference and both paper forms (default and cond_bits = 60); the four are host triangles | watertight: its grid moves collinear vertices off their line, making a sliver at most one grid step wide, which rays through the old segment may hit (that sliver keeps a closed mesh closed once snapped); a repeated vertex or a point is never hit, and rays 3 grid steps beside a collinear triangle never hit it |
| needles and a sliver of aspect ratio 1e4 (cond 2e4 to 2e5) before a wall; rays inside them and one width outside | paper forms equal the reference at n = 16 (all three are host triangles: cond > 2^13) and n = 24 (on the FMPP); host_triangles counts exactly the triangles above 2^(min(n,28)-3) in both mappings | watertight: the needles snap to nothing (host triangles); the sliver snaps to a triangle a grid step away, which the rays miss: the form equals the reference on its snapped mesh |
| a tiny triangle (1e-6) at distance 1, a tiny one 1e-7 in front of the eye, a huge one (1e6 wide) at 1e5 behind a wall | every form equals the reference; ray-parallel redoes the rays of the near one after an overflow (overflow_rays > 0) and tests the far one on the host; object-parallel tests both tiny ones on the host (the near one's column sums are above its cap), the watertight form both and the wall (the huge triangle sets a grid step of ~1400); host_triangles exact | depth: the compared sum keeps at least 9 bits (ray-parallel) or 10 bits (object-parallel) for the farthest hit, so a scene spanning 1e-7 to 1e6 has depth errors up to ~2^-9 there |
| ray directions of lengths 5 to 1e5 in one call | every form equals the reference; t is in units of each ray's own direction | - |
| triangles behind the eye and straddling its plane, rays forward and backward | hits only in front, equal to the reference, every form | - |
| one triangle listed six times with its vertices in every order | a tie: the first copy (lowest index) wins, in the reference and every form (watertight: on its snapped mesh) | - |
| coplanar overlapping triangles (plane z = 4) | reference, object-parallel and watertight: exact tie, lowest index | ray-parallel sums three separately rounded rows per triangle, so two different triangles of one plane differ in the last unit of S: it reports one of them, at the right depth |
| z-fighting: parallel overlapping planes 1e-2, 1e-3, 1e-9 apart, the farther one first | where the gap exceeds twice the form's depth bound, the nearer triangle, as the reference | below that, either of the two, at the right depth |
| interpenetrating triangles crossing along a line | rays away from the crossing: the nearer one, as the reference | on the crossing line, either |
| a floor of 128 triangles 1 below the eye, rays down to 1e-3 elevation (hits ~1900 away), above the horizon, beyond the floor | paper forms equal the reference at n = 16 (many far tiles are host triangles) and n = 24 | watertight: the grid step (~2) exceeds the eye's height, so its floor moves: it equals the reference on its snapped floor |
| directions with zero components (along the axes, in the axis planes) in a box around the eye | every form equals the reference | - |
| a scene and eye translated by (1e5, -1e5, 1e5), also rays with their own origins, tmin and an excluded triangle | primary rays equal the reference in the paper forms, the watertight form on its snapped mesh; arbitrary-origin rays equal it within that kernel's bound 2^-(n-10) | - |
| tiny triangles (0.02 across) 70 from the scene's centre, rays with their own origins aimed inside them (arbitrary-origin kernel) | n = 16: the 16 tiny triangles are host triangles (edge-test condition above 2^(n-4)) and every ray equals the reference; with cond_bits = 60 some rays are wrong; n = 24: on the FMPP, every ray equals the reference | - |
| rays that miss everything, an empty scene, an empty batch | all misses, no host work, no overflow | - |

**Depth bounds used by the tests** (`allowed` in the test file): the paper's forms make
a relative error of about cond 2^-min(n,28) in T and hence in S = 1/t (8 cond 2^-bits
allowed), plus the resolution of the compared sum: ray-parallel brings S to one
exponent chosen so that the nearest possible hit (at dmin, the nearest triangle but at
least 2^-20 of the farthest vertex) is ~2^29, so a hit at d keeps S_c >= 2^28 dmin / d
(8 / S_c allowed); object-parallel keeps S_c >= 2^(mbits-2) / (s_max d) (same
allowance). The watertight form intersects the snapped mesh (surfaces up to sqrt(3)/2
grid steps away: 2 steps / |cos| along a ray allowed) and takes S from one n-bit row
(2^-(n-12) relative allowed).

**Bugs these cases found** (each fixed with its test, see the git log): the reference
broke ties between copies of a triangle by rounding (vertex order) and hit degenerate
triangles through their segment; the kernels quantized all ray directions of a call
with one scale (a short ray lost its bits), let object-parallel keep triangles up to
cond 2^25 at any n, let one near-plane triangle take every bit of the object-parallel
S from all others, dropped triangles the watertight grid flattened (the reference
still hits them), and derived scales from an empty scene (undefined behaviour).
)";

void intro(std::ostream& md, const Options& o, const Setup& s, const std::string& date, double seconds,
           bool consistent) {
  const int size = s.size;
  const Config& machine = s.machine;
  md << "# Precision: accuracy against cycles\n\n";
  md << "Generated by `build/fmpp-report precision" << (o.quick ? " --quick" : "")
     << (o.size != 32 && !o.quick ? " --size " + std::to_string(o.size) : std::string()) << "` on " << date << " ("
     << machine_description() << "; " << fmt(seconds) << " s). Every figure is measured on the golden model "
     << "(clock-exact with the RTL: the lockstep tests check it) as an FMPP of " << machine.blocks << " blocks x "
     << machine.words << " words (the RTL's `" << (o.quick ? "small" : "medium")
     << "` configuration), ray-parallel, at " << size << " x " << size
     << " pixels. The data behind the tables and plots is in `" << o.img_dir << "/precision_data.json`.\n\n";
  if (!consistent) {
    md << "**Generic and constant multiplies gave different results somewhere: see the tool's output. "
          "They must not (docs/intersection.md).**\n\n";
  }
}

void what_is_measured(std::ostream& md) {
  md << R"(## What is measured

- **n**: the multiplier width (`KernelOptions::n`): the mantissas of P^-1 in the paper's
  form, the edge constants (from a grid of (n - 3) / 2 bits) in the watertight form. The
  other operand (ray components) has vbits = 28 bits, so beyond n = 28 the triangle
  test gains little.
- **Forms**: `generic` and `const` are the paper's form with the generic shift-and-add
  multiply and the constant-specialised (CSD) one: bit-identical results by
  construction (checked here on every image and every primary ray), different cycles.
  `watertight` is the exact-integer edge-function form (always constant multiplies).
- **steps/bcast**: instructions (= clocks) per triangle broadcast, primary rays.
- **frame clocks**: FMPP clocks for all primary rays of the image (load, broadcasts,
  readback), counted by the golden model; **render clocks**: for the whole Whitted
  render (primary, shadow, reflection and refraction rays; the secondary rays of mirrors
  and glass use the arbitrary-origin kernel).
- **Raw machine** (`cond_bits = 60`): every triangle on the FMPP, so the error is the
  fixed-point format's. **Fallback** (the default): ill-conditioned triangles (cond >
  2^(min(n,28)-3)) and, in the watertight form, triangles the grid flattens are
  intersected on the host (**host tris**, **host tests** = ray-triangle tests the host
  did instead), and overflowed rays are redone there: the cost of correctness.
- Per primary ray, against the double-precision reference: **wrong** = both hit,
  different triangles; **hit/miss** = one hits and the other does not (both in % of the
  rays); **depth** = |t - t_ref| / t_ref over the rays hitting the same triangle (median
  and maximum).
- **PSNR**: of the 8-bit image of the full render against the reference render (all
  channels; "identical" when every pixel is equal); **px > 8** = pixels more than 8
  levels off in some channel.

)";
}

void scene_table(std::ostream& md, const SceneTable& t) {
  md << "## " << t.name << " (" << t.triangles << " triangles)\n\n";
  md << "| n | form | steps/bcast | raw: frame clocks | wrong % | hit/miss % | depth median | depth max | "
        "fallback: frame clocks | host tris | host tests | wrong % | hit/miss % | render clocks | PSNR dB | px > 8 |\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Row& r : t.rows) {
    md << "| " << r.n << " | " << r.form << " | " << fmt(r.steps, 1) << " | " << big(r.raw_cycles) << " | "
       << pct(r.raw.wrong) << " | " << pct(r.raw.hitmiss) << " | " << sci(r.raw.depth_median) << " | "
       << sci(r.raw.depth_max) << " | " << big(r.cycles) << " | " << r.host_triangles << " | " << big(r.host_tests)
       << " | " << pct(r.fallback.wrong) << " | " << pct(r.fallback.hitmiss) << " | " << big(r.render_cycles) << " | "
       << db(r.psnr) << " | " << r.pixels_off << " |\n";
  }
  md << "\n";
}

void leak_table(std::ostream& md, const Leaks& leaks) {
  md << "## Leak rate on a closed mesh around the eye\n\n";
  md << "The closed, perturbed sphere of `sw/isect/meshes.h` (" << leaks.sphere_triangles
     << " triangles, every edge shared by two) around the eye: **edge rays** are aimed exactly at its "
     << leaks.edge_rays << " vertex and edge points (`edge_and_vertex_rays`), **uniform rays** are "
     << leaks.uniform_rays
     << " random directions. Every ray must hit; a miss is a leak. `paper, raw` is the const form with "
        "cond_bits = 60, `paper, fallback` the default, `watertight` the exact-integer form. "
        "(`tests/hardcases_test.cpp` asserts the bounds.)\n\n";
  md << "| n | form | steps/bcast | edge rays leaking | % | uniform rays leaking | % | host tris |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const LeakRow& l : leaks.rows) {
    md << "| " << l.n << " | " << l.form << " | " << fmt(l.steps, 1) << " | " << l.edge_leaks << " of " << l.edge_rays
       << " | " << pct(static_cast<double>(l.edge_leaks) / static_cast<double>(l.edge_rays)) << " | " << l.uniform_leaks
       << " of " << l.uniform_rays << " | "
       << pct(static_cast<double>(l.uniform_leaks) / static_cast<double>(l.uniform_rays)) << " | " << l.host_triangles
       << " |\n";
  }
  md << "\n";
}

// Per scene, the smallest n meeting each criterion (const form unless named).
void choosing_n(std::ostream& md, const std::vector<Choice>& choices) {
  md << "## Choosing n\n\n";
  md << "Smallest n (of those measured) at which, per scene: the raw machine gets at most 0.1 % of the primary "
        "rays wrong (wrong + hit/miss); the fallback sends at most 1 % of the triangles to the host; the full "
        "render reaches 40 dB PSNR; all three, with the const form's steps per broadcast there; and the "
        "watertight form's raw error is at most 0.1 %.\n\n";
  md << "| scene | raw error <= 0.1 % | host triangles <= 1 % | render PSNR >= 40 dB | all three | steps/bcast there "
        "| watertight raw error <= 0.1 % | its steps/bcast |\n| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  auto steps_of = [](const Row* r) { return r ? fmt(r->steps, 1) : std::string("-"); };
  for (const Choice& c : choices) {
    md << "| " << c.scene << " | " << n_of(c.raw) << " | " << n_of(c.host) << " | " << n_of(c.image) << " | "
       << n_of(c.all) << " | " << steps_of(c.all) << " | " << n_of(c.wt) << " | " << steps_of(c.wt) << " |\n";
  }
  md << "\n";
}

// The reading of the numbers is prose written for the full run; a quick run says so.
void reading(std::ostream& md, bool quick) {
  md << (quick ? "(A quick run: too few pixels and widths to read anything into; see docs/precision.md.)"
               : kReading)
     << "\n\n";
}

void plots_and_cases(std::ostream& md, const Options& o, double seconds) {
  md << "## Plots\n\n![accuracy against cycles](img/precision_scenes.png)\n\n"
        "![leak rate and steps per broadcast against n](img/precision_leaks.png)\n\n";
  md << kHardCases << "\n";
  md << "Reproduce: `make build && build/fmpp-report precision` (writes this file, " << o.img_dir
     << "/precision_{scenes,leaks}.png and " << o.img_dir << "/precision_data.json; about "
     << fmt(std::max(1.0, std::round(seconds / 60)))
     << " min on the machine above). `--quick` is the ctest smoke run (without `--out` it writes "
        "precision-quick.md, never this file).\n";
}

}  // namespace

std::string markdown(const Options& o, const Setup& s, const std::string& date, double seconds,
                     const SceneResults& r, const Leaks& l, const std::vector<Choice>& c) {
  std::ostringstream md;
  intro(md, o, s, date, seconds, r.consistent);
  what_is_measured(md);
  for (const SceneTable& t : r.tables) scene_table(md, t);
  leak_table(md, l);
  choosing_n(md, c);
  reading(md, o.quick);
  plots_and_cases(md, o, seconds);
  return md.str();
}

}  // namespace fmpp::report::precision
