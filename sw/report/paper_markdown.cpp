// fmpp-report paper, the Markdown (paper.h): the tables and values of
// docs/generated/paper-reproduction.md, filled into sw/report/templates/paper-reproduction.md.in
// (md_template.h), which holds every sentence.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "sw/report/md_template.h"
#include "sw/report/paper.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp::report::paper {
namespace {

std::string fmt_sig(double v) {
  char buf[64];
  if (v >= 1e6) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.0f", v);
  }
  return buf;
}

std::string table1(const Table1& t, unsigned n) {
  std::ostringstream md;
  md << "| operation | paper | ours (instructions) | ours on the RTL (clocks) | how |\n| --- | --- | --- | --- | --- |\n";
  md << "| data transfer | 5 | " << t.transfer_instructions << " (or 1 bus write) | " << t.transfer_cycles
     << " | `SETSADR b; MASKSET 0; WRITES w`, or one write to the WORDS window |\n";
  for (const auto& [k, v] : t.mul_gen) {
    md << "| multiply, n = " << k << " | " << 4 * k - 2 << " (4n - 2) | " << v.first << " (4n + 1) | " << v.second
       << " | generic: per bit MASKSET, REF, ADD (SUB for the sign bit), RSHIFT |\n";
  }
  for (const auto& [k, v] : t.mul_csd) {
    md << "| multiply by a constant, n = " << k << " | - | " << fmt(v[0], 1) << " mean (" << fmt(v[1]) << ".." << fmt(v[2])
       << ") | = instructions | CSD: one ADD/SUB per non-zero digit, each shifting the partial sum by the distance from the previous digit (SHR_A), and one RSHIFT (2000 random constants) |\n";
  }
  md << "| sign test | 4 | " << t.sign_instructions << " (1 when the mask is set) | " << t.sign_instructions
     << " | `MASKSET 0x7fffffff; REF.and f = f, w ~ 0` |\n";
  md << "| maximum search, n = " << n << " | " << 3 * n + 1 << " (3n + 1) | " << t.max_instructions << " (3n) | "
     << t.max_instructions << " | per bit `MASKSET; REF.and tmp = cand; FLAGOP.any cand = tmp` |\n";
  return md.str();
}

std::string broadcast_table(const Broadcasts& b, unsigned n) {
  std::ostringstream md;
  md << "| mapping | multiply | paper | ours: steps per broadcast | ours: to the T >= 0 test | RTL clocks / broadcast |\n";
  md << "| --- | --- | --- | --- | --- | --- |\n";
  auto row = [&](const char* map, const char* mulname, const std::string& paper, const Run& r) {
    md << "| " << map << " | " << mulname << " | " << paper << " | " << fmt(r.st.steps_per_broadcast(), 1) << " | "
       << fmt(r.st.test_steps_per_broadcast(), 1) << " | "
       << fmt(static_cast<double>(r.st.compute_cycles) / static_cast<double>(r.st.broadcasts), 1) << " |\n";
  };
  row("ray-parallel", "generic", "36n + 95 = " + std::to_string(36 * n + 95), b.rp_gen);
  row("ray-parallel", "constant (CSD)", "-", b.rp_const);
  row("object-parallel", "generic", "36n + 5 = " + std::to_string(36 * n + 5), b.op_gen);
  row("object-parallel", "constant (CSD)", "-", b.op_const);
  return md.str();
}

// The sweep's table, and the widths at which a mapping broadcast nothing (no steps per
// broadcast: the certified paper form gave every triangle to the host).
std::string sweep_table(const Sweep& s, std::vector<unsigned>& none) {
  std::ostringstream md;
  md << "| n | ray generic | ray CSD | object generic | object CSD | paper ray | paper object |\n"
     << "| --- | --- | --- | --- | --- | --- | --- |\n";
  auto steps = [&](double v, unsigned k) {
    if (v > 0) return fmt(v, 1);
    if (std::find(none.begin(), none.end(), k) == none.end()) none.push_back(k);
    return std::string("- (no broadcast)");
  };
  for (const SweepRow& r : s.rows) {
    const unsigned k = r.n;
    md << "| " << k << " | " << steps(r.ray_generic, k) << " | " << steps(r.ray_const, k) << " | "
       << steps(r.obj_generic, k) << " | " << steps(r.obj_const, k) << " | " << 36 * k + 95 << " | " << 36 * k + 5
       << " |\n";
  }
  return md.str();
}

std::string table2(const Derived& d) {
  std::ostringstream md;
  md << "| rays | paper ray-par. (table) | paper model | ours generic | ours CSD | paper obj.-par. (table) | paper model | ours generic | ours CSD |\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  // The paper's Table 2, for the same ray counts.
  const double table_ray[3] = {420, 5000, 11000}, table_obj[3] = {277, 285, 285};
  int ti = 0;
  for (const Table2Row& r : d.table2) {
    md << "| " << fmt(r.side) << "^2 | " << fmt(table_ray[ti]) << "x | " << fmt(r.paper_ray) << "x | "
       << fmt(r.ray_generic) << "x | " << fmt(r.ray_const) << "x | " << fmt(table_obj[ti]) << "x | "
       << fmt(r.paper_obj) << "x | " << fmt(r.obj_generic) << "x | " << fmt(r.obj_const) << "x |\n";
    ++ti;
  }
  return md.str();
}

std::string fig7_table(const Derived& d) {
  std::ostringstream md;
  md << "| blocks | triangles | paper (text) | paper model | ours generic | ours CSD |\n| --- | --- | --- | --- | --- | --- |\n";
  for (const Fig7Row& r : d.fig7) {
    md << "| " << fmt(r.side) << "^2 | 10,000 | " << (r.side == 64 ? "~130x" : "~1500x") << " | " << fmt(r.paper)
       << "x | " << fmt(r.ray_generic) << "x | " << fmt(r.ray_const) << "x |\n";
  }
  return md.str();
}

std::string amdahl_table(const Derived& d) {
  std::ostringstream md;
  md << "| intersection speedup | overall |\n| --- | --- |\n";
  for (const AmdahlRow& r : d.amdahl) md << "| " << fmt(r.speedup) << "x | " << fmt(r.overall, 2) << "x |\n";
  return md.str();
}

std::string cpu_table(const Derived& d) {
  std::ostringstream md;
  md << "| blocks | tests/s at 50 MHz (the paper's) | x one CPU core |";
  for (const Clock& c : d.clocks) md << " tests/s at " << fmt(c.mhz, 1) << " MHz (" << c.label << ") | x one CPU core |";
  md << "\n| --- | --- | --- |";
  for (size_t i = 0; i < d.clocks.size(); ++i) md << " --- | --- |";
  md << "\n";
  for (const CpuRow& r : d.cpu) {
    md << "| " << fmt(r.side) << "^2 | " << fmt_sig(r.t50) << " | " << fmt(r.x50, 1) << " |";
    for (size_t i = 0; i < r.t.size(); ++i) md << " " << fmt_sig(r.t[i]) << " | " << fmt(r.x[i], 1) << " |";
    md << "\n";
  }
  return md.str();
}

// The notes under the sweep, one per width at which a mapping broadcast nothing.
std::string no_broadcast_notes(const std::vector<unsigned>& none) {
  std::string notes;
  for (unsigned k : none) {
    notes += fill_template("paper_no_broadcast.md.in",
                           {{"n", std::to_string(k)}, {"mantissa_bits", std::to_string(k - 1)}});
  }
  return notes;
}

std::string clock_comparison(const Measured& m) {
  std::ostringstream md;
  write_clock_comparison(m.fpga, m.b.rp_const.st.steps_per_broadcast(), m.cpu.cpu, md);
  return md.str();
}

}  // namespace

std::string markdown(const Options& o, const Config& rcfg, const std::string& date, const Measured& m,
                     const Derived& d) {
  const Broadcasts& b = m.b;
  std::vector<unsigned> none;
  const std::string sweep = sweep_table(m.sweep, none);
  auto count = [](auto v) { return std::to_string(v); };
  return fill_template(
      "paper-reproduction.md.in",
      {{"date", date},
       {"machine", machine_description()},
       {"verilator", backends::verilator_version()},
       {"rtl_config", o.rtl_config},
       {"rtl_size", rcfg.str()},
       {"table1", table1(m.t1, o.n)},
       {"scene_triangles", count(m.w.scene_triangles)},
       {"rays_rp", count(m.w.rays_rp.size())},
       {"rays_op", count(m.w.rays_op.size())},
       {"scene_op", count(m.w.scene_op.size())},
       {"n", count(o.n)},
       {"broadcast_table", broadcast_table(b, o.n)},
       {"op_search", fmt(b.op_search)},
       {"object_searches", count(b.op_const.st.object_searches)},
       {"op_broadcasts", count(b.op_const.st.broadcasts)},
       {"sweep_triangles", count(m.sweep.triangles)},
       {"sweep_rays", count(m.w.rays_op.size())},
       {"sweep_table", sweep},
       {"no_broadcast_notes", no_broadcast_notes(none)},
       {"rp_read_ray", fmt(d.cm.rp_read_ray, 2)},
       {"op_read_ray", fmt(d.cm.op_read_ray, 2)},
       {"table2", table2(d)},
       {"fig7_table", fig7_table(d)},
       {"fig7_paper_64", fmt(d.fig7_paper_64)},
       {"amdahl_table", amdahl_table(d)},
       {"cpu_rate", fmt_sig(m.cpu.cpu)},
       {"reference_rate", fmt_sig(m.cpu.ref)},
       {"csd_clocks", fmt(b.rp_const.st.steps_per_broadcast(), 0)},
       {"cpu_table", cpu_table(d)},
       {"clock_comparison", clock_comparison(m)}});
}

}  // namespace fmpp::report::paper
