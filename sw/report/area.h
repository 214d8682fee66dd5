// The pieces of `fmpp-report area`, exposed for tests: reading the synthesis results of
// tools/synth.sh (area_read.cpp), fitting a cost per block and per stored word and
// setting it beside the paper's Table 3 figures (area_model.cpp), and the Markdown
// (area_markdown.cpp); area.cpp is the subcommand.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace fmpp::report {

// One synthesized size (a row of summary.csv).
struct SynthSize {
  unsigned blocks = 0;
  unsigned words = 0;
  double cells = 0;
  double transistors = 0;
  double flops = 0;
  std::map<std::string, double> cell_counts;  // by yosys cell type ($_MUX_, ...), from cells.csv
};

struct SynthData {
  std::string provenance;  // the CSV's comment lines (yosys version, date, flow)
  std::vector<SynthSize> sizes;
};

// Reads DIR/summary.csv and DIR/cells.csv. Throws std::runtime_error naming the file,
// the line and the field for anything malformed or missing.
SynthData read_synth(const std::string& dir);

// Cost model, fitted by least squares over the sizes:
//   cost(B, W) = fixed + per_word_fixed * W + B * (per_block + per_block_word * W)
// B blocks of W words. per_block is a block without its words (ALU, flags, match
// logic, predicate, write decode); per_block_word is one word of one block (32 bits
// and their share of the read and write multiplexers); fixed is the bus slave, the
// queue and the roots of the responder trees.
struct CostFit {
  double fixed = 0;
  double per_word_fixed = 0;
  double per_block = 0;
  double per_block_word = 0;
  double max_rel_error = 0;  // largest |fit - measured| / measured over the sizes

  double at(double blocks, double words) const {
    return fixed + per_word_fixed * words + blocks * (per_block + per_block_word * words);
  }
};

// Fits `values` (one per size). Throws std::runtime_error if the sizes do not
// determine the model (fewer than two block counts or two word counts, or fewer
// than four sizes), naming the sizes given.
CostFit fit_cost(const std::vector<SynthSize>& sizes, const std::vector<double>& values);

// The fit of one yosys cell type's counts (0 where a size has none).
CostFit fit_cell(const std::vector<SynthSize>& sizes, const std::string& type);

// yosys 0.23 `stat -tech cmos` transistor count of a generic cell; throws
// std::runtime_error for a cell type it has no cost for.
double cmos_transistors(const std::string& cell);

// The paper's Table 3 and the figures quoted with it.
struct PaperRow {
  unsigned side;              // pixels (= processors) = side x side
  double dram_transistors;    // transistors of the DRAM holding the rays
  double fmpp_transistors;    // transistors of the FMPP (CAM on SRAM cells)
};
const std::vector<PaperRow>& paper_table3();
inline constexpr double kPaperCamTransistorsPerBit = 18;
inline constexpr double kPaperAluTransistors = 1000;
inline constexpr unsigned kPaperWordsRayParallel = 23;
inline constexpr unsigned kPaperBitsPerWord = 40;  // 32 data + 8 status flags

// The cost model fitted to the sizes and what it gives beside the paper, for a
// processor of `words` words.
struct CellFit {
  std::string type;               // yosys cell type
  double transistors_each = 0;    // cmos_transistors(type)
  CostFit fit;                    // its count per block and per word
};
struct AreaModel {
  unsigned words = 0;
  CostFit cells, transistors, flops;
  std::vector<CellFit> per_cell;  // every cell type of the sizes, by name
  double paper_processor = 0;     // the paper's processor of `words` 40-bit words: CAM bits + ALU
  double processor = 0;           // this RTL's block of `words` words, transistors
  double bit = 0;                 // transistors per stored bit
  double implied_lo = 0, implied_hi = 0;  // transistors per processor that Table 3 implies
  double implied_bits = 0;        // CAM bits that implied_lo means at 18 per bit + 1000
  double dff_bit = 0, mux_bit = 0;  // $_DFF_P_ and $_MUX_ cells per stored bit
};
AreaModel area_model(const SynthData& data, unsigned words);

// v rounded, digits grouped by thousands ("1,234,567").
std::string grouped(double v);

// The whole report, as Markdown, for `words` words per processor in the Table 3
// comparison.
void write_area_report(const SynthData& data, unsigned words, std::ostream& out);

// A section setting the cost model of `data` beside that of an earlier synthesis
// `before` (the same flow on an earlier RTL, named by `label`): what a change of the RTL
// cost per block, per word and in the fixed part, and the two runs' provenance.
void write_baseline_section(const SynthData& data, const SynthData& before, const std::string& label, unsigned words,
                            std::ostream& out);

}  // namespace fmpp::report
