// One process of a job of several FMPPs (docs/multichip.md): Open MPI's lifetime, this
// process's rank among the others, and the few collective steps every tool needs.
//
// A tool builds one Session first. Started by an MPI launcher (mpirun sets
// OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK), it initialises MPI with thread support
// (WorkQueue serves requests from a thread of rank 0); started any other way it touches
// no MPI at all and is rank 0 of 1, so the tool behaves exactly as a plain program.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fmpp::mpi {

// True when an MPI launcher started this process (its environment says so).
bool launched();

class Session {
 public:
  // Throws std::runtime_error when launched but MPI is not built into this binary or
  // cannot give the thread support the work queue needs.
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Whether MPI is initialised (launched and built with MPI).
  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool leader() const { return rank_ == 0; }
  // The host this rank runs on (MPI_Get_processor_name; "localhost" when not active).
  const std::string& host() const { return host_; }

  // Prints "<tool>: rank r of n (host): <message>" on stderr and ends every process of
  // the job with exit code `code` (MPI_Abort); not active: only prints.
  void abort(const std::string& tool, const std::string& message, int code) const;
  // Throws std::runtime_error naming `what` and the ranks unless every rank passes the
  // same value.
  void check_same(uint64_t value, const std::string& what) const;
  // Every rank's bytes, in rank order, on rank 0 (empty elsewhere). Collective.
  std::vector<std::string> gather(const std::string& mine) const;
  // The element-wise sum over ranks of v, on every rank. Collective.
  std::vector<uint64_t> sum(const std::vector<uint64_t>& v) const;
  // The element-wise maximum over ranks of v, on every rank. Collective.
  std::vector<uint64_t> max(const std::vector<uint64_t>& v) const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
  std::string host_ = "localhost";
};

// FNV-1a over bytes, for check_same.
uint64_t fnv1a(const void* data, size_t bytes, uint64_t h = 14695981039346656037ull);

}  // namespace fmpp::mpi
