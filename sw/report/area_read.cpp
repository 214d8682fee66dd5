// `fmpp-report area`, reading the synthesis results (area.h): tools/synth.sh's
// summary.csv and cells.csv, checked field by field and against each other, and the
// transistor cost of each yosys cell type.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sw/report/area.h"

namespace fmpp::report {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

[[noreturn]] void bad(const std::string& file, unsigned line, const std::string& what) {
  throw std::runtime_error(file + ":" + std::to_string(line) + ": " + what);
}

double number(const std::string& file, unsigned line, const std::string& field, const std::string& text) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  // "inf" parses, and would reach the report as inf or -nan: finite numbers only.
  if (used == 0 || used != text.size() || !(v >= 0) || !std::isfinite(v)) {
    bad(file, line, "field '" + field + "' is '" + text + "', not a finite non-negative number");
  }
  return v;
}

unsigned count(const std::string& file, unsigned line, const std::string& field, const std::string& text) {
  const double v = number(file, line, field, text);
  if (v != std::floor(v) || v < 1 || v > 1e9) bad(file, line, "field '" + field + "' is '" + text + "', not a count");
  return static_cast<unsigned>(v);
}

// Reads a CSV with '#' comment lines and a header naming at least `columns`; calls
// row(line number, fields by column name) for each data row.
template <class Row>
std::string read_csv(const std::string& file, const std::vector<std::string>& columns, Row row) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot open (run tools/synth.sh or make synth first)");
  std::string text, comments;
  std::vector<std::string> header;
  unsigned n = 0;
  while (std::getline(in, text)) {
    ++n;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty()) continue;
    if (text[0] == '#') {
      comments += text.substr(text.find_first_not_of("# ") == std::string::npos ? text.size()
                                                                                  : text.find_first_not_of("# "));
      comments += "\n";
      continue;
    }
    const std::vector<std::string> f = split_csv(text);
    if (header.empty()) {
      header = f;
      for (const std::string& c : columns) {
        if (std::find(header.begin(), header.end(), c) == header.end()) bad(file, n, "header has no column '" + c + "'");
      }
      continue;
    }
    if (f.size() != header.size()) {
      bad(file, n, std::to_string(f.size()) + " fields, the header has " + std::to_string(header.size()));
    }
    std::map<std::string, std::string> byname;
    for (size_t i = 0; i < f.size(); ++i) byname[header[i]] = f[i];
    row(n, byname);
  }
  if (header.empty()) throw std::runtime_error(file + ": no header line");
  return comments;
}

}  // namespace

SynthData read_synth(const std::string& dir) {
  SynthData d;
  const std::string summary = dir + "/summary.csv";
  d.provenance = read_csv(summary, {"blocks", "words", "cells", "transistors", "flops"},
                          [&](unsigned n, std::map<std::string, std::string>& f) {
                            SynthSize s;
                            s.blocks = count(summary, n, "blocks", f["blocks"]);
                            s.words = count(summary, n, "words", f["words"]);
                            s.cells = number(summary, n, "cells", f["cells"]);
                            s.transistors = number(summary, n, "transistors", f["transistors"]);
                            s.flops = number(summary, n, "flops", f["flops"]);
                            for (const SynthSize& o : d.sizes) {
                              if (o.blocks == s.blocks && o.words == s.words) {
                                bad(summary, n, "size " + std::to_string(s.blocks) + "x" + std::to_string(s.words) +
                                                    " appears twice");
                              }
                            }
                            d.sizes.push_back(s);
                          });
  if (d.sizes.empty()) throw std::runtime_error(summary + ": no sizes");
  const std::string cells = dir + "/cells.csv";
  read_csv(cells, {"blocks", "words", "cell", "count"}, [&](unsigned n, std::map<std::string, std::string>& f) {
    const unsigned b = count(cells, n, "blocks", f["blocks"]);
    const unsigned w = count(cells, n, "words", f["words"]);
    auto it = std::find_if(d.sizes.begin(), d.sizes.end(),
                           [&](const SynthSize& s) { return s.blocks == b && s.words == w; });
    if (it == d.sizes.end()) {
      bad(cells, n, "size " + std::to_string(b) + "x" + std::to_string(w) + " is not in summary.csv");
    }
    cmos_transistors(f["cell"]);  // an unknown cell type fails here, naming it
    it->cell_counts[f["cell"]] += number(cells, n, "count", f["count"]);
  });
  for (const SynthSize& s : d.sizes) {
    double cells_sum = 0, trans_sum = 0;
    for (const auto& [cell, c] : s.cell_counts) {
      cells_sum += c;
      trans_sum += c * cmos_transistors(cell);
    }
    if (cells_sum != s.cells || trans_sum != s.transistors) {
      throw std::runtime_error(cells + ": size " + std::to_string(s.blocks) + "x" + std::to_string(s.words) +
                               " lists " + grouped(cells_sum) + " cells / " + grouped(trans_sum) +
                               " transistors, summary.csv says " + grouped(s.cells) + " / " +
                               grouped(s.transistors));
    }
  }
  return d;
}

double cmos_transistors(const std::string& cell) {
  // yosys 0.23 kernel/cost.h, CellCosts::cmos_gate_cost(): static CMOS gates.
  static const std::map<std::string, double> kCost = {
      {"$_BUF_", 1},    {"$_NOT_", 2},    {"$_NAND_", 4},  {"$_NOR_", 4},   {"$_AND_", 6},
      {"$_OR_", 6},     {"$_ANDNOT_", 6}, {"$_ORNOT_", 6}, {"$_XOR_", 12},  {"$_XNOR_", 12},
      {"$_AOI3_", 6},   {"$_OAI3_", 6},   {"$_AOI4_", 8},  {"$_OAI4_", 8},  {"$_MUX_", 12},
      {"$_NMUX_", 10},  {"$_DFF_P_", 16}, {"$_DFF_N_", 16}};
  const auto it = kCost.find(cell);
  if (it == kCost.end()) {
    throw std::runtime_error("cell type '" + cell +
                             "' has no transistor cost (tools/synth.sh legalizes flip-flops to $_DFF_P_)");
  }
  return it->second;
}

}  // namespace fmpp::report
