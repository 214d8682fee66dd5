// The passes of the intersection kernels shared among the FMPPs of a job, one FMPP per
// rank (docs/multichip.md). Every rank runs the same renderer on the same scene, so it
// makes the same calls of isect::run_passes with the same passes; within a call each
// rank takes passes from the WorkQueue whenever its FMPP is free and moves on to the
// next call when none is left. After a batch (or two independent ones) the ranks swap
// the results of their passes, so every rank shades every pixel alike. A pass computes
// exactly what it computes on one FMPP (its rays, its culling, its host redos), so the
// image is the same for any number of ranks.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "sw/fmpp/device.h"
#include "sw/isect/pass/pass.h"
#include "common/mpi/session.h"
#include "common/mpi/work_queue.h"

namespace fmpp::mpi {

class SharedPasses : public isect::PassShare {
 public:
  // leader_works = false: rank 0 takes no pass (it schedules, shades and writes).
  SharedPasses(const Session& s, WorkQueue& q, const Device& dev, bool leader_works = true);

  bool take(uint64_t turn, uint64_t pass, uint64_t passes) override;
  void finish(isect::PassPlan& plan, unsigned blocks) override;
  unsigned devices() const override;

  // The calls that follow fill batch `slot` of the next exchange (0 or 1).
  void begin_batch(int slot) { slot_ = slot; }
  // Collective: every rank sends the hits its passes found in batches[slot] and gets
  // the others' (batches: the intersector's results, indexed like its rays).
  void exchange(const std::vector<std::vector<isect::Hit>*>& batches);

  // What the system did so far, for the report.
  uint64_t calls() const { return calls_; }
  uint64_t passes_run() const { return passes_run_; }
  // Sum over exchanges of the slowest rank's clocks since the last one (the ranks meet
  // at each).
  uint64_t synchronized_clocks() const { return sync_clocks_; }
  uint64_t exchanges() const { return exchanges_; }
  // Bytes of results of all ranks' passes swapped after the calls (each result once).
  uint64_t exchanged_bytes() const { return exchanged_bytes_; }
  // Wall seconds this rank waited in the exchanges (its share of the imbalance).
  double wait_seconds() const { return wait_seconds_; }
  // Wall seconds this rank waited for the work queue's answers.
  double ask_seconds() const { return ask_seconds_; }
  // The clocks of every pass run here: (exchange, call, pass, clocks; turn: its place in
  // the order the call's passes were handed out), the scaling model's input.
  struct PassCost {
    uint64_t exchange, call, pass, clocks, turn;
    double seconds;  // wall time of the pass here (simulation and the pass's host work)
  };
  const std::vector<PassCost>& pass_costs() const { return costs_; }

 private:
  static constexpr int64_t kAsk = -2;  // the next pass is not asked for yet
  const Session& s_;
  WorkQueue& q_;
  const Device& dev_;
  Fault fault_;
  bool idle_;  // this rank takes no pass
  uint64_t last_clocks_;  // the device's clocks at the last exchange
  bool open_ = false;       // inside a call of run_passes
  int64_t next_ = kAsk;     // this rank's next pass of the call, -1 when none is left
  uint64_t call_ = 0, c0_ = 0, passes_ = 0;
  std::vector<uint64_t> mine_;  // this call's passes run here
  int slot_ = 0;
  std::vector<std::pair<int, size_t>> own_;  // (slot, ray) answered here since the last exchange
  uint64_t exchanges_ = 0;
  bool running_ = false;        // mine_.back() runs since pass_c0_
  uint64_t turn_ = 0;           // the turn it was handed out at
  uint64_t pass_c0_ = 0;
  std::chrono::steady_clock::time_point pass_t0_;
  std::vector<PassCost> costs_;
  void end_pass();
  uint64_t calls_ = 0, passes_run_ = 0, sync_clocks_ = 0, exchanged_bytes_ = 0;
  double wait_seconds_ = 0, ask_seconds_ = 0;
  int64_t ask(uint64_t passes);  // the queue's next pass of this call, timed
};

}  // namespace fmpp::mpi
