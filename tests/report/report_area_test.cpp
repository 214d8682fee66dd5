// fmpp-report area (sw/report/area.cpp): reading tools/synth.sh output, the cost
// model fit, the comparison with the paper's Table 3, and loud failures on bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sw/report/area.h"

namespace fmpp::report {
namespace {

namespace fs = std::filesystem;

// A synthesis directory written from known per-cell-type cost models.
struct SynthDir {
  explicit SynthDir(const std::string& name) : dir(fs::temp_directory_path() / ("fmpp_area_test_" + name)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~SynthDir() { fs::remove_all(dir); }

  // Counts of each cell type: fixed + fw*W + B*(blk + word*W).
  struct Model {
    const char* cell;
    double fixed, fw, blk, word;
  };
  void write(const std::vector<std::pair<unsigned, unsigned>>& sizes, const std::vector<Model>& models) {
    std::ofstream s(dir / "summary.csv"), c(dir / "cells.csv");
    s.precision(12);
    c.precision(12);
    s << "# test synthesis\nblocks,words,cells,transistors,flops\n";
    c << "# test synthesis\nblocks,words,cell,count\n";
    for (auto [b, w] : sizes) {
      double cells = 0, trans = 0, flops = 0;
      for (const Model& m : models) {
        const double n = m.fixed + m.fw * w + b * (m.blk + m.word * w);
        c << b << "," << w << "," << m.cell << "," << n << "\n";
        cells += n;
        trans += n * cmos_transistors(m.cell);
        if (std::string(m.cell) == "$_DFF_P_") flops += n;
      }
      s << b << "," << w << "," << cells << "," << trans << "," << flops << "\n";
    }
  }
  void put(const char* file, const std::string& text) { std::ofstream(dir / file) << text; }
  std::string path() const { return dir.string(); }

  fs::path dir;
};

const std::vector<std::pair<unsigned, unsigned>> kSizes = {{1, 8},  {2, 8},  {4, 8},  {8, 8},
                                                           {8, 16}, {8, 32}, {16, 32}};
const std::vector<SynthDir::Model> kModels = {
    {"$_DFF_P_", 1500, 0, 8, 32}, {"$_MUX_", 3000, 20, 300, 128}, {"$_XOR_", 200, 0, 70, 0}, {"$_NOT_", 500, 1, 9, 0.5}};

TEST(ReportArea, FitRecoversThePerBlockAndPerWordCosts) {
  SynthDir d("fit");
  d.write(kSizes, kModels);
  const SynthData data = read_synth(d.path());
  ASSERT_EQ(data.sizes.size(), kSizes.size());
  EXPECT_EQ(data.provenance, "test synthesis\n");
  std::vector<double> t, f;
  for (const SynthSize& s : data.sizes) {
    t.push_back(s.transistors);
    f.push_back(s.flops);
  }
  const CostFit ft = fit_cost(data.sizes, t);
  // word: 32 DFF x 16 + 128 MUX x 12 + 0.5 NOT x 2; block: 8 x 16 + 300 x 12 + 70 x 12 + 9 x 2.
  EXPECT_NEAR(ft.per_block_word, 32 * 16 + 128 * 12 + 0.5 * 2, 1e-6);
  EXPECT_NEAR(ft.per_block, 8 * 16 + 300 * 12 + 70 * 12 + 9 * 2, 1e-6);
  EXPECT_NEAR(ft.fixed, 1500 * 16 + 3000 * 12 + 200 * 12 + 500 * 2, 1e-4);
  EXPECT_NEAR(ft.per_word_fixed, 20 * 12 + 1 * 2, 1e-6);
  EXPECT_LT(ft.max_rel_error, 1e-9);
  EXPECT_NEAR(fit_cost(data.sizes, f).per_block_word, 32, 1e-9);
}

TEST(ReportArea, ReportSetsTheFitBesideTable3) {
  SynthDir d("report");
  d.write(kSizes, kModels);
  std::ostringstream out;
  write_area_report(read_synth(d.path()), 23, out);
  const std::string r = out.str();
  for (const char* want : {"| 128 x 128 | 1.57M | 375M | 239x |", "| 512 x 512 | 25.2M | 5.86G |",
                           "| 1024 x 1024 | 101M | 23.5G | 233x |", "transistors per stored bit | 18 |",
                           "one block of 23 words", "`$_MUX_` | 12 |", "## What differs, and why"}) {
    EXPECT_NE(r.find(want), std::string::npos) << want << "\n" << r;
  }
  // 1024^2 processors of 23 words at this test's costs, over the paper's DRAM figure.
  const double block = 8 * 16 + 300 * 12 + 70 * 12 + 9 * 2 + 23 * (32 * 16 + 128 * 12 + 0.5 * 2);
  const double fixed = 1500 * 16 + 3000 * 12 + 200 * 12 + 500 * 2 + 23 * (20 * 12 + 2);
  char want[64];
  std::snprintf(want, sizeof want, "| %.0fx | ", (fixed + 1048576.0 * block) / 101e6);
  EXPECT_NE(r.find(want), std::string::npos) << want << "\n" << r;
}

// The comparison with an earlier synthesis: the same models with 32 more $_MUX_ and 4
// more $_XOR_ per block cost 32 x 12 + 4 x 12 = 432 transistors and 36 cells more per block.
TEST(ReportArea, BaselineSectionShowsThePerBlockDifference) {
  SynthDir before("before"), now("now");
  before.write(kSizes, kModels);
  std::vector<SynthDir::Model> more = kModels;
  more[1].blk += 32;
  more[2].blk += 4;
  now.write(kSizes, more);
  std::ostringstream out;
  write_baseline_section(read_synth(now.path()), read_synth(before.path()), "the old RTL", 23, out);
  const std::string r = out.str();
  const double blk0 = 8 * 16 + 300 * 12 + 70 * 12 + 9 * 2;
  const std::string want_t = "| " + grouped(blk0) + " | " + grouped(blk0 + 432) + " | +432 |";
  for (const std::string& want : {std::string("## Against an earlier synthesis: the old RTL"),
                                  std::string("| block without its words | 387 | 423 | +36 |"), want_t,
                                  std::string("| 0 | 2,049 | 2,049 | 0 |"),
                                  std::string("| 8 | 1 .. 8 | 1,671 | 1,707 | +36 |"),
                                  std::string("| 32 | 8 .. 16 | 5,523 | 5,559 | +36 |"), std::string("    test synthesis")}) {
    EXPECT_NE(r.find(want), std::string::npos) << want << "\n" << r;
  }
}

TEST(ReportArea, BadInputFailsNamingTheFileLineAndField) {
  SynthDir d("bad");
  auto expect_error = [&](const std::string& summary, const std::string& cells, const std::string& want) {
    d.put("summary.csv", summary);
    d.put("cells.csv", cells);
    try {
      read_synth(d.path());
      ADD_FAILURE() << "no error, wanted: " << want;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << e.what();
    }
  };
  const std::string cells_ok = "blocks,words,cell,count\n1,8,$_NOT_,10\n";
  expect_error("# c\nblocks,words,cells,transistors,flops\n1,8,1x0,20,0\n", cells_ok,
               "summary.csv:3: field 'cells' is '1x0', not a finite non-negative number");
  // "inf" is a number to stod, and gave -nan in docs/generated/area.md.
  expect_error("blocks,words,cells,transistors,flops\n1,8,inf,20,0\n", cells_ok,
               "summary.csv:2: field 'cells' is 'inf', not a finite non-negative number");
  expect_error("blocks,words,cells,transistors\n", cells_ok, "summary.csv:1: header has no column 'flops'");
  expect_error("blocks,words,cells,transistors,flops\n1,8,10,20\n", cells_ok,
               "summary.csv:2: 4 fields, the header has 5");
  expect_error("blocks,words,cells,transistors,flops\n0,8,10,20,0\n", cells_ok, "field 'blocks' is '0', not a count");
  expect_error("blocks,words,cells,transistors,flops\n1,8,10,20,0\n1,8,10,20,0\n", cells_ok,
               "summary.csv:3: size 1x8 appears twice");
  expect_error("blocks,words,cells,transistors,flops\n1,8,10,20,0\n", "blocks,words,cell,count\n1,8,$_DFFE_PP_,10\n",
               "cell type '$_DFFE_PP_' has no transistor cost");
  expect_error("blocks,words,cells,transistors,flops\n1,8,10,20,0\n", "blocks,words,cell,count\n2,8,$_NOT_,10\n",
               "cells.csv:2: size 2x8 is not in summary.csv");
  expect_error("blocks,words,cells,transistors,flops\n1,8,10,21,0\n", cells_ok,
               "lists 10 cells / 20 transistors, summary.csv says 10 / 21");
  fs::remove(d.dir / "summary.csv");
  try {
    read_synth(d.path());
    ADD_FAILURE() << "no error for a missing summary.csv";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("summary.csv: cannot open"), std::string::npos) << e.what();
  }
}

TEST(ReportArea, SizesMustDetermineTheModel) {
  SynthDir d("sizes");
  d.write({{1, 8}, {2, 8}, {4, 8}, {8, 8}, {8, 16}}, kModels);  // words varied at one block count only
  const SynthData data = read_synth(d.path());
  std::vector<double> t;
  for (const SynthSize& s : data.sizes) t.push_back(s.transistors);
  try {
    fit_cost(data.sizes, t);
    FAIL() << "fitted a model the sizes do not determine";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("word count varied at two block counts"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sizes given: 1x8 2x8 4x8 8x8 8x16"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fmpp::report
