// Work handed out on demand among the ranks of a job (docs/multichip.md): every rank
// numbers its jobs alike (job j is the j-th call of the same code on every rank), and
// within a job asks for the next item whenever it is free. Rank 0 keeps the counters
// and answers the others from a thread of its own, so that it works on items too and a
// request never waits for its current item to end.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <map>
#include <mutex>
#include <thread>

#include "common/mpi/session.h"

namespace fmpp::mpi {

class WorkQueue {
 public:
  // Collective: every rank builds its queue at the same point. leader_works = false:
  // rank 0 only answers (it never asks), the others share the items.
  explicit WorkQueue(const Session& s, bool leader_works = true);
  // Stops rank 0's thread. Every rank must have had its -1 of every job first.
  ~WorkQueue();
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  // The next item of job `job` (of `items`, the same count on every rank), or -1 once
  // every item is out. Each rank asks until it gets -1, which it gets once per job;
  // the items it receives increase.
  int64_t next(uint64_t job, uint64_t items);

 private:
  struct Job {
    uint64_t next = 0;
    int done = 0;
  };
  int64_t hand_out(uint64_t job, uint64_t items);  // rank 0, under mutex_
  void serve();                                   // rank 0's thread

  const Session& s_;
  const int askers_;  // ranks that ask until their -1
  std::mutex mutex_;
  std::map<uint64_t, Job> jobs_;
  std::atomic<bool> stop_{false};
  std::thread server_;
};

// Test-only fault injection, FMPP_TEST_FAULT=rank:passes:how (how: kill, exit, throw):
// that rank, when it has run `passes` passes (or fmpp-sim runs) and asks the queue for
// more, kills itself with SIGKILL, exits with status 3 without a word, or throws (as a
// backend reporting an error would). Every rank asks at least once per pass loop, so
// `passes` = 0 always fires. Parsed from the environment; an ill-formed value is an error.
struct Fault {
  int rank = -1;
  uint64_t passes = 0;
  std::string how;
  static Fault from_env();
  // Called before each of this rank's passes with the passes it has run.
  void maybe(int my_rank, uint64_t done) const;
};

}  // namespace fmpp::mpi
