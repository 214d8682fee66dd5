// `fmpp-report area`: the FMPP's synthesized cost (tools/synth.sh: yosys generic
// gates, `stat -tech cmos`) per block and per stored bit, beside the paper's Table 3
// (FMPP vs DRAM transistors for 128^2, 512^2 and 1024^2 pixels) and its figures of
// 18 transistors per CAM bit and about 1000 per block ALU.
#include "sw/report/area.h"
#include "sw/report/fpga.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "sw/report/report.h"
#include "sw/util/files.h"

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

// Solves the 4x4 normal equations of the cost model (Gaussian elimination, partial pivoting).
std::array<double, 4> solve4(std::array<std::array<double, 5>, 4> m) {
  double scale = 0;
  for (int r = 0; r < 4; ++r) scale = std::max(scale, std::fabs(m[r][r]));
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r) {
      if (std::fabs(m[r][c]) > std::fabs(m[p][c])) p = r;
    }
    if (std::fabs(m[p][c]) <= 1e-10 * scale) throw std::runtime_error("singular");
    std::swap(m[c], m[p]);
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      const double k = m[r][c] / m[c][c];
      for (int j = c; j < 5; ++j) m[r][j] -= k * m[c][j];
    }
  }
  return {m[0][4] / m[0][0], m[1][4] / m[1][1], m[2][4] / m[2][2], m[3][4] / m[3][3]};
}

// 3 significant digits with k, M, G.
std::string si(double v) {
  const char* suffix = "";
  double a = std::fabs(v);
  if (a >= 1e9) {
    v /= 1e9;
    suffix = "G";
  } else if (a >= 1e6) {
    v /= 1e6;
    suffix = "M";
  } else if (a >= 1e4) {
    v /= 1e3;
    suffix = "k";
  }
  a = std::fabs(v);
  std::ostringstream s;
  s << std::fixed << std::setprecision(a >= 100 ? 0 : a >= 10 ? 1 : 2) << v << suffix;
  return s.str();
}

std::string grouped(double v) {
  std::string digits = std::to_string(static_cast<long long>(std::llround(v)));
  const bool neg = digits[0] == '-';
  if (neg) digits.erase(0, 1);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(static_cast<size_t>(i), ",");
  return (neg ? "-" : "") + digits;
}

std::string fixed(double v, int prec) {
  // Fitted slopes of cells a size does not scale come out as +-1e-12: print them as 0.
  if (std::fabs(v) < 0.5 * std::pow(10.0, -prec)) v = 0;
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

std::string ratio(double v) { return fixed(v, v >= 100 ? 0 : v >= 10 ? 1 : 2) + "x"; }

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

CostFit fit_cost(const std::vector<SynthSize>& sizes, const std::vector<double>& values) {
  if (values.size() != sizes.size()) throw std::logic_error("fmpp::report::fit_cost: one value per size");
  std::set<unsigned> blocks, words;
  std::string given;
  for (const SynthSize& s : sizes) {
    blocks.insert(s.blocks);
    words.insert(s.words);
    given += (given.empty() ? "" : " ") + std::to_string(s.blocks) + "x" + std::to_string(s.words);
  }
  const std::string need =
      "the sizes do not determine the cost model's four terms: it needs two block counts and two word counts, with "
      "the word count varied at two block counts (e.g. tools/synth.sh 1x8 4x8 8x8 8x16 16x32); sizes given: " +
      given;
  if (sizes.size() < 4 || blocks.size() < 2 || words.size() < 2) throw std::runtime_error(need);
  std::array<std::array<double, 5>, 4> m{};
  for (size_t i = 0; i < sizes.size(); ++i) {
    const double b = sizes[i].blocks, w = sizes[i].words;
    const double x[4] = {1, w, b, b * w};
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) m[r][c] += x[r] * x[c];
      m[r][4] += x[r] * values[i];
    }
  }
  std::array<double, 4> k;
  try {
    k = solve4(m);
  } catch (const std::runtime_error&) {
    throw std::runtime_error(need);
  }
  CostFit f{k[0], k[1], k[2], k[3], 0};
  for (size_t i = 0; i < sizes.size(); ++i) {
    if (values[i] > 0) {
      f.max_rel_error = std::max(f.max_rel_error, std::fabs(f.at(sizes[i].blocks, sizes[i].words) - values[i]) / values[i]);
    }
  }
  return f;
}

const std::vector<PaperRow>& paper_table3() {
  // Table 3 of the paper. (Its DRAM byte row reads 192M for 128x128, a misprint for
  // 192K: 16384 rays x 12 bytes; the transistor row is 1 transistor per DRAM bit.)
  static const std::vector<PaperRow> kRows = {{128, 1.57e6, 375e6}, {512, 25.2e6, 5.86e9}, {1024, 101e6, 23.5e9}};
  return kRows;
}

void write_area_report(const SynthData& data, unsigned words, std::ostream& out) {
  const std::vector<SynthSize>& sz = data.sizes;
  std::vector<double> cells, trans, flops;
  for (const SynthSize& s : sz) {
    cells.push_back(s.cells);
    trans.push_back(s.transistors);
    flops.push_back(s.flops);
  }
  const CostFit fc = fit_cost(sz, cells), ft = fit_cost(sz, trans), ff = fit_cost(sz, flops);
  std::set<std::string> types;
  for (const SynthSize& s : sz) {
    for (const auto& [cell, c] : s.cell_counts) types.insert(cell);
  }

  out << "# FMPP area: synthesis beside the paper's Table 3\n\n";
  out << "Generated by `fmpp-report area` from tools/synth.sh output:\n\n";
  std::istringstream prov(data.provenance);
  for (std::string l; std::getline(prov, l);) out << "    " << l << "\n";
  out << "\n## Measured sizes\n\n";
  out << "| blocks x words | cells | transistors | flip-flops | cost model error (transistors) |\n";
  out << "| ---: | ---: | ---: | ---: | ---: |\n";
  for (const SynthSize& s : sz) {
    const double e = (ft.at(s.blocks, s.words) - s.transistors) / s.transistors * 100;
    out << "| " << s.blocks << " x " << s.words << " | " << grouped(s.cells) << " | " << grouped(s.transistors) << " | "
        << grouped(s.flops) << " | " << (e >= 0 ? "+" : "") << fixed(e, 1) << " % |\n";
  }

  out << "\n## Cost model\n\n";
  out << "Least squares over the sizes above, for B blocks of W words:\n"
         "cost(B, W) = fixed + W x fixed-per-word + B x (block + W x word).\n\n";
  out << "| part | cells | transistors | flip-flops |\n| --- | ---: | ---: | ---: |\n";
  auto row = [&](const char* what, double c, double t, double f) {
    out << "| " << what << " | " << grouped(c) << " | " << grouped(t) << " | " << grouped(f) << " |\n";
  };
  row("fixed: AXI slave, 16-entry queue, responder tree roots", fc.fixed, ft.fixed, ff.fixed);
  row("fixed, per word of the configuration", fc.per_word_fixed, ft.per_word_fixed, ff.per_word_fixed);
  row("**block** without its words: ALU, 8 flags, match, predicate, write select", fc.per_block, ft.per_block,
      ff.per_block);
  row("**word** of a block: 32 bits, their write enables and read multiplexers", fc.per_block_word,
      ft.per_block_word, ff.per_block_word);
  out << "| **stored bit** (word / 32) | " << fixed(fc.per_block_word / 32, 1) << " | "
      << fixed(ft.per_block_word / 32, 1) << " | " << fixed(ff.per_block_word / 32, 2) << " |\n";
  for (unsigned w : {8u, words, 32u}) {
    const std::string what = "one block of " + std::to_string(w) + " words";
    row(what.c_str(), fc.per_block + w * fc.per_block_word, ft.per_block + w * ft.per_block_word,
        ff.per_block + w * ff.per_block_word);
  }
  out << "\nLargest model error over the sizes: " << fixed(fc.max_rel_error * 100, 1) << " % (cells), "
      << fixed(ft.max_rel_error * 100, 1) << " % (transistors).\n";

  out << "\n### What a block and a stored word are made of\n\n";
  out << "The block and word slopes of the model, fitted per yosys cell type "
         "(transistors per cell from `stat -tech cmos`):\n\n";
  out << "| cell | transistors each | per block (no words) | per word | per stored bit | transistors per bit |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: |\n";
  for (const std::string& t : types) {
    std::vector<double> v;
    for (const SynthSize& s : sz) {
      const auto it = s.cell_counts.find(t);
      v.push_back(it == s.cell_counts.end() ? 0 : it->second);
    }
    const CostFit f = fit_cost(sz, v);
    const double each = cmos_transistors(t);
    out << "| `" << t << "` | " << each << " | " << fixed(f.per_block, 0) << " | " << fixed(f.per_block_word, 1)
        << " | " << fixed(f.per_block_word / 32, 2) << " | " << fixed(f.per_block_word / 32 * each, 1) << " |\n";
  }

  // The paper's model of a processor: CAM bits at 18 transistors plus a 1000-transistor ALU.
  const double paper_words_model = words * kPaperBitsPerWord * kPaperCamTransistorsPerBit + kPaperAluTransistors;
  const double ours_block = ft.per_block + words * ft.per_block_word;
  const double bit = ft.per_block_word / 32;
  const auto& t3 = paper_table3();
  double implied_lo = 1e30, implied_hi = 0;
  for (const PaperRow& r : t3) {
    const double p = r.fmpp_transistors / (static_cast<double>(r.side) * r.side);
    implied_lo = std::min(implied_lo, p);
    implied_hi = std::max(implied_hi, p);
  }
  const double implied_bits = (implied_lo - kPaperAluTransistors) / kPaperCamTransistorsPerBit;

  out << "\n## Beside the paper\n\n";
  out << "The paper (section 5.1 and Table 3) counts 18 transistors per CAM bit (SRAM cell with match logic) and "
         "about 1000 per block ALU, one processor per pixel, "
      << kPaperWordsRayParallel << " words per processor in the ray-parallel mapping. Below, this RTL's processor has "
      << words << " words";
  if (words % 2 != 0) out << " (the RTL needs an even NumWords: the cost model interpolates)";
  out << " and its 8 flags; the paper's words are 40 bits, 32 data and 8 status flags.\n\n";
  out << "| | paper | this RTL | this RTL / paper |\n| --- | ---: | ---: | ---: |\n";
  out << "| transistors per stored bit | " << kPaperCamTransistorsPerBit << " | " << fixed(bit, 1) << " | "
      << ratio(bit / kPaperCamTransistorsPerBit) << " |\n";
  out << "| transistors per block without its words | about " << kPaperAluTransistors << " (ALU) | "
      << si(ft.per_block) << " | " << ratio(ft.per_block / kPaperAluTransistors) << " |\n";
  out << "| transistors per processor of " << words << " words | " << si(paper_words_model) << " ("
      << words << " x " << kPaperBitsPerWord << " bits x 18 + 1000) | " << si(ours_block) << " | "
      << ratio(ours_block / paper_words_model) << " |\n";
  out << "| the same, as Table 3 implies | " << si(implied_lo) << " .. " << si(implied_hi) << " | " << si(ours_block)
      << " | " << ratio(ours_block / implied_hi) << " .. " << ratio(ours_block / implied_lo) << " |\n";

  out << "\n### Table 3, one processor of " << words << " words per pixel\n\n";
  out << "| pixels | DRAM (paper) | FMPP (paper) | paper / DRAM | FMPP (this RTL) | this RTL / DRAM | this RTL / paper |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const PaperRow& r : t3) {
    const double n = static_cast<double>(r.side) * r.side;
    const double ours = ft.at(n, words);
    out << "| " << r.side << " x " << r.side << " | " << si(r.dram_transistors) << " | " << si(r.fmpp_transistors)
        << " | " << ratio(r.fmpp_transistors / r.dram_transistors) << " | " << si(ours) << " | "
        << ratio(ours / r.dram_transistors) << " | " << ratio(ours / r.fmpp_transistors) << " |\n";
  }
  out << "\nThe paper's FMPP column divided by the pixels gives " << si(implied_lo) << " to " << si(implied_hi)
      << " transistors per processor: at 18 per bit and 1000 for the ALU that is about " << fixed(implied_bits, 0)
      << " CAM bits, " << fixed(implied_bits / kPaperBitsPerWord, 1) << " words of 40 bits, rather than the "
      << kPaperWordsRayParallel << " x 40 = " << kPaperWordsRayParallel * kPaperBitsPerWord
      << " the text suggests; the paper does not give its breakdown. Its 'FMPP bytes' row "
         "(160K, 2.5M, 10M: 10 bytes per pixel) does not follow from either.\n";

  // Cell-type figures quoted in the explanation.
  auto slope = [&](const char* type, bool per_word) {
    std::vector<double> v;
    for (const SynthSize& s : sz) {
      const auto it = s.cell_counts.find(type);
      v.push_back(it == s.cell_counts.end() ? 0 : it->second);
    }
    const CostFit f = fit_cost(sz, v);
    return per_word ? f.per_block_word : f.per_block;
  };
  const double dff_bit = slope("$_DFF_P_", true) / 32, mux_bit = slope("$_MUX_", true) / 32;
  out << "\n## What differs, and why\n\n";
  out << "- **A stored bit is a flip-flop, not a CAM cell.** Each bit is an edge-triggered flip-flop ("
      << fixed(dff_bit, 2) << " `$_DFF_P_` per bit, 16 transistors in yosys's table) whose write enable is a "
         "multiplexer in front of it. The paper's bit is an SRAM-based CAM cell of 18 transistors: 6 for storage, "
         "the rest for the bit's match logic.\n";
  out << "- **Four read ports.** In one clock the ALU reads words A and B and the destination D (kept where the "
         "predicate is 0 and in partial writes), and the host reads any word through the WORDS window: each bit "
         "feeds four W-to-1 multiplexer trees, and its write enable is one more multiplexer. That is "
      << fixed(mux_bit, 1) << " `$_MUX_` per stored bit (12 transistors each), " << fixed(mux_bit * 12, 0) << " of its "
      << fixed(bit, 0) << " transistors. A CAM array reads through shared bit lines and sense amplifiers, which a "
         "gate-level netlist has no cell for.\n";
  out << "- **Match logic per block, not per bit.** REF compares one named word (A) of each block with the key, "
         "through the A read port: 32 comparators per block, counted in the block part. A CAM cell compares every "
         "word at once, which is why the paper's per-bit cost includes a comparator.\n";
  out << "- **A wider ALU.** The block part (" << si(ft.per_block)
      << " transistors) holds more than the paper's adder, logic unit and shifter: SUB, the arithmetic right shift, "
         "BITCOPY's bit selection, the C and V flags, the predicate flag multiplexer, FLAGOP's lookup table, the "
         "8 flags and the per-block share of the window-write decode and of the responder trees (COUNT, FIRST). "
         "docs/isa.md lists what each extension buys.\n";
  out << "- **Generic static CMOS gates.** yosys counts every gate as a static CMOS cell (a 2:1 multiplexer is 12 "
         "transistors, an XOR 12); a full-custom array would use pass-transistor multiplexers and dynamic match "
         "lines. The figures are a consistent estimate for comparing sizes, not a layout.\n";
  out << "- **The fixed part vanishes at scale.** The AXI slave and the 16-entry instruction queue ("
      << si(ft.fixed) << " transistors, about " << fixed(ft.fixed / ours_block, 1) << " blocks of " << words
      << " words) do not matter beside 16,384 or more processors.\n";
  out << "- **The conclusion stands.** Per pixel this RTL needs about " << ratio(ours_block / implied_lo)
      << " the paper's Table 3 estimate, so the FMPP of one processor per pixel is about "
      << ratio(ft.at(1024.0 * 1024.0, words) / t3.back().dram_transistors)
      << " the DRAM holding the same rays, where the paper finds 250x: the paper's verdict (unrealistic for whole "
         "images; a limited FMPP of 64 x 64 to 256 x 256 processors is the practical machine) holds with more "
         "margin.\n";

  out << "\n## How this was measured\n\n";
  out << "`make synth` runs tools/synth.sh (yosys on every size above, flip-flops legalized so that `stat -tech cmos` "
         "counts them, writing summary.csv and cells.csv) and then this report. docs/area.md is this report over the "
         "results committed in docs/synth/: after `make synth`, `cp build/synth/*.csv docs/synth/` and "
         "`build/fmpp-report area --synth-dir docs/synth --fpga-csv docs/fpga/summary.csv --out docs/area.md` (the ctest report_area_doc checks that "
         "it is current).\n";
}

// ------------------------------------------------------------------------- CLI

namespace {
struct AreaOptions {
  std::string synth_dir = "build/synth";
  unsigned words = kPaperWordsRayParallel;
  std::string out;
  std::string fpga_csv;  // tools/fpga.sh summary.csv: adds the FPGA section (fpga.cpp)
};
}  // namespace

void register_area(CLI::App& app) {
  auto opt = std::make_shared<AreaOptions>();
  CLI::App* sub = app.add_subcommand(
      "area", "synthesis cost per block and per stored bit beside the paper's Table 3 (reads tools/synth.sh output)");
  sub->add_option("--synth-dir", opt->synth_dir, "directory with summary.csv and cells.csv from tools/synth.sh")
      ->capture_default_str();
  sub->add_option("--words", opt->words, "words per processor for the Table 3 comparison (paper, ray-parallel: 23)")
      ->capture_default_str()
      ->check(CLI::Range(1u, 64u));
  sub->add_option("--out", opt->out, "write the Markdown report to this file instead of stdout ('-': stdout)");
  sub->add_option("--fpga-csv", opt->fpga_csv, "summary.csv of tools/fpga.sh: adds the measured FPGA clock and size");
  sub->callback([opt] {
    if (!opt->out.empty()) check_writable("--out", opt->out);
    const SynthData data = read_synth(opt->synth_dir);
    FpgaData fpga;
    if (!opt->fpga_csv.empty()) fpga = read_fpga(opt->fpga_csv);
    auto write = [&](std::ostream& os) {
      write_area_report(data, opt->words, os);
      if (!fpga.runs.empty()) write_fpga_section(fpga, os);
    };
    if (opt->out.empty() || opt->out == "-") {
      write(std::cout);
      return;
    }
    std::ofstream f(opt->out);
    if (!f) throw std::runtime_error(opt->out + ": cannot write");
    write(f);
  });
}

}  // namespace fmpp::report
