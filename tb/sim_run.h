// One run of fmpp-sim (a seeded random program, the RTL in lockstep with the golden
// model), as a function: the command line of one run, its options, and what it found.
// fmpp_sim_main.cpp runs one or a list of them, on one process or spread over the
// ranks of an MPI job (tb/sim_jobs.cpp, docs/multichip.md).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace fmpp::tb {

struct SimOptions {
  std::string config = "small";
  uint64_t seed = 1;
  uint64_t ops = 10000;
  std::string mode = "check";
  uint64_t hash_interval = 4096;
  bool stress = false;
  std::string trace;
  uint64_t trace_start = 0, trace_end = ~0ull;
  std::string backend = "rtl";
  bool inject = false;  // --inject-at given
  uint64_t inject_at = 0;
  int64_t inject_block = -1;
  unsigned inject_word = 0;
  uint32_t inject_value = 0xDEADBEEF;
  uint64_t random_init = 0;
  bool max_backpressure = false, storms = false;
  uint64_t reset_every = 0;
  std::string coverage_out;
};

// Adds the options of one run to `app`, bound to *o (call sync_inject after parsing).
void add_run_options(CLI::App& app, SimOptions* o);
// After app's parse: whether --inject-at was given.
void sync_inject(const CLI::App& app, SimOptions* o);
// The options of one run from a line of a job list ("--config small --seed 3 ...").
// Throws std::invalid_argument naming the line's problem.
SimOptions parse_run(const std::string& line);
// The command line that repeats run `o` alone, with its state compared after every entry.
std::string reproduce_command(const SimOptions& o);

struct SimResult {
  std::string line;  // the summary line, key=value pairs
  uint64_t accesses = 0, instructions = 0, cycles = 0, mismatches = 0;
  double seconds = 0;
  // A mismatch: the lockstep's report, the access and instruction counts before it.
  std::string report;
  uint64_t mismatch_access = 0, mismatch_instruction = 0;
  std::string waveform;  // where to look in the trace, if one was written
  std::string missing;   // opcodes or error causes never exercised
  bool coverage_fail = false;  // missing at 20,000 accesses or more
};

// Runs `o`. Throws std::invalid_argument for bad options, and whatever the backend
// throws for a failure that is not a lockstep mismatch (an RTL assertion).
SimResult run_sim(const SimOptions& o);

}  // namespace fmpp::tb
