// fmpp-sim's list of runs, spread over the ranks of an MPI job (docs/multichip.md):
// every rank holds the same list, takes the next run from the WorkQueue whenever it is
// free, and rank 0 gathers what each run found, in the list's order, with the rank that
// ran it. Without a launcher the same code runs the list on one process.
#pragma once

#include <string>
#include <vector>

#include "common/mpi/session.h"
#include "tb/sim_run.h"

namespace fmpp::tb {

struct JobOutcome {
  int rank = 0;  // the rank that ran it
  SimResult result;
};

// Runs `jobs`; on rank 0 every outcome in list order, elsewhere none. A run that throws
// (bad options, an RTL assertion) rethrows with its list position and reproducing
// command, on the rank that ran it.
std::vector<JobOutcome> run_jobs(const mpi::Session& s, const std::vector<SimOptions>& jobs);

// The runs of a job list file: one run's options per line; empty lines and lines
// starting with '#' are skipped. Throws naming the file and line.
std::vector<SimOptions> read_job_list(const std::string& path);

// The aggregated summary line of `outcomes` over `ranks` ranks and `seconds` of wall time.
std::string total_line(const std::vector<JobOutcome>& outcomes, int ranks, double seconds);

}  // namespace fmpp::tb
