// fmpp-report paper, the clock model (paper.h). Clocks scale linearly with rays,
// triangles and passes, and every instruction takes one clock whatever the number of
// blocks, so the measured per-broadcast, per-ray and per-triangle costs give exact
// clocks for machines too large to simulate: Table 2, Fig. 7, the Amdahl figures and
// the data of Figs. 5-7 (plotted by tools/plot_paper.py).
#include <cmath>
#include <stdexcept>
#include <string>

#include "sw/report/paper.h"

namespace fmpp::report::paper {

using json = nlohmann::json;

double CostModel::paper_ray(double R, double m, double P) const {
  const double passes = std::ceil(R / P);
  return passes * m * (36.0 * n + 95) + 18 * R;
}

double CostModel::ours_ray(double R, double m, double P, double steps) const {
  const double passes = std::ceil(R / P);
  return passes * (m * steps + rp_init) + R * (rp_load_ray + rp_read_ray);
}

double CostModel::ours_obj(double R, double m, double P, double steps) const {
  const double passes = std::ceil(m / P);
  return passes * (R * (steps + op_read_ray) + op_init) + m * op_load_tri;
}

CostModel fit_model(const Workload& w, const Broadcasts& b, unsigned n) {
  const Run& rp_const = b.rp_const;
  const Run& op_const = b.op_const;
  const std::vector<fmpp::isect::Ray>& rays_rp = w.rays_rp;
  const std::vector<fmpp::isect::Ray>& rays_op = w.rays_op;
  const double op_tris = static_cast<double>(w.scene_op.size());
  CostModel cm;
  cm.n = n;
  cm.rp_steps = rp_const.st.steps_per_broadcast();
  cm.rp_init = static_cast<double>(rp_const.st.load_cycles) -
               3.0 * static_cast<double>(rays_rp.size());  // the rest of the load is the 3 words per ray
  cm.rp_load_ray = 3.0;
  cm.rp_read_ray = static_cast<double>(rp_const.st.readback_cycles) / static_cast<double>(rays_rp.size());
  cm.op_steps = op_const.st.steps_per_broadcast();
  cm.op_read_ray = static_cast<double>(op_const.st.readback_cycles) / static_cast<double>(rays_op.size());
  cm.op_load_tri = 12.0;
  cm.op_init = static_cast<double>(op_const.st.load_cycles) - 12.0 * op_tris;
  return cm;
}

namespace {

// Table 2: m = 10,000 triangles, one block per ray or per triangle.
std::vector<Table2Row> table2(const CostModel& cm, const Broadcasts& b) {
  const double m = 10000;
  std::vector<Table2Row> rows;
  for (double side : {128.0, 512.0, 1024.0}) {
    const double R = side * side;
    const double seq = cm.seq(R, m);
    Table2Row t;
    t.side = side;
    t.paper_ray = seq / cm.paper_ray(R, m, R);
    t.paper_obj = seq / cm.paper_obj(R, m);
    t.ray_generic = seq / cm.ours_ray(R, m, R, b.rp_gen.st.steps_per_broadcast());
    t.ray_const = seq / cm.ours_ray(R, m, R, b.rp_const.st.steps_per_broadcast());
    t.obj_generic = seq / cm.ours_obj(R, m, m, b.op_gen.st.steps_per_broadcast());
    t.obj_const = seq / cm.ours_obj(R, m, m, b.op_const.st.steps_per_broadcast());
    rows.push_back(t);
  }
  return rows;
}

// Fig. 7: 1024 x 1024 rays, ray-parallel on 64^2 and 256^2 blocks.
std::vector<Fig7Row> fig7(const CostModel& cm, const Broadcasts& b) {
  const double m = 10000;
  const double R = 1024.0 * 1024.0;
  std::vector<Fig7Row> rows;
  for (double side : {64.0, 256.0}) {
    const double P = side * side;
    const double seq = cm.seq(R, m);
    rows.push_back(Fig7Row{side, seq / cm.paper_ray(R, m, P),
                           seq / cm.ours_ray(R, m, P, b.rp_gen.st.steps_per_broadcast()),
                           seq / cm.ours_ray(R, m, P, b.rp_const.st.steps_per_broadcast())});
  }
  return rows;
}

json fig7_curves(const CostModel& cm, const Broadcasts& b) {
  const double R = 1024.0 * 1024.0;
  json f7 = json::array();
  for (double side : {64.0, 256.0}) {
    const double P = side * side;
    for (double mm : {100.0, 300.0, 1000.0, 3000.0, 10000.0, 30000.0, 100000.0, 300000.0, 1000000.0}) {
      const double seq = cm.seq(R, mm);
      f7.push_back({{"blocks", P}, {"m", mm}, {"paper", seq / cm.paper_ray(R, mm, P)},
                    {"ray_generic", seq / cm.ours_ray(R, mm, P, b.rp_gen.st.steps_per_broadcast())},
                    {"ray_const", seq / cm.ours_ray(R, mm, P, b.rp_const.st.steps_per_broadcast())}});
    }
  }
  return f7;
}

// Fig. 5 / 6 data: time against triangles, ideal machines.
json fig56(const CostModel& cm, const Broadcasts& b) {
  json f56 = json::array();
  for (double side : {128.0, 512.0, 1024.0}) {
    const double RR = side * side;
    for (double mm : {100.0, 300.0, 1000.0, 3000.0, 10000.0, 30000.0, 100000.0}) {
      f56.push_back({{"rays", RR}, {"m", mm}, {"seq", cm.seq(RR, mm) / 50e6},
                     {"paper_ray", cm.paper_ray(RR, mm, RR) / 50e6}, {"paper_obj", cm.paper_obj(RR, mm) / 50e6},
                     {"ray_generic", cm.ours_ray(RR, mm, RR, b.rp_gen.st.steps_per_broadcast()) / 50e6},
                     {"ray_const", cm.ours_ray(RR, mm, RR, b.rp_const.st.steps_per_broadcast()) / 50e6},
                     {"obj_generic", cm.ours_obj(RR, mm, mm, b.op_gen.st.steps_per_broadcast()) / 50e6},
                     {"obj_const", cm.ours_obj(RR, mm, mm, b.op_const.st.steps_per_broadcast()) / 50e6}});
    }
  }
  return f56;
}

// With intersection 90 % of the ray tracer's time: the paper's two speedups, then ours
// on 64^2 blocks and on the ideal machine (CSD, 1024^2 rays, 10,000 triangles).
std::vector<AmdahlRow> amdahl(const CostModel& cm, const Broadcasts& b) {
  const double m = 10000;
  const double R = 1024.0 * 1024.0;
  std::vector<AmdahlRow> rows;
  for (double s : {100.0, 10000.0, cm.seq(R, m) / cm.ours_ray(R, m, 64.0 * 64, b.rp_const.st.steps_per_broadcast()),
                   cm.seq(R, m) / cm.ours_ray(R, m, R, b.rp_const.st.steps_per_broadcast())}) {
    rows.push_back(AmdahlRow{s, 1.0 / (0.1 + 0.9 / s)});
  }
  return rows;
}

// Ray-parallel CSD broadcasts test (blocks) rays each.
std::vector<CpuRow> cpu_rows(const Broadcasts& b, const CpuRates& rates, const std::vector<Clock>& clocks) {
  const double cpu = rates.cpu;
  std::vector<CpuRow> rows;
  for (double side : {64.0, 256.0, 1024.0}) {
    const double P = side * side;
    CpuRow r{side, P, P * 50e6 / b.rp_const.st.steps_per_broadcast(), 0, {}, {}};
    r.x50 = r.t50 / cpu;
    for (const Clock& c : clocks) {
      r.t.push_back(P * c.mhz * 1e6 / b.rp_const.st.steps_per_broadcast());
      r.x.push_back(r.t.back() / cpu);
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

Clock parse_clock(const std::string& text) {
  const size_t colon = text.find(':');
  Clock c;
  size_t used = 0;
  try {
    c.mhz = std::stod(text.substr(0, colon), &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (colon == std::string::npos || used != colon || !(c.mhz > 0 && c.mhz < 1e6) || colon + 1 >= text.size()) {
    throw std::invalid_argument("--clock '" + text + "': expected MHZ:LABEL, MHz in (0, 1e6) and a label");
  }
  c.label = text.substr(colon + 1);
  return c;
}

Derived derive(const Workload& w, const Broadcasts& b, const CpuRates& cpu, unsigned n,
               const std::vector<Clock>& clocks) {
  Derived d;
  d.cm = fit_model(w, b, n);
  d.table2 = table2(d.cm, b);
  d.fig7 = fig7(d.cm, b);
  const double m = 10000, R = 1024.0 * 1024.0;
  d.fig7_paper_64 = d.cm.seq(R, m) / d.cm.paper_ray(R, m, 64.0 * 64);
  d.fig7_curves = fig7_curves(d.cm, b);
  d.fig56 = fig56(d.cm, b);
  d.amdahl = amdahl(d.cm, b);
  d.cpu = cpu_rows(b, cpu, clocks);
  d.clocks = clocks;
  return d;
}

json report_data(const Table1& t1, const Sweep& sweep, const CpuRates& cpu, const Derived& d) {
  json data;
  data["table1"] = {{"transfer", t1.transfer_instructions}, {"sign", t1.sign_instructions}, {"max", t1.max_instructions}};
  json sw = json::array();
  for (const SweepRow& r : sweep.rows) {
    sw.push_back({{"n", r.n}, {"ray_generic", r.ray_generic}, {"ray_const", r.ray_const},
                  {"obj_generic", r.obj_generic}, {"obj_const", r.obj_const}});
  }
  data["sweep"] = sw;
  json t2 = json::array();
  for (const Table2Row& r : d.table2) {
    t2.push_back({{"side", r.side}, {"paper_ray", r.paper_ray}, {"paper_obj", r.paper_obj},
                  {"ray_generic", r.ray_generic}, {"ray_const", r.ray_const}, {"obj_generic", r.obj_generic},
                  {"obj_const", r.obj_const}});
  }
  data["table2"] = t2;
  data["fig7"] = d.fig7_curves;
  data["fig56"] = d.fig56;
  json cpu_rows = json::array();
  for (const CpuRow& r : d.cpu) cpu_rows.push_back({{"blocks", r.blocks}, {"t50", r.t50}, {"t_at_clocks", r.t}});
  json clocks = json::array();
  for (const Clock& c : d.clocks) clocks.push_back({{"mhz", c.mhz}, {"label", c.label}});
  data["cpu"] = {{"tests_per_s", cpu.cpu}, {"reference_tests_per_s", cpu.ref}, {"clocks", clocks}, {"rows", cpu_rows}};
  return data;
}

}  // namespace fmpp::report::paper
