// fmpp-render on several FMPPs (docs/multichip.md): what the tool does differently when
// a launcher starts it on N ranks. Every call is collective (all ranks, same order).
//
//   agree()   every rank loaded the same triangles and planned the same machine;
//   attach()  the SharedPasses for KernelOptions::share (nullptr outside a launcher);
//   wrap()    the intersector the renderer calls: the FMPP's, plus the exchange of
//             results after each batch (or pair of independent batches);
//   total()   the system's counters: the sum of every chip's (the figures one FMPP gives);
//   report()  the "chips" section: per-chip clocks, the system's frame time, the balance.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/isect/kernels.h"
#include "sw/render/render.h"
#include "sw/mpi/pass_share.h"
#include "common/mpi/session.h"
#include "common/mpi/work_queue.h"

namespace fmpp::mpi {

class RenderChips {
 public:
  explicit RenderChips(const Session& s) : s_(s) {}
  // Throws std::runtime_error naming the first rank that differs: the triangles, the
  // configuration, and every kernel option with the role kAgreed (sw/isect/pass/options.h).
  void agree(const std::vector<isect::Triangle>& tris, const Config& cfg, const isect::KernelOptions& ko) const;
  // leader_works = false: rank 0 only schedules (fmpp-render --rank0 schedule).
  isect::PassShare* attach(const Device& dev, bool leader_works = true);
  // After attach: `fi` with the exchange (fi itself when MPI is not active).
  rt::Intersector& wrap(rt::FmppIntersector& fi);
  isect::KernelStats total(const isect::KernelStats& mine) const;
  // On rank 0 the section, elsewhere null. mine: this rank's whole-frame counters.
  nlohmann::json report(const isect::KernelStats& mine, double clock_mhz) const;

 private:
  const Session& s_;
  std::unique_ptr<WorkQueue> q_;
  std::unique_ptr<SharedPasses> share_;
  std::unique_ptr<rt::Intersector> wrapped_;
};

}  // namespace fmpp::mpi
