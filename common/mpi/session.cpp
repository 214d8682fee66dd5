// Open MPI's lifetime and the collectives of the tools (see session.h).
#include "common/mpi/session.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#ifdef FMPP_HAVE_MPI
#include <mpi.h>
#endif

namespace fmpp::mpi {

bool launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(v) != nullptr) return true;
  }
  return false;
}

uint64_t fnv1a(const void* data, size_t bytes, uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

#ifdef FMPP_HAVE_MPI

Session::Session(int* argc, char*** argv) {
  if (!launched()) return;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS) {
    throw std::runtime_error("MPI_Init_thread failed");
  }
  active_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int len = 0;
  MPI_Get_processor_name(name, &len);
  host_.assign(name, static_cast<size_t>(len));
  if (provided < MPI_THREAD_MULTIPLE && size_ > 1) {
    throw std::runtime_error("this MPI library gives thread level " + std::to_string(provided) +
                             ", the work queue needs MPI_THREAD_MULTIPLE");
  }
}

Session::~Session() {
  if (active_) MPI_Finalize();
}

void Session::abort(const std::string& tool, const std::string& message, int code) const {
  std::fprintf(stderr, "%s: rank %d of %d (%s): %s\n", tool.c_str(), rank_, size_, host_.c_str(), message.c_str());
  std::fflush(stderr);
  if (active_) MPI_Abort(MPI_COMM_WORLD, code);
}

void Session::check_same(uint64_t value, const std::string& what) const {
  if (!active_ || size_ == 1) return;
  std::vector<uint64_t> all(static_cast<size_t>(size_));
  MPI_Allgather(&value, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
  for (int r = 1; r < size_; ++r) {
    if (all[static_cast<size_t>(r)] != all[0]) {
      throw std::runtime_error(what + " differs between rank 0 and rank " + std::to_string(r) +
                               " (every rank must read the same files and options)");
    }
  }
}

std::vector<std::string> Session::gather(const std::string& mine) const {
  if (!active_) return {mine};
  const int n = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<size_t>(size_)), displs(static_cast<size_t>(size_));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank_ == 0) {
    size_t total = 0;
    for (int r = 0; r < size_; ++r) {
      displs[static_cast<size_t>(r)] = static_cast<int>(total);
      total += static_cast<size_t>(counts[static_cast<size_t>(r)]);
    }
    all.resize(total);
  }
  MPI_Gatherv(mine.data(), n, MPI_CHAR, all.data(), counts.data(), displs.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  if (rank_ == 0) {
    for (int r = 0; r < size_; ++r) {
      out.push_back(all.substr(static_cast<size_t>(displs[static_cast<size_t>(r)]),
                               static_cast<size_t>(counts[static_cast<size_t>(r)])));
    }
  }
  return out;
}

std::vector<uint64_t> Session::sum(const std::vector<uint64_t>& v) const {
  if (!active_) return v;
  std::vector<uint64_t> out(v.size());
  MPI_Allreduce(v.data(), out.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return out;
}

std::vector<uint64_t> Session::max(const std::vector<uint64_t>& v) const {
  if (!active_) return v;
  std::vector<uint64_t> out(v.size());
  MPI_Allreduce(v.data(), out.data(), static_cast<int>(v.size()), MPI_UINT64_T, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

#else  // built without MPI: one process, and an error if a launcher started several

Session::Session(int*, char***) {
  if (launched()) {
    throw std::runtime_error("started by an MPI launcher, but this binary was built without MPI "
                             "(install libopenmpi-dev and configure again; docs/multichip.md)");
  }
}
Session::~Session() = default;
void Session::abort(const std::string& tool, const std::string& message, int) const {
  std::fprintf(stderr, "%s: %s\n", tool.c_str(), message.c_str());
}
void Session::check_same(uint64_t, const std::string&) const {}
std::vector<std::string> Session::gather(const std::string& mine) const { return {mine}; }
std::vector<uint64_t> Session::sum(const std::vector<uint64_t>& v) const { return v; }
std::vector<uint64_t> Session::max(const std::vector<uint64_t>& v) const { return v; }

#endif

}  // namespace fmpp::mpi
