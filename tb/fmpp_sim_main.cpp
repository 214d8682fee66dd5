// fmpp-sim: constrained-random RTL regression of one FMPP configuration.
//
// Drives the Verilated RTL through its AXI4-Lite port with a seeded random
// program and runs every access on the golden model in lockstep. Prints one
// summary line and exits 0 only if nothing differed, no RTL assertion fired and,
// for runs of 20,000 accesses or more, every opcode and error cause was exercised
// (a shorter run reports what it missed on stderr but does not fail for it).
//
// --backend systemc sends the RTL side's accesses through the SystemC TLM-2.0
// platform (backends/systemc/: initiator socket -> b_transport -> target -> RTL) instead of
// driving the RTL directly; the golden model stays the reference.
// --inject-at N demonstrates a mismatch: before access N it writes a wrong value
// into one word of the RTL only (the model gets the word's current value, so both
// sides spend the same clocks) and the lockstep must report it (docs/debugging.md).
// --seeds K runs the same options with seeds seed .. seed + K - 1, --jobs FILE the runs
// listed in a file (one run's options per line); under mpirun the runs are spread over
// the ranks (docs/multichip.md), and a total line and the first mismatch (with its rank,
// seed, access and instruction index, and the command that repeats it alone) follow.
//
//   fmpp-sim --config small --seed 1 --ops 100000 --mode check
//   fmpp-sim --config large --mode fast --hash-interval 2000 --stress
//   fmpp-sim --config small --ops 500 --trace sim.fst
//   fmpp-sim --config small --backend systemc --ops 100000
//   fmpp-sim --config odd --ops 3000 --inject-at 2000 --trace inject.fst
//   mpirun -np 2 fmpp-sim --jobs tests/sim/regress.jobs
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/util/cli_usage.h"
#include "fmpp/config.h"
#include "backends/rtl/rtl_bus.h"
#include "tb/sim_jobs.h"

using namespace fmpp;

namespace {

// The runs the command line asks for: the --jobs file's, or --seeds runs of its options.
std::vector<tb::SimOptions> jobs_of(const CLI::App& app, const tb::SimOptions& o, uint64_t seeds,
                                    const std::string& jobs_file) {
  std::vector<tb::SimOptions> jobs;
  if (!jobs_file.empty()) {
    for (const CLI::Option* opt : app.get_options()) {
      if (opt->count() > 0 && opt->get_name() != "--jobs") {
        throw std::invalid_argument("--jobs " + jobs_file + " takes every run's options from the file; " +
                                    opt->get_name() + " is not allowed with it");
      }
    }
    return tb::read_job_list(jobs_file);
  }
  if (seeds > 1 && (!o.trace.empty() || !o.coverage_out.empty())) {
    throw std::invalid_argument("--seeds " + std::to_string(seeds) +
                                ": every run would write the same --trace or --coverage-out file");
  }
  for (uint64_t k = 0; k < seeds; ++k) {
    jobs.push_back(o);
    jobs.back().seed = o.seed + k;
  }
  return jobs;
}

// Each run's line, its coverage hole on stderr, the total line (several runs), and the
// first mismatch with the command that repeats it; the exit status.
int report(const std::vector<tb::SimOptions>& jobs, const std::vector<tb::JobOutcome>& out, bool single, int ranks,
           double secs) {
  int status = 0;
  const tb::JobOutcome* first = nullptr;
  size_t first_job = 0;
  for (size_t k = 0; k < out.size(); ++k) {
    const tb::SimResult& r = out[k].result;
    std::printf("%s\n", r.line.c_str());
    if (r.mismatches) {
      status = 1;
      if (!first) {
        first = &out[k];
        first_job = k;
      }
    } else if (!r.missing.empty()) {
      std::fprintf(stderr, "coverage hole: never exercised: %s%s\n", r.missing.c_str(),
                   r.coverage_fail ? "" : " (not an error below 20000 accesses)");
      if (r.coverage_fail) status = 1;
    }
  }
  if (!single) std::printf("%s\n", tb::total_line(out, ranks, secs).c_str());
  std::fflush(stdout);
  if (!first) return status;
  const tb::SimOptions& j = jobs[first_job];
  if (!single) {
    std::fprintf(stderr,
                 "first mismatch: run %zu of %zu on rank %d: config %s seed %llu, at access index %llu "
                 "(from 0) after %llu instructions\n",
                 first_job + 1, jobs.size(), first->rank, j.config.c_str(), static_cast<unsigned long long>(j.seed),
                 static_cast<unsigned long long>(first->result.mismatch_access),
                 static_cast<unsigned long long>(first->result.mismatch_instruction));
  }
  std::fprintf(stderr, "%s\nreproduce: %s\n", first->result.report.c_str(), tb::reproduce_command(j).c_str());
  if (!first->result.waveform.empty()) std::fprintf(stderr, "%s\n", first->result.waveform.c_str());
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<mpi::Session> session;  // MPI only under a launcher (docs/multichip.md)
  try {
    session = std::make_unique<mpi::Session>(&argc, &argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-sim: %s\n", e.what());
    return 2;
  }
  CLI::App app{"FMPP RTL regression: random programs, RTL in lockstep with the golden model"};
  tb::SimOptions o;
  tb::add_run_options(app, &o);
  bool list = false;
  uint64_t seeds = 1;
  std::string jobs_file;
  app.add_flag("--list", list, "list the built configurations and exit");
  auto* seeds_opt = app.add_option("--seeds", seeds, "runs with seeds seed .. seed + K - 1 (spread over MPI ranks)")
                        ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 20));
  app.add_option("--jobs", jobs_file, "a list of runs, one run's options per line (spread over MPI ranks)")
      ->excludes(seeds_opt);
  app.footer(
      "Exit status: 0 every run matched, 1 a run found a mismatch, a failed RTL assertion or (from 20000 accesses) "
      "a coverage hole, 2 a usage error (an unknown option, a bad or missing value) or an error that stopped the "
      "runs (its message says which).");
  if (const int status = parse_command_line(app, argc, argv); status >= 0) return status;
  tb::sync_inject(app, &o);

  if (list) {
    if (session->leader()) {
      for (const auto& n : backends::rtl_configs()) std::printf("%s %s\n", n.c_str(), named_config(n).str().c_str());
    }
    return 0;
  }

  try {
    const std::vector<tb::SimOptions> jobs = jobs_of(app, o, seeds, jobs_file);
    const bool single = jobs.size() == 1 && session->size() == 1 && jobs_file.empty();
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<tb::JobOutcome> out = tb::run_jobs(*session, jobs);
    if (!session->leader()) return 0;
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return report(jobs, out, single, session->size(), secs);
  } catch (const std::exception& e) {
    if (session->size() > 1) session->abort("fmpp-sim", e.what(), 2);
    std::fprintf(stderr, "fmpp-sim: %s\n", e.what());
    return 2;
  }
}
