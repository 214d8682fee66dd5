// FPGA figures for the reports (fpga.h); their prose is in sw/report/templates/area_fpga.md.in
// and paper_fpga_clock.md.in (md_template.h).
#include "sw/report/fpga.h"
#include "sw/report/md_template.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace fmpp::report {

namespace {

const char* const kColumns[] = {"device", "package", "blocks", "words", "lcs",     "lcs_avail", "luts",    "dffs",
                                "brams",  "ios",     "fmax_mhz", "placed", "crit_ns", "crit_from", "crit_to"};

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw std::runtime_error(where + ": " + what); }

double parse_number(const std::string& where, const std::string& field, const std::string& text, bool allow_empty) {
  if (text.empty() && allow_empty) return 0;
  size_t used = 0;
  double v = -1;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !(v >= 0)) {
    fail(where, "field '" + field + "' is '" + text + "', not a non-negative number");
  }
  return v;
}

unsigned parse_count(const std::string& where, const std::string& field, const std::string& text) {
  const double v = parse_number(where, field, text, false);
  if (v != std::floor(v) || v > 1e9) fail(where, "field '" + field + "' is '" + text + "', not a count");
  return static_cast<unsigned>(v);
}

std::string fixed(double v, int prec) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

// Three significant digits (e.g. 4.88e+09), on a stream of its own.
std::string sig3(double v) {
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

}  // namespace

FpgaData read_fpga(const std::string& csv) {
  std::ifstream in(csv);
  if (!in) fail(csv, "cannot open (run tools/fpga.sh or make fpga first)");
  FpgaData d;
  std::vector<std::string> header;
  std::string text;
  for (unsigned n = 1; std::getline(in, text); ++n) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty()) continue;
    if (text[0] == '#') {
      d.provenance += text.substr(std::min(text.size(), text.find_first_not_of("# "))) + "\n";
      continue;
    }
    std::vector<std::string> f;
    std::istringstream ls(text);
    for (std::string cell; std::getline(ls, cell, ',');) f.push_back(cell);
    if (text.back() == ',') f.emplace_back();
    const std::string where = csv + ":" + std::to_string(n);
    if (header.empty()) {
      header = f;
      for (const char* c : kColumns) {
        if (std::find(header.begin(), header.end(), c) == header.end()) fail(where, std::string("header has no column '") + c + "'");
      }
      continue;
    }
    if (f.size() != header.size()) {
      fail(where, std::to_string(f.size()) + " fields, the header has " + std::to_string(header.size()));
    }
    std::map<std::string, std::string> v;
    for (size_t i = 0; i < f.size(); ++i) v[header[i]] = f[i];
    FpgaRun r;
    r.device = v["device"];
    r.package = v["package"];
    if (r.device.empty()) fail(where, "field 'device' is empty");
    r.blocks = parse_count(where, "blocks", v["blocks"]);
    r.words = parse_count(where, "words", v["words"]);
    r.lcs = parse_count(where, "lcs", v["lcs"]);
    r.lcs_avail = parse_count(where, "lcs_avail", v["lcs_avail"]);
    r.luts = parse_count(where, "luts", v["luts"]);
    r.dffs = parse_count(where, "dffs", v["dffs"]);
    r.brams = parse_count(where, "brams", v["brams"]);
    r.ios = parse_count(where, "ios", v["ios"]);
    if (v["placed"] != "0" && v["placed"] != "1") fail(where, "field 'placed' is '" + v["placed"] + "', not 0 or 1");
    r.placed = v["placed"] == "1";
    r.fmax_mhz = parse_number(where, "fmax_mhz", v["fmax_mhz"], !r.placed);
    r.crit_ns = parse_number(where, "crit_ns", v["crit_ns"], !r.placed);
    if (r.placed && r.fmax_mhz <= 0) fail(where, "a placed run needs a maximum frequency");
    r.crit_from = v["crit_from"];
    r.crit_to = v["crit_to"];
    d.runs.push_back(r);
  }
  if (header.empty()) fail(csv, "no header line");
  if (d.runs.empty()) fail(csv, "no run");
  return d;
}

const FpgaRun& reference_run(const FpgaData& d) {
  const FpgaRun* best = nullptr;
  for (const FpgaRun& r : d.runs) {
    if (!r.placed) continue;
    if (!best || r.lcs_avail > best->lcs_avail ||
        (r.lcs_avail == best->lcs_avail && (r.blocks > best->blocks ||
                                            (r.blocks == best->blocks && r.fmax_mhz > best->fmax_mhz)))) {
      best = &r;
    }
  }
  if (!best) throw std::runtime_error("FPGA figures: no run was placed and routed");
  return *best;
}

namespace {

std::string runs_table(const FpgaData& d) {
  std::ostringstream out;
  out << "| device | blocks x words | logic cells | LUTs | flip-flops | block RAMs | Fmax (MHz) | critical path (ns) |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const FpgaRun& r : d.runs) {
    out << "| iCE40" << r.device << "-" << r.package << " | " << r.blocks << " x " << r.words << " | " << r.lcs << " / "
        << r.lcs_avail << " (" << fixed(100.0 * r.lcs / r.lcs_avail, 0) << " %) | " << r.luts << " | " << r.dffs
        << " | " << r.brams << " | " << (r.placed ? fixed(r.fmax_mhz, 1) : "does not fit") << " | "
        << (r.placed ? fixed(r.crit_ns, 1) : "-") << " |\n";
  }
  return out.str();
}

// Cost per block: slope between the smallest and the largest block count of one device and word count.
std::string per_block_table(const FpgaData& d) {
  std::ostringstream out;
  out << "| device | words | blocks | LUTs per block | flip-flops per block | logic cells per block | Fmax lost per block (MHz) |\n";
  out << "| --- | ---: | --- | ---: | ---: | ---: | ---: |\n";
  std::map<std::pair<std::string, unsigned>, std::vector<const FpgaRun*>> groups;
  for (const FpgaRun& r : d.runs) groups[{r.device, r.words}].push_back(&r);
  for (auto& [key, g] : groups) {
    std::sort(g.begin(), g.end(), [](const FpgaRun* a, const FpgaRun* b) { return a->blocks < b->blocks; });
    const FpgaRun& lo = *g.front();
    const FpgaRun& hi = *g.back();
    if (hi.blocks == lo.blocks) continue;
    const double db = hi.blocks - lo.blocks;
    out << "| iCE40" << key.first << " | " << key.second << " | " << lo.blocks << " .. " << hi.blocks << " | "
        << fixed((double(hi.luts) - lo.luts) / db, 0) << " | " << fixed((double(hi.dffs) - lo.dffs) / db, 0) << " | "
        << fixed((double(hi.lcs) - lo.lcs) / db, 0) << " | "
        << (hi.placed && lo.placed ? fixed((lo.fmax_mhz - hi.fmax_mhz) / db, 2) : "-") << " |\n";
  }
  return out.str();
}

}  // namespace

void write_fpga_section(const FpgaData& d, std::ostream& out) {
  const FpgaRun& ref = reference_run(d);
  const FpgaRun* small = &ref;
  for (const FpgaRun& r : d.runs) {
    if (r.placed && r.device == ref.device && r.words == ref.words && r.blocks < small->blocks) small = &r;
  }
  std::string provenance;
  std::istringstream prov(d.provenance);
  for (std::string l; std::getline(prov, l);) provenance += "    " + l + "\n";
  const bool above = ref.fmax_mhz >= 50.0;
  out << fill_template("area_fpga.md.in",
                       {{"provenance", provenance},
                        {"runs_table", runs_table(d)},
                        {"per_block_table", per_block_table(d)},
                        {"blocks", std::to_string(ref.blocks)},
                        {"words", std::to_string(ref.words)},
                        {"device", ref.device},
                        {"critical_ns", fixed(ref.crit_ns, 1)},
                        {"critical_from", ref.crit_from},
                        {"critical_to", ref.crit_to},
                        {"fmax", fixed(ref.fmax_mhz, 1)},
                        {"smaller", small == &ref ? std::string()
                                                  : "; " + fixed(small->fmax_mhz, 1) + " MHz with " +
                                                        std::to_string(small->blocks)},
                        {"above_or_below", above ? "above" : "below"},
                        {"factor", fixed(above ? ref.fmax_mhz / 50.0 : 50.0 / ref.fmax_mhz, 2)}});
}

void write_clock_comparison(const FpgaData& d, double clocks_per_broadcast, double cpu_tests_per_s,
                            std::ostream& out) {
  if (!(clocks_per_broadcast > 0) || !(cpu_tests_per_s > 0)) {
    throw std::invalid_argument("write_clock_comparison: clocks per broadcast " + fixed(clocks_per_broadcast, 1) +
                                " and CPU rate " + fixed(cpu_tests_per_s, 1) + " must be positive");
  }
  const FpgaRun& ref = reference_run(d);
  const double f = ref.fmax_mhz * 1e6;
  std::ostringstream rates;
  rates << "| blocks | tests/s at 50 MHz (paper) | x one CPU core | tests/s at " << fixed(ref.fmax_mhz, 1)
        << " MHz (measured, iCE40) | x one CPU core |\n| --- | --- | --- | --- | --- |\n";
  for (double side : {64.0, 256.0, 1024.0}) {
    const double p = side * side;
    const double t50 = p * 50e6 / clocks_per_broadcast, tf = p * f / clocks_per_broadcast;
    rates << "| " << fixed(side, 0) << "^2 | " << sig3(t50) << " | " << fixed(t50 / cpu_tests_per_s, 1) << " | "
          << sig3(tf) << " | " << fixed(tf / cpu_tests_per_s, 1) << " |\n";
  }
  out << fill_template("paper_fpga_clock.md.in",
                       {{"fmax", fixed(ref.fmax_mhz, 1)},
                        {"blocks", std::to_string(ref.blocks)},
                        {"words", std::to_string(ref.words)},
                        {"device", ref.device},
                        {"rates_table", rates.str()},
                        {"speedup", fixed(ref.fmax_mhz / 50.0, 2)},
                        {"slowdown", fixed(50.0 / ref.fmax_mhz, 2)}});
}

}  // namespace fmpp::report
