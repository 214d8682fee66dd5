// The pieces of `fmpp-report area` (area.cpp), exposed for tests: reading the
// synthesis results of tools/synth.sh, fitting a cost per block and per stored word,
// and the paper's Table 3 figures they are compared with.
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

// The whole report, as Markdown, for `words` words per processor in the Table 3
// comparison.
void write_area_report(const SynthData& data, unsigned words, std::ostream& out);

}  // namespace fmpp::report
