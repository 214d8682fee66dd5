// The pieces of `fmpp-report paper` and the data passed between them:
//   paper_measure.cpp   runs the machines: the Verilated RTL (the golden model where the
//                       RTL would be too slow) and the CPU baseline;
//   paper_model.cpp     the clock model: the paper's and ours, fitted from the measured
//                       costs, giving Table 2, Fig. 5-7 and Amdahl for machines too large
//                       to simulate, and the JSON data the plots are drawn from;
//   paper_markdown.cpp  the report's text, one function per section;
//   paper.cpp           the subcommand: options, then measure, model, write.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/util/source_tree.h"
#include "fmpp/config.h"
#include "sw/isect/kernels.h"
#include "sw/report/fpga.h"
#include "sw/report/output.h"

namespace fmpp::report::paper {

struct Options : ReportOutput {
  Options() : ReportOutput("paper-reproduction.md", "paper-quick", "paper_data.json", "plot_paper.py") {}
  std::string rtl_config = "small";
  unsigned triangles = 10000;
  unsigned n = 32;
  bool counts_only = false;  // no CPU timing: its sections hold placeholders (tools/docs.py check)
  // Clocks beside the paper's 50 MHz in the comparison with the CPU, as "MHZ:LABEL" (the
  // label says whether measured or projected: make docs passes make asic's measured clock
  // and its projection to the CPU's node, tools/node_scale.py).
  std::vector<std::string> clocks;
  std::string fpga_csv = source_file("docs/data/fpga/summary.csv");  // make fpga's figures (fpga.cpp)
};

// ------------------------------------------------------------------ measured

// Table 1: instructions (and RTL clocks) of the basic operations.
struct Table1 {
  size_t transfer_instructions = 0;
  uint64_t transfer_cycles = 0;                              // on the RTL
  std::map<unsigned, std::pair<size_t, uint64_t>> mul_gen;  // n -> instructions, RTL clocks
  std::map<unsigned, std::array<double, 3>> mul_csd;        // n -> mean, min, max
  size_t sign_instructions = 0;
  size_t max_instructions = 0;                               // maximum search at the report's n
};

// One kernel call: its counters and wall time.
struct Run {
  fmpp::isect::KernelStats st;
  double wall = 0;
};

// The scene and rays of the step counts.
struct Workload {
  unsigned scene_triangles = 0;                  // m_scene: --triangles, at most 300 with --quick
  std::vector<fmpp::isect::Triangle> scene;
  std::vector<fmpp::isect::Ray> rays_rp;         // ray-parallel: one per block
  std::vector<fmpp::isect::Triangle> scene_op;   // object-parallel: one triangle per block
  std::vector<fmpp::isect::Ray> rays_op;
};

// Steps per broadcast of both mappings and both multiplies, on the RTL.
struct Broadcasts {
  Run rp_const, rp_gen, op_const, op_gen;
  double op_search = 0;  // instructions of the object-parallel maximum search
};

// Steps per broadcast against n, on the golden model.
struct SweepRow {
  unsigned n = 0;
  double ray_generic = 0, ray_const = 0, obj_generic = 0, obj_const = 0;
};
struct Sweep {
  size_t triangles = 0;
  std::vector<SweepRow> rows;
};

// Ray-triangle tests per second on one core of this machine.
struct CpuRates {
  double cpu = 0;  // the optimized single-precision brute-force loop
  double ref = 0;  // the double-precision watertight reference
};

Table1 measure_table1(const std::string& rtl_config, const Config& rcfg, unsigned n);
Workload make_workload(const Config& rcfg, unsigned scene_triangles, bool quick);
Broadcasts measure_broadcasts(const Config& rcfg, const Workload& w, unsigned n);
Sweep measure_sweep(const Config& rcfg, const Workload& w);
CpuRates measure_cpu(bool quick);

// -------------------------------------------------------------------- model

// The paper's clock model (docs/paper.md, section 7) and ours, for R rays, m triangles and P
// blocks at n bits.
struct CostModel {
  unsigned n = 32;
  // Ours, measured.
  double rp_steps = 0;          // per triangle broadcast, ray-parallel
  double rp_init = 0;           // per pass
  double rp_load_ray = 0;       // per ray: its 3 words
  double rp_read_ray = 0;       // per ray: reading its result
  double op_steps = 0;          // per ray broadcast, object-parallel (with the maximum search)
  double op_read_ray = 0;       // per ray per pass: responders and the winner's S
  double op_load_tri = 0;       // per triangle: its 12 words
  double op_init = 0;           // per pass

  double seq(double R, double m) const { return 33 * R * m; }
  double paper_ray(double R, double m, double P) const;
  double paper_obj(double R, double m) const { return R * (36.0 * n + 5) + 54 * m; }
  double ours_ray(double R, double m, double P, double steps) const;
  double ours_obj(double R, double m, double P, double steps) const;
};

// Our model's per-ray, per-triangle and per-pass costs from the measured CSD runs.
CostModel fit_model(const Workload& w, const Broadcasts& b, unsigned n);

// Table 2: speedups over the sequential machine, one block per ray or triangle.
struct Table2Row {
  double side = 0;  // rays = side^2
  double paper_ray = 0, paper_obj = 0, ray_generic = 0, ray_const = 0, obj_generic = 0, obj_const = 0;
};
// Fig. 7 at 10,000 triangles: speedups with fewer blocks than rays.
struct Fig7Row {
  double side = 0;  // blocks = side^2
  double paper = 0, ray_generic = 0, ray_const = 0;
};
struct AmdahlRow {
  double speedup = 0, overall = 0;
};
// A clock of the comparison with the CPU, with what it is (measured where, or projected).
struct Clock {
  double mhz = 0;
  std::string label;
};
// Parses --clock's "MHZ:LABEL"; throws std::invalid_argument naming the text.
Clock parse_clock(const std::string& text);
// Test rates of FMPPs of side^2 blocks doing CSD broadcasts, against the CPU.
struct CpuRow {
  double side = 0, blocks = 0;  // blocks = side^2
  double t50 = 0, x50 = 0;      // tests per second at 50 MHz, and over the CPU's rate
  std::vector<double> t, x;     // the same at each of Options::clocks
};

// Everything the clock model derives from the measurements.
struct Derived {
  CostModel cm;
  std::vector<Table2Row> table2;
  std::vector<Fig7Row> fig7;
  double fig7_paper_64 = 0;  // the paper's model at 64^2 blocks (its text says about 130x)
  nlohmann::json fig7_curves, fig56;  // plot data: against the number of triangles
  std::vector<AmdahlRow> amdahl;
  std::vector<CpuRow> cpu;
  std::vector<Clock> clocks;  // of CpuRow::t
};

Derived derive(const Workload& w, const Broadcasts& b, const CpuRates& cpu, unsigned n,
               const std::vector<Clock>& clocks);

// The JSON data behind the report and its plots (img_dir/paper_data.json).
nlohmann::json report_data(const Table1& t1, const Sweep& sweep, const CpuRates& cpu, const Derived& d);

// ----------------------------------------------------------------- Markdown

// The report: what was measured (the inputs) and what the model derived from it.
struct Measured {
  const Table1& t1;
  const Workload& w;
  const Broadcasts& b;
  const Sweep& sweep;
  const CpuRates& cpu;
  const FpgaData& fpga;  // make fpga's place-and-route runs (read, not measured here)
};
std::string markdown(const Options& o, const Config& rcfg, const std::string& date, const Measured& m,
                     const Derived& d);

}  // namespace fmpp::report::paper
