// fmpp-report precision, the Markdown (precision.h): one function per section of
// docs/generated/precision.md, each formatting figures measured or chosen before; the prose that
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
const char* kReading = R"(**What the numbers mean for choosing n** (read from the tables above; the figures below
are those of the run of 2026-11-24, and a regeneration that changes them says so in the
tables first):

- **Every form and mapping is certified, so every answer is right at every n.** The
  wrong and hit/miss columns are 0 for every scene, form and n from 8 to 32: the paper's
  form (both multiplies), the watertight form, the object-parallel mapping, and in the
  renders the arbitrary-origin form of the reflection and refraction rays. A decision
  that is not certain within the form's bound is flagged and redone exactly on the host,
  and a t whose bound exceeds 2^-12 is computed there
  ([intersection.md](../intersection.md#certified-results-certifyh) derives each form's
  bounds). The renders are identical to the reference's, or at 78-83 dB where a t
  within its 2^-12 moves a shading value by a level (50 dB once: one pixel of
  spheres_10k, object-parallel at n = 32, where such a t tips a shadow ray at an edge).
  What n buys is work kept off the host, and clocks.
- **The host's share falls steeply with n.** With the constant multiply the render's
  flagged share is 11.6 % (cornell), 4.8 % (spheres_1k) and 14.3 % (spheres_10k) at
  n = 16, 0.20 %, 0.25 % and 1.8 % at n = 20 and 0.07 %, 0 % and 0.12 % at n = 24;
  the t from the host follows (64 %, 53 %, 43 % at n = 16; 0.13 %, 0.38 %, 1.9 % at
  n = 24). Below n = 16 the condition limit sends most triangles to the host anyway.
  The "redone <= 1 %" column is where the host's share (flagged and t) falls under 1 %:
  n = 24 for cornell and spheres_1k, 32 for spheres_10k at these 32 x 32 pixels.
- **Clocks grow linearly with n.** The constant (CSD) multiply with the certainty tests
  costs about 6n + 40 steps per broadcast (82.5 at n = 8, 184 at 24, 231 at 32 on
  cornell) and the generic one 22n + 55, 3.2 to 3.6 times more, for bit-identical
  results (checked on every ray and image here). Use the constant multiply at every n.
- **The watertight form** evaluates the edge functions on the scene's own vertices
  ([intersection.md](../intersection.md#the-watertight-form-form_watertightcpp-certify_watertightcpp)):
  nothing moves, it lets no ray through the closed sphere at any n, and its t is tighter
  (its render's t from the host: 0 % on cornell and spheres_1k at n = 24, against 0.13 %
  and 0.38 % with the paper's form). It costs about 22 % more steps per broadcast (225.6
  against 183.6 at n = 24 on cornell) and more render clocks (809k against 644k on
  cornell at n = 24; 1.70M against 0.88M on spheres_10k, where the FMPP's box test and
  the probe serve only the paper's form), so it meets the host criterion at a lower n
  (24, 20 and 24) for more clocks.
- **The object-parallel mapping** certifies the same answers with per-block bounds and
  flags fewer primary rays at low n (0.29 % on cornell at n = 16, against 1.3 %), but a
  frame of 1,024 primary rays, each a broadcast, costs 4.5 to 65 times the
  ray-parallel clocks (306k against 49k on cornell at n = 24): it pays only for far
  fewer rays per frame than triangles.
- **The Pareto plot** below puts each scene's render clocks against the host's share:
  every point gives the same certified answers, so its front is the choice. It runs
  from n = 8 (few FMPP clocks, most of the work on the host) to the constant-multiply
  paper form at n = 24 and 32 (at most 2 % on the host); the watertight form is on it
  at n = 8-16 of one_triangle (n = 16: nothing on the host at 5.3k clocks).
- **A scanned mesh (armadillo, 52,532 triangles)** behaves like the sphere fields at
  a larger n: its small triangles seen from the eye exceed the condition limit below
  n = 24 (61 host triangles there, 768 at n = 20), and its render's host share falls
  from 27 % at n = 20 to 6.9 % at n = 24 and 0.27 % at n = 32 with the constant
  multiply (mostly t from the host: far, small triangles leave loose t bounds); the
  watertight form's tighter t needs the host for 0.9 % at n = 24. The object-parallel
  mapping gives 46 % of its render's t to the host at n = 32 against 0.8 % at n = 24
  (54 % of its primary hits, the same at n = 28): from n = 28 its condition limit is
  2^25, and 56 ill-conditioned triangles that are host triangles at n = 24 (61 host
  triangles against 5; the stage's large ones, its floor seen at a grazing angle among
  them) stay on the FMPP, where its 28-bit matrix mantissas leave their t bounds above
  2^-12: each of their hits takes one exact test on the host, where at n = 24 the host
  tested them for every ray. The answers are right either way.
- **The precision plan** (`fmpp-render`) picks, per frame, the smallest n whose sampled
  primary rays and frame meet the error target (0.2 %) with at most 1 % of the sample's
  rays redone. Its choices on the shipped scenes at 128 x 128, and the measured full
  frames against the target, are in [raytracer.md](../raytracer.md#the-precision-plan)
  (a generated table the ctest docs_check keeps current).
)";

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
| rays exactly through the shared vertex and the shared edges of a closed fan of 7 triangles | reference and watertight (n = 16, 24, 32): every ray hits (no crack), and reports the lowest-index triangle sharing the edge or vertex (the ray meets them at one point); rays 2^-40 of a height inside a triangle hit it; paper forms: any hit is such a triangle, at the right depth | the paper's form decides an exact edge by the sign of a rounded T, so it may crack there (counted, not bounded; the certified ray-parallel form flags such a ray and redoes it exactly); rays 8 cond 2^-min(n,28) of the triangle's height inside a triangle hit exactly that triangle, as the reference does |
| closed perturbed sphere (288 triangles) around the eye, rays aimed exactly at its edges and vertices | every ray hits in the reference; the watertight form never leaks and equals the reference on every ray (n = 16, 24, 32) | the paper's form leaks on exact edges at a rate that does not fall with n (table above): asserted below 35 %; rays a margin (as above) inside every triangle never leak and hit that triangle, in both mappings |
| the same sphere, 12,000 uniformly random directions | the watertight form never leaks | the paper's form leaks only within the crack width of an edge (about cond 2^-n of a triangle's height): asserted at most 16 x 2^-n (measured 4.3-5.5 x 2^-n for n = 8..12, none from 16) |
| eye exactly in a triangle's plane, inside a triangle, and 1e-12, 1e-6, 1e-3 off the plane, with a wall behind | every form equals the reference (n = 16, 24), never a garbage hit; the singular triangle (det = 0) is a host triangle even with cond_bits = 60; nearly singular ones are counted host triangles | - |
| degenerate triangles: collinear vertices (exact integers and dyadic), a repeated vertex, three equal vertices; rays aimed exactly at them | never hit: the rays hit the wall behind, in the reference, both paper forms (default and cond_bits = 60) and the watertight form (n = 16, 24); the four are host triangles | - |
| needles and a sliver of aspect ratio 1e4 (cond 2e4 to 2e5) before a wall; rays inside them and one width outside | paper forms and the watertight form equal the reference at n = 16 (all three are host triangles: cond > 2^13) and n = 24 (on the FMPP); host_triangles counts exactly the triangles above 2^(min(n,28)-3) in both mappings and the watertight form | - |
| a tiny triangle (1e-6) at distance 1, a tiny one 1e-7 in front of the eye, a huge one (1e6 wide) at 1e5 behind a wall | every form equals the reference; ray-parallel tests both the near one (the bound of its compared sum, scaled by the shift to the common exponent, is beyond what a comparison can certify) and the far one on the host; object-parallel tests both tiny ones on the host (the near one's column sums are above its cap), the watertight form as ray-parallel; host_triangles exact | depth: the compared sum keeps at least 9 bits (ray-parallel) or 10 bits (object-parallel) for the farthest hit, so a scene spanning 1e-7 to 1e6 has depth errors up to ~2^-9 there |
| ray directions of lengths 5 to 1e5 in one call | every form equals the reference; t is in units of each ray's own direction | - |
| triangles behind the eye and straddling its plane, rays forward and backward | hits only in front, equal to the reference, every form | - |
| one triangle listed six times with its vertices in every order | a tie: the first copy (lowest index) wins, in the reference and every form | - |
| coplanar overlapping triangles (plane z = 4) | reference, object-parallel and watertight: exact tie, lowest index; ray-parallel (certified): the tie is within the bounds, so the ray is flagged and redone exactly: lowest index | - |
| z-fighting: parallel overlapping planes 1e-2, 1e-3, 1e-9 apart, the farther one first | where the gap exceeds twice the form's depth bound, the nearer triangle, as the reference | below that, either of the two, at the right depth |
| interpenetrating triangles crossing along a line | rays away from the crossing: the nearer one, as the reference | on the crossing line, either |
| a floor of 128 triangles 1 below the eye, rays down to 1e-3 elevation (hits ~1900 away), above the horizon, beyond the floor | paper forms and the watertight form equal the reference at n = 16 (many far tiles are host triangles) and n = 24 | - |
| directions with zero components (along the axes, in the axis planes) in a box around the eye | every form equals the reference | - |
| a scene and eye translated by (1e5, -1e5, 1e5), also rays with their own origins, tmin and an excluded triangle | primary rays equal the reference in the paper forms and the watertight form; arbitrary-origin rays equal it within that kernel's bound 2^-(n-10) | - |
| tiny triangles (0.02 across) 70 from the scene's centre, rays with their own origins aimed inside them (arbitrary-origin kernel) | n = 16: the 16 tiny triangles are host triangles (edge-test condition above 2^(n-4)) and every ray equals the reference; with cond_bits = 60 some rays are wrong; n = 24: on the FMPP, every ray equals the reference | - |
| rays that miss everything, an empty scene, an empty batch | all misses, no host work, no overflow | - |

**Depth bounds used by the tests** (`allowed` in the test file): the paper's forms make
a relative error of about cond 2^-min(n,28) in T and hence in S = 1/t (8 cond 2^-bits
allowed), plus the resolution of the compared sum: ray-parallel brings S to one
exponent chosen so that the nearest possible hit (at dmin, the nearest triangle but at
least 2^-20 of the farthest vertex) is ~2^29, so a hit at d keeps S_c >= 2^28 dmin / d
(8 / S_c allowed); object-parallel keeps S_c >= 2^(mbits-2) / (s_max d) (same
allowance). The watertight form is certified: its t is within the requested accuracy
(2^-12 relative) or the host's exact one.

**Bugs these cases found** (each fixed with its test, see the git log): the reference
broke ties between copies of a triangle by rounding (vertex order) and hit degenerate
triangles through their segment; the kernels quantized all ray directions of a call
with one scale (a short ray lost its bits), let object-parallel keep triangles up to
cond 2^25 at any n, let one near-plane triangle take every bit of the object-parallel
S from all others, dropped triangles the watertight form's former vertex grid flattened
(the reference still hits them), and derived scales from an empty scene (undefined behaviour).
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
     << " pixels. The data behind the tables and plots is in `docs/data/precision_data.json`.\n\n";
  if (!consistent) {
    md << "**Generic and constant multiplies gave different results somewhere: see the tool's output. "
          "They must not (docs/intersection.md).**\n\n";
  }
}

void what_is_measured(std::ostream& md) {
  md << R"(## What is measured

- **n**: the multiplier width (`KernelOptions::n`): the mantissas of P^-1 in the paper's
  form, the edge constants and the compared row (w = N / det) in the watertight form. The
  other operand (ray components) has vbits = 28 bits, so beyond n = 28 the triangle
  test gains little.
- **Forms**: `generic` and `const` are the paper's form with the generic shift-and-add
  multiply and the constant-specialised (CSD) one: bit-identical results by
  construction (checked here on every image and every primary ray), different cycles.
  `watertight` is the certified edge-function form on the scene's own vertices (always
  constant multiplies).
- **steps/bcast**: instructions (= clocks) per triangle broadcast, primary rays.
- **frame clocks**: FMPP clocks for all primary rays of the image (load, broadcasts,
  readback), counted by the golden model; **render clocks**: for the whole Whitted
  render (primary, shadow, reflection and refraction rays; the secondary rays of mirrors
  and glass use the arbitrary-origin kernel).
- **Raw machine** (`cond_bits = 60`): every triangle on the FMPP, so the error is the
  fixed-point format's. **Fallback** (the default): ill-conditioned triangles (cond >
  2^(min(n,28)-3)) and, in the watertight form, triangles whose orientation is not
  certain are intersected on the host (**host tris**, **host tests** = ray-triangle tests the host
  did instead), and overflowed rays are redone there: the cost of correctness.
- Per primary ray, against the double-precision reference: **wrong** = both hit,
  different triangles; **hit/miss** = one hits and the other does not (both in % of the
  rays); **depth** = |t - t_ref| / t_ref over the rays hitting the same triangle (median
  and maximum).
- **Certification** ([intersection.md](../intersection.md#certified-results-certifyh)
  derives the error bounds of each form): **flagged** = primary rays whose decision was
  not certain within the bounds, redone exactly on the host; **t host** = certified hits
  whose t bound exceeded the requested accuracy (2^-12), their t computed on the host;
  both in % of the rays a certifying form answered ("-": none did). **render flagged**
  and **render t host**: the same over every ray of the render (shadow rays, and the
  reflection and refraction rays of the arbitrary-origin form, too). `object` is the
  paper's form in the object-parallel mapping for the primary rays (the render's other
  rays are ray-parallel).
- **PSNR**: of the 8-bit image of the full render against the reference render (all
  channels; "identical" when every pixel is equal); **px > 8** = pixels more than 8
  levels off in some channel.

**The error bounds** behind the flagged and t-host columns are derived, per form, in
[intersection.md](../intersection.md#certified-results-certifyh): the paper's form
(P^-1 rows and the compared sum from the host's rounding, the mantissas, the quantized
direction and the floors), the object-parallel mapping (the same, per block, held in
words), the watertight form (edge functions on the scene's own vertices) and the
arbitrary-origin form (edge rows, det and the quotient). Each bound is checked against
exact rational arithmetic by the certify tests. The randomized differential tests of
every form against exact arithmetic, and full renders of every scene at the plan's n
against the exact reference, are in [certification.md](../certification.md).

)";
}

// a / b in %, "-" when b = 0 (no ray took a certified form).
std::string share(uint64_t a, uint64_t b) {
  return b ? pct(static_cast<double>(a) / static_cast<double>(b)) : std::string("-");
}

void scene_table(std::ostream& md, const SceneTable& t) {
  md << "## " << t.name << " (" << t.triangles << " triangles)\n\n";
  md << "| n | form | steps/bcast | raw: frame clocks | wrong % | hit/miss % | depth median | depth max | "
        "fallback: frame clocks | host tris | host tests | wrong % | hit/miss % | flagged % | t host % | render clocks | "
        "render flagged % | render t host % | PSNR dB | px > 8 |\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Row& r : t.rows) {
    md << "| " << r.n << " | " << r.form << " | " << fmt(r.steps, 1) << " | " << big(r.raw_cycles) << " | "
       << pct(r.raw.wrong) << " | " << pct(r.raw.hitmiss) << " | " << sci(r.raw.depth_median) << " | "
       << sci(r.raw.depth_max) << " | " << big(r.cycles) << " | " << r.host_triangles << " | " << big(r.host_tests)
       << " | " << pct(r.fallback.wrong) << " | " << pct(r.fallback.hitmiss) << " | " << share(r.flagged, r.certified_rays)
       << " | " << share(r.t_redone, r.certified_rays) << " | " << big(r.render_cycles) << " | "
       << (r.render_certified ? share(r.render_flagged, r.render_rays) : std::string("-")) << " | "
       << (r.render_certified ? share(r.render_t_host, r.render_rays) : std::string("-")) << " | " << db(r.psnr)
       << " | " << r.pixels_off << " |\n";
  }
  md << "\n";
}

void leak_table(std::ostream& md, const Leaks& leaks) {
  md << "## Leak rate on a closed mesh around the eye\n\n";
  md << "The closed, perturbed sphere of `sw/report/meshes.h` (" << leaks.sphere_triangles
     << " triangles, every edge shared by two) around the eye: **edge rays** are aimed exactly at its "
     << leaks.edge_rays << " vertex and edge points (`edge_and_vertex_rays`), **uniform rays** are "
     << leaks.uniform_rays
     << " random directions. Every ray must hit; a miss is a leak. `paper, raw` is the const form with "
        "cond_bits = 60, `paper, fallback` the default, `watertight` the certified edge-function form. "
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
        "render reaches 40 dB PSNR; the host redoes at most 1 % of the render's rays to certify them (flagged, or "
        "t beyond 2^-12); all four, with the const form's steps per broadcast there; and the same four for the "
        "watertight form.\n\n";
  md << "| scene | raw error <= 0.1 % | host triangles <= 1 % | render PSNR >= 40 dB | redone <= 1 % | all four | "
        "steps/bcast there | watertight: all four | its steps/bcast |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  auto steps_of = [](const Row* r) { return r ? fmt(r->steps, 1) : std::string("-"); };
  for (const Choice& c : choices) {
    md << "| " << c.scene << " | " << n_of(c.raw) << " | " << n_of(c.host) << " | " << n_of(c.image) << " | "
       << n_of(c.redone) << " | " << n_of(c.all) << " | " << steps_of(c.all) << " | " << n_of(c.wt) << " | " << steps_of(c.wt) << " |\n";
  }
  md << "\n";
}

// The reading of the numbers is prose written for the full run; a quick run says so.
void reading(std::ostream& md, bool quick) {
  md << (quick ? "(A quick run: too few pixels and widths to read anything into; see docs/generated/precision.md.)"
               : kReading)
     << "\n\n";
}

void plots_and_cases(std::ostream& md, double seconds) {
  md << "## Plots\n\n![accuracy against cycles](../img/precision_scenes.png)\n\n"
        "![leak rate and steps per broadcast against n](../img/precision_leaks.png)\n\n"
        "![FMPP clocks against the host's share of certified results](../img/precision_pareto.png)\n\n";
  md << kHardCases << "\n";
  md << "Reproduce: `build/fmpp-report precision` (about " << fmt(std::max(1.0, std::round(seconds / 60)))
     << " min on the machine above) writes this file, its plots and its data into the build directory "
        "(build/docs/generated/precision.md, build/docs/img/precision_{scenes,leaks,pareto}.png, "
        "build/docs/data/precision_data.json); `make docs` runs it with the other generators and `make "
        "docs-update` copies the results over the committed ones. `--quick` is the ctest smoke run "
        "(build/precision-quick.md).\n";
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
  plots_and_cases(md, seconds);
  return md.str();
}

}  // namespace fmpp::report::precision
