// The pieces of `fmpp-report precision` and the data passed between them:
//   precision_measure.cpp   runs the kernels and renders on the golden model and the
//                           double-precision reference: errors, clocks, PSNR per scene,
//                           form and n; leaks on a closed mesh;
//   precision_choose.cpp    reads the measurements: per scene the smallest n meeting
//                           each accuracy criterion, and the JSON data of the plots;
//   precision_markdown.cpp  the report's text, one function per section;
//   precision.cpp           the subcommand: options, then measure, choose, write.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/util/source_tree.h"
#include "fmpp/config.h"
#include "sw/isect/kernels.h"
#include "sw/report/output.h"

namespace fmpp::report::precision {

struct Options : ReportOutput {
  Options() : ReportOutput("precision.md", "precision-quick", "precision_data.json", "plot_precision.py") {}
  std::string scenes_dir = source_file("scenes");
  int size = 32;
  std::string only_scene;  // measure this scene only, no leak rates (tools/docs.py check)
};

// The machine every figure is measured on: the RTL's medium configuration (a 32 x 32
// image is one pass of primary rays), simulated by the golden model. The quick smoke
// run uses the small one (64 blocks), whose instructions simulate 16 times faster.
inline const Config kMachine{1024, 32};
inline const Config kQuickMachine{64, 32};
inline const char* const kScenes[] = {"cornell", "spheres_1k", "spheres_10k", "one_triangle"};
// A real scanned mesh (52,532 triangles), in the full run only.
inline const char* const kScannedScene = "armadillo";

// What one run measures over: the image size, the machine and the widths n.
struct Setup {
  int size = 0;
  Config machine;
  std::vector<unsigned> bits;
  std::chrono::steady_clock::time_point start;  // for the progress lines
};
Setup make_setup(const Options& o);

// ------------------------------------------------------------------ measured

// Errors of one set of hits against the reference's, per ray.
struct Errors {
  double wrong = 0;    // both hit, different triangles
  double hitmiss = 0;  // one hits, the other does not
  double depth_median = 0, depth_max = 0;  // |t - t_ref| / t_ref where both hit the same triangle
};

// One row of a scene table.
struct Row {
  unsigned n = 0;
  std::string form;
  double steps = 0;  // per broadcast, primary rays, raw
  uint64_t broadcasts = 0;
  uint64_t raw_cycles = 0;  // primary frame, cond_bits = 60
  Errors raw;
  uint64_t cycles = 0;  // primary frame, default fallback
  Errors fallback;
  uint64_t host_triangles = 0, host_tests = 0, overflow_rays = 0;
  uint64_t render_cycles = 0, render_host_tests = 0;
  // Certification (docs/intersection.md, "Certified results"), primary frame with the
  // fallback: rays flagged uncertain and redone on the host, hits whose t came from the
  // host, out of the rays of certified forms; and over the whole render.
  uint64_t flagged = 0, t_redone = 0, certified_rays = 0;
  uint64_t render_flagged = 0, render_t_host = 0, render_rays = 0, render_certified = 0;
  uint64_t render_redone() const { return render_flagged + render_t_host; }
  double psnr = 0;
  uint64_t pixels_off = 0;  // pixels more than 8 levels off the reference render
};

struct SceneTable {
  std::string name;
  size_t triangles = 0;
  std::vector<Row> rows;  // for each n, each form
};

struct SceneResults {
  std::vector<SceneTable> tables;  // in kScenes order, then kScannedScene (full run)
  bool consistent = true;          // generic and const gave bit-identical results everywhere
};

// One row of the leak table.
struct LeakRow {
  unsigned n = 0;
  std::string form;
  double steps = 0;
  size_t edge_leaks = 0, edge_rays = 0, uniform_leaks = 0, uniform_rays = 0;
  uint64_t host_triangles = 0;
};

struct Leaks {
  size_t sphere_triangles = 0, edge_rays = 0, uniform_rays = 0;
  std::vector<LeakRow> rows;
};

// Every scene of kScenes at every n and form: the raw machine, the default fallback
// and the full render, each against the reference.
SceneResults measure_scenes(const Options& o, const Setup& s);
// The closed sphere around the eye: rays at its edges and vertices, and uniform rays.
Leaks measure_leaks(const Options& o, const Setup& s);

// ------------------------------------------------------------------ choosing

// Per scene, the smallest n measured that meets each criterion (nullptr: none does);
// the rows point into the SceneTable's.
struct Choice {
  std::string scene;
  const Row* raw = nullptr;    // const form: raw error (wrong + hit/miss) <= 0.1 %
  const Row* host = nullptr;   // const form: host triangles <= 1 %
  const Row* image = nullptr;  // const form: render PSNR >= 40 dB
  const Row* redone = nullptr;  // const form: rays of the render redone on the host (certification) <= 1 %
  const Row* all = nullptr;    // const form: all four
  const Row* wt = nullptr;     // watertight form: all four
};
std::vector<Choice> choose_n(const SceneResults& r);

// "-" for no row, else its n.
std::string n_of(const Row* r);

// The JSON data behind the report and its plots (img_dir/precision_data.json).
nlohmann::json report_data(const Setup& s, const SceneResults& r, const Leaks& l, const std::vector<Choice>& c);

// ----------------------------------------------------------------- Markdown

std::string markdown(const Options& o, const Setup& s, const std::string& date, double seconds,
                     const SceneResults& r, const Leaks& l, const std::vector<Choice>& c);

}  // namespace fmpp::report::precision
