// FPGA figures for the reports (sw/report/fpga.cpp): reading tools/fpga.sh's summary.csv,
// choosing the clock to quote, the per-block slopes, and loud failures on bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "sw/report/fpga.h"

namespace fmpp::report {
namespace {

namespace fs = std::filesystem;

const char* kHeader = "device,package,blocks,words,lcs,lcs_avail,luts,dffs,brams,ios,fmax_mhz,placed,crit_ns,crit_from,crit_to\n";

std::string write_csv(const std::string& name, const std::string& body) {
  const fs::path p = fs::temp_directory_path() / ("fmpp_fpga_test_" + name + ".csv");
  std::ofstream(p) << "# tools line\n" << kHeader << body;
  return p.string();
}

std::string error_of(const std::string& csv) {
  try {
    read_fpga(csv);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ReportFpga, ReadsRunsAndQuotesTheLargestPlacedOne) {
  const std::string csv = write_csv("ok",
                                    "hx8k,ct256,1,8,3000,7680,2000,800,6,4,26.5,1,37.7,a,b\n"
                                    "hx8k,ct256,3,8,6000,7680,5000,1300,6,4,23.0,1,43.5,c,d\n"
                                    "hx8k,ct256,4,8,8100,7680,6400,1600,6,4,,0,,,\n"
                                    "up5k,sg48,1,8,3000,5280,2000,800,6,4,10.3,1,97.1,e,f\n");
  const FpgaData d = read_fpga(csv);
  ASSERT_EQ(d.runs.size(), 4u);
  EXPECT_EQ(d.provenance, "tools line\n");
  EXPECT_FALSE(d.runs[2].placed);
  const FpgaRun& ref = reference_run(d);
  EXPECT_EQ(ref.device, "hx8k");
  EXPECT_EQ(ref.blocks, 3u) << "the 4-block run did not fit, so it cannot be quoted";
  std::ostringstream out;
  write_fpga_section(d, out);
  const std::string md = out.str();
  EXPECT_NE(md.find("does not fit"), std::string::npos);
  // hx8k 1 .. 4 blocks: (6400 - 2000) / 3 LUTs and (1600 - 800) / 3 flip-flops per block.
  EXPECT_NE(md.find("| iCE40hx8k | 8 | 1 .. 4 | 1467 | 267 |"), std::string::npos) << md;
  EXPECT_NE(md.find("23.0 MHz (3 blocks; 26.5 MHz with 1)"), std::string::npos) << md;
  fs::remove(csv);
}

TEST(ReportFpga, NamesTheFileLineAndFieldOfBadInput) {
  EXPECT_NE(error_of(write_csv("text", "hx8k,ct256,1,8,x,7680,2000,800,6,4,26.5,1,37.7,a,b\n"))
                .find("fmpp_fpga_test_text.csv:3: field 'lcs' is 'x'"),
            std::string::npos);
  EXPECT_NE(error_of(write_csv("short", "hx8k,ct256,1,8\n")).find(":3: 4 fields, the header has 15"), std::string::npos);
  EXPECT_NE(error_of(write_csv("placed", "hx8k,ct256,1,8,1,2,3,4,5,6,7,yes,1,a,b\n")).find("field 'placed' is 'yes'"),
            std::string::npos);
  EXPECT_NE(error_of(write_csv("nofmax", "hx8k,ct256,1,8,1,2,3,4,5,6,,1,,a,b\n")).find("field 'fmax_mhz' is ''"),
            std::string::npos);
  EXPECT_NE(error_of("/nonexistent/summary.csv").find("cannot open"), std::string::npos);
  const FpgaData none = read_fpga(write_csv("none", "hx8k,ct256,4,8,8100,7680,6400,1600,6,4,,0,,,\n"));
  EXPECT_THROW(reference_run(none), std::runtime_error);
}

}  // namespace
}  // namespace fmpp::report
