// Passes handed out among the FMPPs of a job, results swapped after each call (see
// pass_share.h).
#include "sw/mpi/pass_share.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <type_traits>

#ifdef FMPP_HAVE_MPI
#include <mpi.h>
#endif

namespace fmpp::mpi {
namespace {

#ifdef FMPP_HAVE_MPI
// Waits for `req` without spinning: Open MPI's blocking collectives poll a core at full
// speed, and a rank waiting for the slowest one would take that core from the FMPPs
// (two ranks on two cores, or other work on the machine). Sleeps grow from 20 us to 1 ms.
void wait_quietly(MPI_Request* req) {
  int done = 0;
  for (int us = 20;; us = std::min(1000, 2 * us)) {
    MPI_Test(req, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::microseconds(us));
  }
}
#endif

// One ray's result on the wire.
struct Record {
  uint64_t index;
  double t;
  double t_err;
  int32_t tri;
  int16_t redo;
  int16_t slot;
};
static_assert(std::is_trivially_copyable_v<Record> && sizeof(Record) == 32, "Record travels as bytes");

}  // namespace

SharedPasses::SharedPasses(const Session& s, WorkQueue& q, const Device& dev, bool leader_works)
    : s_(s), q_(q), dev_(dev), fault_(Fault::from_env()), idle_(s.leader() && !leader_works && s.size() > 1),
      last_clocks_(dev.cycles()) {}

int64_t SharedPasses::ask(uint64_t passes) {
  const auto t0 = std::chrono::steady_clock::now();
  const int64_t n = q_.next(call_, passes);
  ask_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return n;
}

void SharedPasses::end_pass() {
  if (!running_) return;
  costs_.push_back(PassCost{exchanges_, call_, mine_.back(), dev_.cycles() - pass_c0_, turn_,
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_t0_).count()});
  running_ = false;
}

bool SharedPasses::take(uint64_t turn, uint64_t pass, uint64_t passes) {
  if (idle_) return false;
  end_pass();
  if (!open_) {
    open_ = true;
    passes_ = passes;
    c0_ = dev_.cycles();
    mine_.clear();
    next_ = kAsk;
  }
  if (next_ == kAsk) {
    fault_.maybe(s_.rank(), passes_run_);
    next_ = ask(passes_);
  }
  if (next_ != static_cast<int64_t>(turn)) return false;
  mine_.push_back(pass);
  turn_ = turn;
  ++passes_run_;
  next_ = kAsk;
  running_ = true;
  pass_c0_ = dev_.cycles();
  pass_t0_ = std::chrono::steady_clock::now();
  return true;
}

// The same answer on every rank (the order of the passes must agree): the ranks of the
// job, an idle leader included.
unsigned SharedPasses::devices() const { return s_.active() ? static_cast<unsigned>(s_.size()) : 1; }

void SharedPasses::finish(isect::PassPlan& plan, unsigned blocks) {
  const size_t items = plan.items();
  if (items == 0 || idle_) return;  // no pass on any rank, or none here: nothing was asked
  if (!open_) throw std::logic_error("SharedPasses::finish without take");
  end_pass();
  // The passes are all out; this rank's last question gets its -1 (exactly one per job).
  if (next_ == kAsk) next_ = ask(passes_);
  if (next_ != -1) throw std::logic_error("SharedPasses: pass " + std::to_string(next_) + " handed out but not run");
  open_ = false;
  ++call_;
  ++calls_;
  std::vector<std::pair<size_t, isect::Hit>> res;
  for (uint64_t p : mine_) {
    const size_t base = static_cast<size_t>(p) * blocks;
    plan.results(base, static_cast<unsigned>(std::min<size_t>(blocks, items - base)), &res);
  }
  for (const auto& r : res) own_.emplace_back(slot_, r.first);
}

void SharedPasses::exchange(const std::vector<std::vector<isect::Hit>*>& batches) {
  if (open_) throw std::logic_error("SharedPasses::exchange inside a pass loop");
  const uint64_t clocks = dev_.cycles() - last_clocks_;
  last_clocks_ = dev_.cycles();
  ++exchanges_;
  slot_ = 0;
  std::vector<Record> out;
  out.reserve(own_.size());
  for (const auto& [slot, i] : own_) {
    const isect::Hit& h = batches.at(static_cast<size_t>(slot))->at(i);
    out.push_back(Record{i, h.t, h.t_err, h.tri, static_cast<int16_t>(h.redo), static_cast<int16_t>(slot)});
  }
  own_.clear();
  if (!s_.active() || s_.size() == 1) {
    sync_clocks_ += clocks;
    return;
  }
#ifdef FMPP_HAVE_MPI
  const auto t0 = std::chrono::steady_clock::now();
  const size_t n = static_cast<size_t>(s_.size());
  // Each rank's record count and clocks since the last exchange, then the records.
  const uint64_t head[2] = {out.size(), clocks};
  std::vector<uint64_t> heads(2 * n);
  MPI_Request req;
  MPI_Iallgather(head, 2, MPI_UINT64_T, heads.data(), 2, MPI_UINT64_T, MPI_COMM_WORLD, &req);
  wait_quietly(&req);
  std::vector<int> counts(n), displs(n);
  size_t total = 0;
  uint64_t slowest = 0;
  for (size_t r = 0; r < n; ++r) {
    const uint64_t bytes = heads[2 * r] * sizeof(Record);
    if (bytes > static_cast<uint64_t>(INT32_MAX) - total) throw std::length_error("SharedPasses: exchange over 2 GiB");
    counts[r] = static_cast<int>(bytes);
    displs[r] = static_cast<int>(total);
    total += bytes;
    slowest = std::max(slowest, heads[2 * r + 1]);
  }
  std::vector<Record> all(total / sizeof(Record));
  MPI_Iallgatherv(out.data(), static_cast<int>(out.size() * sizeof(Record)), MPI_BYTE, all.data(), counts.data(),
                  displs.data(), MPI_BYTE, MPI_COMM_WORLD, &req);
  wait_quietly(&req);
  wait_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sync_clocks_ += slowest;
  exchanged_bytes_ += total;
  const size_t own_first = static_cast<size_t>(displs[static_cast<size_t>(s_.rank())]) / sizeof(Record);
  for (size_t i = 0; i < all.size(); ++i) {
    if (i >= own_first && i < own_first + out.size()) continue;
    isect::Hit& h = batches.at(static_cast<size_t>(all[i].slot))->at(static_cast<size_t>(all[i].index));
    h.tri = all[i].tri;
    h.t = all[i].t;
    h.t_err = all[i].t_err;
    h.redo = static_cast<isect::HostRedo>(all[i].redo);
  }
#endif
}

}  // namespace fmpp::mpi
