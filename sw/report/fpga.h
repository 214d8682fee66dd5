// FPGA figures of `make fpga` (tools/fpga.sh: yosys synth_ice40 + nextpnr-ice40) for the
// reports: docs/generated/area.md sets them beside the ASIC estimate, docs/generated/paper-reproduction.md
// puts the measured clock beside the paper's 50 MHz.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace fmpp::report {

// One place-and-route run (a row of tools/fpga.sh's summary.csv).
struct FpgaRun {
  std::string device, package;
  unsigned blocks = 0, words = 0;
  unsigned lcs = 0, lcs_avail = 0, luts = 0, dffs = 0, brams = 0, ios = 0;
  bool placed = false;
  double fmax_mhz = 0;   // 0 when not placed
  double crit_ns = 0;
  std::string crit_from, crit_to;
};

struct FpgaData {
  std::string provenance;  // the CSV's comment lines (tools, date, machine)
  std::vector<FpgaRun> runs;
};

// Reads summary.csv of tools/fpga.sh. Throws std::runtime_error naming the file, the
// line and the field for anything malformed or missing.
FpgaData read_fpga(const std::string& csv);

// The measured clock to quote: the placed run with the most blocks on the largest
// device (ties: the fastest). Throws std::runtime_error if no run was placed.
const FpgaRun& reference_run(const FpgaData& d);

// docs/generated/area.md's FPGA section: the runs, the cost per block, the critical path and
// what the figures imply for an ASIC.
void write_fpga_section(const FpgaData& d, std::ostream& out);

// docs/generated/paper-reproduction.md: the measured FPGA clock beside the paper's 50 MHz. A
// table of ray-parallel test rates at both clocks (`clocks_per_broadcast` per broadcast,
// against `cpu_tests_per_s` of one CPU core) and what the clock changes in the
// speed-up tables.
void write_clock_comparison(const FpgaData& d, double clocks_per_broadcast, double cpu_tests_per_s,
                            std::ostream& out);

}  // namespace fmpp::report
