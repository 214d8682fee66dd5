// fmpp-render's steps on several FMPPs (see render_chips.h).
#include "sw/mpi/render_chips.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace fmpp::mpi {
namespace {

// KernelStats is a flat record of uint64_t counters: it travels and sums as such.
static_assert(std::is_trivially_copyable_v<isect::KernelStats> && sizeof(isect::KernelStats) % 8 == 0,
              "KernelStats must stay a record of uint64_t counters");
constexpr size_t kWords = sizeof(isect::KernelStats) / 8;

std::vector<uint64_t> words(const isect::KernelStats& st) {
  std::vector<uint64_t> v(kWords);
  std::memcpy(v.data(), &st, sizeof st);
  return v;
}

}  // namespace

void RenderChips::agree(const std::vector<isect::Triangle>& tris, const Config& cfg, unsigned bits) const {
  uint64_t h = fnv1a(tris.data(), tris.size() * sizeof(isect::Triangle));
  s_.check_same(h, "the scene's triangles");
  const unsigned machine[3] = {cfg.blocks, cfg.words, bits};
  s_.check_same(fnv1a(machine, sizeof machine), "the FMPP configuration or the multiplier bits");
}

isect::PassShare* RenderChips::attach(const Device& dev) {
  if (!s_.active()) return nullptr;
  q_ = std::make_unique<WorkQueue>(s_);
  share_ = std::make_unique<SharedPasses>(s_, *q_, dev);
  return share_.get();
}

isect::KernelStats RenderChips::total(const isect::KernelStats& mine) const {
  if (!s_.active()) return mine;
  const std::vector<uint64_t> sum = s_.sum(words(mine));
  isect::KernelStats out;
  std::memcpy(static_cast<void*>(&out), sum.data(), sizeof out);
  return out;
}

nlohmann::json RenderChips::report(const isect::KernelStats& mine, double clock_mhz) const {
  if (!share_) return nullptr;
  nlohmann::json me = {{"rank", s_.rank()},
                       {"host", s_.host()},
                       {"clocks", mine.cycles},
                       {"load_cycles", mine.load_cycles},
                       {"compute_cycles", mine.compute_cycles},
                       {"readback_cycles", mine.readback_cycles},
                       {"passes", mine.passes},
                       {"broadcasts", mine.broadcasts},
                       {"exchange_wait_seconds", share_->wait_seconds()}};
  for (const SharedPasses::PassCost& c : share_->pass_costs()) me["pass_clocks"].push_back({c.call, c.pass, c.clocks});
  const std::vector<std::string> all = s_.gather(me.dump());
  if (!s_.leader()) return nullptr;
  nlohmann::json chips = nlohmann::json::array();
  uint64_t max_clocks = 0, sum_clocks = 0, transfers = 0;
  // Every pass's clocks, by call and pass (the input of tools/scaling_model.py).
  std::vector<std::vector<uint64_t>> calls(share_->calls());
  for (const std::string& j : all) {
    chips.push_back(nlohmann::json::parse(j));
    for (const auto& c : chips.back()["pass_clocks"]) {
      std::vector<uint64_t>& call = calls.at(c[0].get<size_t>());
      const size_t pass = c[1].get<size_t>();
      if (call.size() <= pass) call.resize(pass + 1, 0);
      call[pass] = c[2].get<uint64_t>();
    }
    chips.back().erase("pass_clocks");
    const uint64_t c = chips.back()["clocks"].get<uint64_t>();
    max_clocks = std::max(max_clocks, c);
    sum_clocks += c;
    transfers += chips.back()["load_cycles"].get<uint64_t>() + chips.back()["readback_cycles"].get<uint64_t>();
  }
  const double n = static_cast<double>(s_.size());
  // The chips meet after every call of the pass loop: a call lasts as long as its
  // slowest chip. The results then cross the host's 64-bit bus once, 8 bytes a clock.
  const uint64_t sync = share_->synchronized_clocks();
  const uint64_t exchange = (share_->exchanged_bytes() + 7) / 8;
  const uint64_t frame = sync + exchange;
  return {{"count", s_.size()},
          {"per_chip", chips},
          {"calls", share_->calls()},
          {"synchronized_clocks", sync},
          {"exchange_bytes", share_->exchanged_bytes()},
          {"exchange_bus_clocks", exchange},
          {"frame_clocks", frame},
          {"frame_ms", static_cast<double>(frame) / (clock_mhz * 1e3)},
          {"shared_bus_frame_clocks", std::max(frame, transfers + exchange)},
          {"speedup_clocks", frame ? static_cast<double>(sum_clocks) / static_cast<double>(frame) : 0.0},
          {"load_balance", max_clocks ? static_cast<double>(sum_clocks) / n / static_cast<double>(max_clocks) : 1.0},
          {"sync_efficiency", sync ? static_cast<double>(sum_clocks) / (n * static_cast<double>(sync)) : 1.0},
          {"pass_clocks", calls}};
}

}  // namespace fmpp::mpi
