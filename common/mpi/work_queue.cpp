// Items handed out on demand by rank 0 (see work_queue.h).
#include "common/mpi/work_queue.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef FMPP_HAVE_MPI
#include <mpi.h>
#endif

namespace fmpp::mpi {

#ifdef FMPP_HAVE_MPI
namespace {
constexpr int kTagAsk = 7101, kTagGive = 7102;
}  // namespace
#endif

WorkQueue::WorkQueue(const Session& s, bool leader_works)
    : s_(s), askers_(leader_works || !s.active() || s.size() == 1 ? s.size() : s.size() - 1) {
#ifdef FMPP_HAVE_MPI
  if (s_.active() && s_.leader() && s_.size() > 1) server_ = std::thread([this] { serve(); });
#endif
}

WorkQueue::~WorkQueue() {
  stop_ = true;
  if (server_.joinable()) server_.join();
}

int64_t WorkQueue::hand_out(uint64_t job, uint64_t items) {
  Job& j = jobs_[job];
  if (j.next < items) return static_cast<int64_t>(j.next++);
  // Every rank gets its -1 once; the last one retires the job.
  if (++j.done == askers_) jobs_.erase(job);
  return -1;
}

int64_t WorkQueue::next(uint64_t job, uint64_t items) {
  if (s_.leader() || !s_.active()) {
    std::lock_guard<std::mutex> lock(mutex_);
    return hand_out(job, items);
  }
#ifdef FMPP_HAVE_MPI
  uint64_t ask[2] = {job, items};
  int64_t give = -1;
  MPI_Send(ask, 2, MPI_UINT64_T, 0, kTagAsk, MPI_COMM_WORLD);
  MPI_Recv(&give, 1, MPI_INT64_T, 0, kTagGive, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return give;
#else
  throw std::logic_error("WorkQueue: several ranks without MPI");
#endif
}

void WorkQueue::serve() {
#ifdef FMPP_HAVE_MPI
  // Polls with sleeps: a blocking receive would spin the core rank 0's FMPP runs on. Each
  // probe costs a turn of Open MPI's progress engine, so an idle queue backs off from
  // 20 us to 1 ms between probes (with a fixed 50 us poll, rank 0's RTL passes ran 22
  // to 40 % slower than on one rank, rank 1's did not); an answer then waits at most
  // 1 ms, against passes of milliseconds (golden model) to seconds (RTL).
  int sleep_us = 20;
  while (!stop_) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagAsk, MPI_COMM_WORLD, &flag, &st);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::microseconds(sleep_us));
      sleep_us = std::min(1000, 2 * sleep_us);
      continue;
    }
    sleep_us = 20;
    uint64_t ask[2] = {0, 0};
    MPI_Recv(ask, 2, MPI_UINT64_T, st.MPI_SOURCE, kTagAsk, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    int64_t give = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      give = hand_out(ask[0], ask[1]);
    }
    MPI_Send(&give, 1, MPI_INT64_T, st.MPI_SOURCE, kTagGive, MPI_COMM_WORLD);
  }
#endif
}

Fault Fault::from_env() {
  Fault f;
  const char* v = std::getenv("FMPP_TEST_FAULT");
  if (v == nullptr || *v == 0) return f;
  const std::string s(v);
  const size_t a = s.find(':'), b = a == std::string::npos ? a : s.find(':', a + 1);
  try {
    if (b == std::string::npos) throw std::invalid_argument("form");
    f.rank = std::stoi(s.substr(0, a));
    f.passes = std::stoull(s.substr(a + 1, b - a - 1));
    f.how = s.substr(b + 1);
  } catch (const std::exception&) {
    throw std::invalid_argument("FMPP_TEST_FAULT='" + s + "': expected rank:passes:kill|exit|throw");
  }
  if (f.how != "kill" && f.how != "exit" && f.how != "throw") {
    throw std::invalid_argument("FMPP_TEST_FAULT='" + s + "': '" + f.how + "' is not one of kill, exit, throw");
  }
  return f;
}

void Fault::maybe(int my_rank, uint64_t done) const {
  if (my_rank != rank || done != passes) return;
  if (how == "kill") std::raise(SIGKILL);
  if (how == "exit") std::_Exit(3);
  throw std::runtime_error("FMPP_TEST_FAULT: injected backend error after " + std::to_string(done) +
                           " passes of this rank");
}

}  // namespace fmpp::mpi
