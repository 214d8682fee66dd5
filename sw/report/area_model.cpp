// `fmpp-report area`, the cost model (area.h): a least-squares fit of cells,
// transistors and flip-flops per block and per stored word over the synthesized sizes,
// per cell type too, and the paper's Table 3 with the per-processor figures it implies.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

#include "sw/report/area.h"

namespace fmpp::report {

namespace {

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

}  // namespace

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

CostFit fit_cell(const std::vector<SynthSize>& sizes, const std::string& type) {
  std::vector<double> v;
  for (const SynthSize& s : sizes) {
    const auto it = s.cell_counts.find(type);
    v.push_back(it == s.cell_counts.end() ? 0 : it->second);
  }
  return fit_cost(sizes, v);
}

AreaModel area_model(const SynthData& data, unsigned words) {
  const std::vector<SynthSize>& sz = data.sizes;
  AreaModel a;
  a.words = words;
  std::vector<double> cells, trans, flops;
  for (const SynthSize& s : sz) {
    cells.push_back(s.cells);
    trans.push_back(s.transistors);
    flops.push_back(s.flops);
  }
  a.cells = fit_cost(sz, cells);
  a.transistors = fit_cost(sz, trans);
  a.flops = fit_cost(sz, flops);
  const CostFit& ft = a.transistors;
  std::set<std::string> types;
  for (const SynthSize& s : sz) {
    for (const auto& [cell, c] : s.cell_counts) types.insert(cell);
  }
  for (const std::string& t : types) a.per_cell.push_back(CellFit{t, cmos_transistors(t), fit_cell(sz, t)});

  // The paper's model of a processor: CAM bits at 18 transistors plus a 1000-transistor ALU.
  a.paper_processor = words * kPaperBitsPerWord * kPaperCamTransistorsPerBit + kPaperAluTransistors;
  a.processor = ft.per_block + words * ft.per_block_word;
  a.bit = ft.per_block_word / 32;
  a.implied_lo = 1e30;
  a.implied_hi = 0;
  for (const PaperRow& r : paper_table3()) {
    const double p = r.fmpp_transistors / (static_cast<double>(r.side) * r.side);
    a.implied_lo = std::min(a.implied_lo, p);
    a.implied_hi = std::max(a.implied_hi, p);
  }
  a.implied_bits = (a.implied_lo - kPaperAluTransistors) / kPaperCamTransistorsPerBit;

  // Cell-type figures quoted in the explanation.
  a.dff_bit = fit_cell(sz, "$_DFF_P_").per_block_word / 32;
  a.mux_bit = fit_cell(sz, "$_MUX_").per_block_word / 32;
  return a;
}

}  // namespace fmpp::report
