// fmpp-render's steps on several FMPPs (see render_chips.h).
#include "sw/mpi/render_chips.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <type_traits>

#include "sw/isect/stats_json.h"

namespace fmpp::mpi {
namespace {

// KernelStats is a flat record of uint64_t counters: it travels and sums as such.
static_assert(std::is_trivially_copyable_v<isect::KernelStats> && sizeof(isect::KernelStats) % 8 == 0,
              "KernelStats must stay a record of uint64_t counters");
constexpr size_t kWords = sizeof(isect::KernelStats) / 8;

nlohmann::json pass_lists(const std::vector<std::map<std::pair<uint64_t, uint64_t>, uint64_t>>& by_exchange) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& m : by_exchange) {
    nlohmann::json l = nlohmann::json::array();
    for (const auto& kv : m) l.push_back(kv.second);
    out.push_back(l);
  }
  return out;
}

std::vector<uint64_t> words(const isect::KernelStats& st) {
  std::vector<uint64_t> v(kWords);
  std::memcpy(v.data(), &st, sizeof st);
  return v;
}

// The FMPP's intersector; after each batch, or pair of independent batches, the ranks
// swap the results of their passes.
class SharedIntersector : public rt::Intersector {
 public:
  SharedIntersector(rt::FmppIntersector& fi, SharedPasses& share) : fi_(fi), share_(share) {}
  void set_batch_kind(rt::BatchKind k) override { fi_.set_batch_kind(k); }
  double spawn_margin() const override { return fi_.spawn_margin(); }
  isect::AnswerRules answer_rules(rt::BatchKind k) const override { return fi_.answer_rules(k); }
  std::string describe() const override { return fi_.describe() + ", passes shared among the ranks"; }
  std::vector<isect::Hit> intersect(const std::vector<isect::Ray>& rays) override {
    share_.begin_batch(0);
    std::vector<isect::Hit> h = fi_.intersect(rays);
    share_.exchange({&h});
    return h;
  }
  std::pair<std::vector<isect::Hit>, std::vector<isect::Hit>> intersect_two(const std::vector<isect::Ray>& a,
                                                                            rt::BatchKind ka,
                                                                            const std::vector<isect::Ray>& b,
                                                                            rt::BatchKind kb) override {
    // b first: the renderer's second batch holds the rays with their own origins,
    // whose passes cost the most, and the queue hands passes out in order (the longest
    // first balances best). A pass's results do not depend on the order.
    share_.begin_batch(1);
    fi_.set_batch_kind(kb);
    std::vector<isect::Hit> hb = fi_.intersect(b);
    share_.begin_batch(0);
    fi_.set_batch_kind(ka);
    std::vector<isect::Hit> ha = fi_.intersect(a);
    share_.exchange({&ha, &hb});
    return {std::move(ha), std::move(hb)};
  }

 private:
  rt::FmppIntersector& fi_;
  SharedPasses& share_;
};

}  // namespace

rt::Intersector& RenderChips::wrap(rt::FmppIntersector& fi) {
  if (!share_) return fi;
  wrapped_ = std::make_unique<SharedIntersector>(fi, *share_);
  return *wrapped_;
}

void RenderChips::agree(const std::vector<isect::Triangle>& tris, const Config& cfg,
                        const isect::KernelOptions& ko) const {
  uint64_t h = fnv1a(tris.data(), tris.size() * sizeof(isect::Triangle));
  s_.check_same(h, "the scene's triangles");
  // The machine's size and every kAgreed kernel option (sw/isect/pass/options.h).
  const unsigned machine[2] = {cfg.blocks, cfg.words};
  const std::string options = isect::options_json(ko, isect::kAgreed).dump();
  s_.check_same(fnv1a(options.data(), options.size(), fnv1a(machine, sizeof machine)),
                "the FMPP configuration or the kernel options (plan)");
}

isect::PassShare* RenderChips::attach(const Device& dev, bool leader_works) {
  if (!s_.active()) return nullptr;
  q_ = std::make_unique<WorkQueue>(s_, leader_works);
  share_ = std::make_unique<SharedPasses>(s_, *q_, dev, leader_works);
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
                       {"exchange_wait_seconds", share_->wait_seconds()},
                       {"queue_wait_seconds", share_->ask_seconds()}};
  for (const SharedPasses::PassCost& c : share_->pass_costs()) {
    me["pass_clocks"].push_back({c.exchange, c.call, c.pass, c.clocks, c.seconds, c.turn});
  }
  const std::vector<std::string> all = s_.gather(me.dump());
  if (!s_.leader()) return nullptr;
  nlohmann::json chips = nlohmann::json::array();
  uint64_t max_clocks = 0, sum_clocks = 0, transfers = 0;
  // Every pass's clocks, by exchange, in the order of calls and of the passes' handing
  // out (the input of tools/scaling_model.py).
  std::vector<std::map<std::pair<uint64_t, uint64_t>, uint64_t>> by_exchange(share_->exchanges());
  for (const std::string& j : all) {
    chips.push_back(nlohmann::json::parse(j));
    for (const auto& c : chips.back()["pass_clocks"]) {
      by_exchange.at(c[0].get<size_t>())[{c[1].get<uint64_t>(), c[5].get<uint64_t>()}] = c[3].get<uint64_t>();
    }
    // Which passes this chip ran: (exchange, call, pass, wall seconds); its busy seconds.
    nlohmann::json& chip = chips.back();
    chip["pass_list"] = nlohmann::json::array();
    double busy = 0;
    for (const auto& c : chip["pass_clocks"]) {
      chip["pass_list"].push_back({c[0], c[1], c[2], c[4]});
      busy += c[4].get<double>();
    }
    chip["pass_seconds"] = busy;
    chip.erase("pass_clocks");
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
          {"exchanges", share_->exchanges()},
          {"pass_clocks", pass_lists(by_exchange)}};
}

}  // namespace fmpp::mpi
