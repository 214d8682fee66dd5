// fmpp-sim's runs spread over ranks (see sim_jobs.h).
#include "tb/sim_jobs.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <stdexcept>

#include "common/mpi/work_queue.h"

namespace fmpp::tb {
namespace {

nlohmann::json to_json(size_t job, int rank, const SimResult& r) {
  return {{"job", job}, {"rank", rank}, {"line", r.line}, {"accesses", r.accesses}, {"instructions", r.instructions},
          {"cycles", r.cycles}, {"mismatches", r.mismatches}, {"seconds", r.seconds}, {"report", r.report},
          {"mismatch_access", r.mismatch_access}, {"mismatch_instruction", r.mismatch_instruction},
          {"waveform", r.waveform}, {"missing", r.missing}, {"coverage_fail", r.coverage_fail}};
}

JobOutcome from_json(const nlohmann::json& j) {
  JobOutcome o;
  o.rank = j["rank"].get<int>();
  SimResult& r = o.result;
  r.line = j["line"].get<std::string>();
  r.accesses = j["accesses"].get<uint64_t>();
  r.instructions = j["instructions"].get<uint64_t>();
  r.cycles = j["cycles"].get<uint64_t>();
  r.mismatches = j["mismatches"].get<uint64_t>();
  r.seconds = j["seconds"].get<double>();
  r.report = j["report"].get<std::string>();
  r.mismatch_access = j["mismatch_access"].get<uint64_t>();
  r.mismatch_instruction = j["mismatch_instruction"].get<uint64_t>();
  r.waveform = j["waveform"].get<std::string>();
  r.missing = j["missing"].get<std::string>();
  r.coverage_fail = j["coverage_fail"].get<bool>();
  return o;
}

}  // namespace

std::vector<JobOutcome> run_jobs(const mpi::Session& s, const std::vector<SimOptions>& jobs) {
  const mpi::Fault fault = mpi::Fault::from_env();  // test-only (common/mpi/work_queue.h): a run stands for a pass
  nlohmann::json mine = nlohmann::json::array();
  {
    mpi::WorkQueue q(s);
    uint64_t done = 0;
    for (int64_t j; fault.maybe(s.rank(), done), (j = q.next(0, jobs.size())) >= 0; ++done) {
      const SimOptions& o = jobs[static_cast<size_t>(j)];
      try {
        mine.push_back(to_json(static_cast<size_t>(j), s.rank(), run_sim(o)));
      } catch (const std::exception& e) {
        throw std::runtime_error("run " + std::to_string(j + 1) + " of " + std::to_string(jobs.size()) + " (" +
                                 reproduce_command(o) + "): " + e.what());
      }
    }
    // Every rank has had its -1 once the gather below starts: the queue may stop.
    s.check_same(jobs.size(), "the job list");
  }
  std::vector<JobOutcome> out;
  const std::vector<std::string> all = s.gather(mine.dump());
  if (!s.leader()) return out;
  out.resize(jobs.size());
  std::vector<bool> seen(jobs.size(), false);
  for (const std::string& part : all) {
    for (const auto& j : nlohmann::json::parse(part)) {
      const size_t k = j["job"].get<size_t>();
      out.at(k) = from_json(j);
      seen[k] = true;
    }
  }
  for (size_t k = 0; k < seen.size(); ++k) {
    if (!seen[k]) throw std::logic_error("run " + std::to_string(k + 1) + " came back from no rank");
  }
  return out;
}

std::vector<SimOptions> read_job_list(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open");
  std::vector<SimOptions> jobs;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    try {
      jobs.push_back(parse_run(line.substr(first)));
    } catch (const std::exception& e) {
      throw std::invalid_argument(path + ":" + std::to_string(n) + ": " + e.what());
    }
  }
  if (jobs.empty()) throw std::invalid_argument(path + ": no run in the list");
  return jobs;
}

std::string total_line(const std::vector<JobOutcome>& outcomes, int ranks, double seconds) {
  uint64_t acc = 0, ins = 0, cyc = 0, mis = 0;
  double busy = 0;
  for (const JobOutcome& o : outcomes) {
    acc += o.result.accesses;
    ins += o.result.instructions;
    cyc += o.result.cycles;
    mis += o.result.mismatches;
    busy += o.result.seconds;
  }
  char line[512];
  std::snprintf(line, sizeof line,
                "total runs=%zu ranks=%d accesses=%llu instructions=%llu cycles=%llu mismatches=%llu "
                "run_seconds=%.1f wall_seconds=%.1f",
                outcomes.size(), ranks, static_cast<unsigned long long>(acc), static_cast<unsigned long long>(ins),
                static_cast<unsigned long long>(cyc), static_cast<unsigned long long>(mis), busy, seconds);
  return line;
}

}  // namespace fmpp::tb
