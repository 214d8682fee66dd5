// `fmpp-report area`, the Markdown (area.h): the tables and values of docs/generated/area.md
// (the synthesized sizes, the fitted cost model, the paper's figures), filled into
// sw/report/templates/area.md.in and area_baseline.md.in (md_template.h), which hold every sentence.
#include <cmath>
#include <algorithm>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>

#include "sw/report/area.h"
#include "sw/report/md_template.h"

namespace fmpp::report {

std::string grouped(double v) {
  std::string digits = std::to_string(static_cast<long long>(std::llround(v)));
  const bool neg = digits[0] == '-';
  if (neg) digits.erase(0, 1);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(static_cast<size_t>(i), ",");
  return (neg ? "-" : "") + digits;
}

namespace {

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

std::string fixed(double v, int prec) {
  // Fitted slopes of cells a size does not scale come out as +-1e-12: print them as 0.
  if (std::fabs(v) < 0.5 * std::pow(10.0, -prec)) v = 0;
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

std::string ratio(double v) { return fixed(v, v >= 100 ? 0 : v >= 10 ? 1 : 2) + "x"; }

// A run's provenance (tools/synth.sh's lines), indented as a code block.
std::string provenance(const SynthData& data) {
  std::string out;
  std::istringstream prov(data.provenance);
  for (std::string l; std::getline(prov, l);) out += "    " + l + "\n";
  return out;
}

std::string sizes_table(const SynthData& data, const CostFit& ft) {
  std::ostringstream out;
  out << "| blocks x words | cells | transistors | flip-flops | cost model error (transistors) |\n";
  out << "| ---: | ---: | ---: | ---: | ---: |\n";
  for (const SynthSize& s : data.sizes) {
    const double e = (ft.at(s.blocks, s.words) - s.transistors) / s.transistors * 100;
    out << "| " << s.blocks << " x " << s.words << " | " << grouped(s.cells) << " | " << grouped(s.transistors) << " | "
        << grouped(s.flops) << " | " << (e >= 0 ? "+" : "") << fixed(e, 1) << " % |\n";
  }
  return out.str();
}

std::string cost_table(const AreaModel& a) {
  const CostFit& fc = a.cells;
  const CostFit& ft = a.transistors;
  const CostFit& ff = a.flops;
  std::ostringstream out;
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
  for (unsigned w : {8u, a.words, 32u}) {
    const std::string what = "one block of " + std::to_string(w) + " words";
    row(what.c_str(), fc.per_block + w * fc.per_block_word, ft.per_block + w * ft.per_block_word,
        ff.per_block + w * ff.per_block_word);
  }
  return out.str();
}

std::string cell_table(const AreaModel& a) {
  std::ostringstream out;
  out << "| cell | transistors each | per block (no words) | per word | per stored bit | transistors per bit |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: |\n";
  for (const CellFit& c : a.per_cell) {
    const CostFit& f = c.fit;
    const double each = c.transistors_each;
    out << "| `" << c.type << "` | " << each << " | " << fixed(f.per_block, 0) << " | " << fixed(f.per_block_word, 1)
        << " | " << fixed(f.per_block_word / 32, 2) << " | " << fixed(f.per_block_word / 32 * each, 1) << " |\n";
  }
  return out.str();
}

std::string paper_table(const AreaModel& a) {
  const unsigned words = a.words;
  std::ostringstream out;
  out << "| | paper | this RTL | this RTL / paper |\n| --- | ---: | ---: | ---: |\n";
  out << "| transistors per stored bit | " << kPaperCamTransistorsPerBit << " | " << fixed(a.bit, 1) << " | "
      << ratio(a.bit / kPaperCamTransistorsPerBit) << " |\n";
  out << "| transistors per block without its words | about " << kPaperAluTransistors << " (ALU) | "
      << si(a.transistors.per_block) << " | " << ratio(a.transistors.per_block / kPaperAluTransistors) << " |\n";
  out << "| transistors per processor of " << words << " words | " << si(a.paper_processor) << " (" << words << " x "
      << kPaperBitsPerWord << " bits x 18 + 1000) | " << si(a.processor) << " | "
      << ratio(a.processor / a.paper_processor) << " |\n";
  out << "| the same, as Table 3 implies | " << si(a.implied_lo) << " .. " << si(a.implied_hi) << " | "
      << si(a.processor) << " | " << ratio(a.processor / a.implied_hi) << " .. " << ratio(a.processor / a.implied_lo)
      << " |\n";
  return out.str();
}

std::string table3(const AreaModel& a) {
  std::ostringstream out;
  out << "| pixels | DRAM (paper) | FMPP (paper) | paper / DRAM | FMPP (this RTL) | this RTL / DRAM | this RTL / paper |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const PaperRow& r : paper_table3()) {
    const double n = static_cast<double>(r.side) * r.side;
    const double ours = a.transistors.at(n, a.words);
    out << "| " << r.side << " x " << r.side << " | " << si(r.dram_transistors) << " | " << si(r.fmpp_transistors)
        << " | " << ratio(r.fmpp_transistors / r.dram_transistors) << " | " << si(ours) << " | "
        << ratio(ours / r.dram_transistors) << " | " << ratio(ours / r.fmpp_transistors) << " |\n";
  }
  return out.str();
}

// The values of "What differs, and why".
void what_differs(const AreaModel& a, TemplateValues& v) {
  const CostFit& ft = a.transistors;
  v["dff_per_bit"] = fixed(a.dff_bit, 2);
  v["mux_per_bit"] = fixed(a.mux_bit, 1);
  v["mux_transistors"] = fixed(a.mux_bit * 12, 0);
  v["bit_transistors"] = fixed(a.bit, 0);
  v["block_transistors"] = si(ft.per_block);
  v["fixed_transistors"] = si(ft.fixed);
  v["fixed_blocks"] = fixed(ft.fixed / a.processor, 1);
  v["ratio_to_paper"] = ratio(a.processor / a.implied_lo);
  v["ratio_to_dram"] = ratio(ft.at(1024.0 * 1024.0, a.words) / paper_table3().back().dram_transistors);
}

}  // namespace

void write_area_report(const SynthData& data, unsigned words, std::ostream& out) {
  const AreaModel a = area_model(data, words);
  TemplateValues v = {
      {"provenance", provenance(data)},
      {"sizes_table", sizes_table(data, a.transistors)},
      {"cost_table", cost_table(a)},
      {"cells_error", fixed(a.cells.max_rel_error * 100, 1)},
      {"transistors_error", fixed(a.transistors.max_rel_error * 100, 1)},
      {"cell_table", cell_table(a)},
      {"paper_words", std::to_string(kPaperWordsRayParallel)},
      {"words", std::to_string(a.words)},
      {"odd_words", a.words % 2 != 0 ? " " + fill_inline("area_odd_words.md.in", {}) : std::string()},
      {"paper_table", paper_table(a)},
      {"table3", table3(a)},
      {"implied_lo", si(a.implied_lo)},
      {"implied_hi", si(a.implied_hi)},
      {"implied_bits", fixed(a.implied_bits, 0)},
      {"implied_words", fixed(a.implied_bits / kPaperBitsPerWord, 1)},
      {"paper_bits", std::to_string(kPaperWordsRayParallel * kPaperBitsPerWord)}};
  what_differs(a, v);
  out << fill_template("area.md.in", v);
}

namespace {

std::string signed_grouped(double v) { return std::abs(v) < 0.5 ? std::string("0") : (v > 0 ? "+" : "") + grouped(v); }

// The fit's parts before and now.
std::string parts_table(const AreaModel& was, const AreaModel& now) {
  std::ostringstream out;
  out << "| part | cells before | cells now | difference | transistors before | transistors now | difference |\n";
  out << "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  auto row = [&](const char* what, double c0, double c1, double t0, double t1) {
    out << "| " << what << " | " << grouped(c0) << " | " << grouped(c1) << " | " << signed_grouped(c1 - c0) << " | "
        << grouped(t0) << " | " << grouped(t1) << " | " << signed_grouped(t1 - t0) << " |\n";
  };
  row("block without its words", was.cells.per_block, now.cells.per_block, was.transistors.per_block,
      now.transistors.per_block);
  row("word of a block", was.cells.per_block_word, now.cells.per_block_word, was.transistors.per_block_word,
      now.transistors.per_block_word);
  row("fixed part", was.cells.fixed, now.cells.fixed, was.transistors.fixed, now.transistors.fixed);
  return out.str();
}

const SynthSize* size_of(const SynthData& d, unsigned w, unsigned b) {
  for (const SynthSize& z : d.sizes) {
    if (z.words == w && z.blocks == b) return &z;
  }
  return nullptr;
}

// The fit spreads a change over its four parts; a direct figure per word count: the
// cost between the fewest and the most blocks synthesized with those words, per block.
std::string per_block_table(const SynthData& data, const SynthData& before) {
  std::ostringstream out;
  out << "| words | blocks | cells per block before | now | difference | transistors per block before | now | "
         "difference |\n| ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  std::map<unsigned, std::pair<unsigned, unsigned>> range;  // words -> fewest, most blocks (in both runs)
  for (const SynthSize& z : data.sizes) {
    if (!size_of(before, z.words, z.blocks)) continue;
    auto it = range.find(z.words);
    if (it == range.end()) {
      range[z.words] = {z.blocks, z.blocks};
    } else {
      it->second.first = std::min(it->second.first, z.blocks);
      it->second.second = std::max(it->second.second, z.blocks);
    }
  }
  for (const auto& [w, r] : range) {
    if (r.first == r.second) continue;
    const double db = r.second - r.first;
    const SynthSize *a0 = size_of(before, w, r.first), *a1 = size_of(before, w, r.second);
    const SynthSize *n0 = size_of(data, w, r.first), *n1 = size_of(data, w, r.second);
    const double c0 = (a1->cells - a0->cells) / db, c1 = (n1->cells - n0->cells) / db;
    const double t0 = (a1->transistors - a0->transistors) / db, t1 = (n1->transistors - n0->transistors) / db;
    out << "| " << w << " | " << r.first << " .. " << r.second << " | " << grouped(c0) << " | " << grouped(c1) << " | "
        << signed_grouped(c1 - c0) << " | " << grouped(t0) << " | " << grouped(t1) << " | " << signed_grouped(t1 - t0)
        << " |\n";
  }
  return out.str();
}

}  // namespace

void write_baseline_section(const SynthData& data, const SynthData& before, const std::string& label, unsigned words,
                            std::ostream& out) {
  const AreaModel now = area_model(data, words), was = area_model(before, words);
  const double b0 = was.transistors.per_block + words * was.transistors.per_block_word;
  const double b1 = now.transistors.per_block + words * now.transistors.per_block_word;
  out << fill_template("area_baseline.md.in",
                       {{"label", label},
                        {"provenance", provenance(before)},
                        {"parts_table", parts_table(was, now)},
                        {"per_block_table", per_block_table(data, before)},
                        {"words", std::to_string(words)},
                        {"before", grouped(b0)},
                        {"after", grouped(b1)},
                        {"change", (b1 >= b0 ? "+" : "") + fixed((b1 - b0) / b0 * 100, 2)}});
}

}  // namespace fmpp::report
