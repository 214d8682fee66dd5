// The pass loop of the intersection kernels (see pass.h).
#include "sw/isect/pass/pass.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sw/isect/exact/reference.h"

namespace fmpp::isect {

void push_counted(Device& dev, const std::vector<uint64_t>& code, KernelStats* st) {
  dev.push(code);
  st->instructions += code.size();
}

namespace {

// Names the pass in the hits of its rays (Hit::pass), where the plan's passes each decide
// their own items.
void tag_pass(PassPlan& plan, size_t base, unsigned count, uint64_t pass) {
  if (!plan.shareable()) return;
  std::vector<std::pair<size_t, Hit>> res;
  plan.results(base, count, &res);
  for (auto& [index, hit] : res) {
    hit.pass = static_cast<uint32_t>(pass);
    plan.set_result(index, hit);
  }
}

}  // namespace

void run_passes(Device& dev, PassPlan& plan, const KernelOptions& opt, KernelStats* st) {
  const unsigned blocks = dev.config().blocks;
  const size_t items = plan.items();
  const uint64_t planned = (items + blocks - 1) / blocks;
  if (opt.share && !plan.shareable()) throw std::invalid_argument("this mapping's passes cannot be shared among FMPPs");
  std::vector<size_t> perm;
  if (opt.share && opt.share->devices() > 1) perm = plan.pass_order(blocks);
  if (!perm.empty() && perm.size() != planned) throw std::logic_error("PassPlan::pass_order: not one entry per pass");
  for (uint64_t turn = 0; turn < planned; ++turn) {
    const uint64_t pass = perm.empty() ? turn : perm[turn];
    const size_t base = static_cast<size_t>(pass) * blocks;
    if (opt.share && !opt.share->take(turn, pass, planned)) continue;  // another FMPP's pass
    const unsigned count = static_cast<unsigned>(std::min<size_t>(blocks, items - base));
    ++st->passes;
    std::vector<size_t> order = plan.select(base, count);

    uint64_t c0 = dev.cycles();
    plan.load(dev, base, count);
    st->load_cycles += dev.cycles() - c0;

    bool sent = plan.walk(dev, base, count, &order);
    for (size_t first = 0;;) {
      for (size_t j = first; !sent && j < order.size(); ++j) {
        send_broadcast(dev, plan, order[j], static_cast<uint32_t>(j + 1), opt, st);
      }
      sent = false;
      c0 = dev.cycles();
      bool appended = false;
      std::vector<size_t> next = plan.refine(dev, base, count, order, &appended);
      st->readback_cycles += dev.cycles() - c0;
      if (next.empty()) break;
      first = appended ? order.size() : 0;
      if (!appended) order.clear();
      order.insert(order.end(), next.begin(), next.end());
    }

    c0 = dev.cycles();
    plan.read_back(dev, base, count, order);
    st->readback_cycles += dev.cycles() - c0;
    plan.host(base, count);
    tag_pass(plan, base, count, st->passes);
    if (opt.progress) opt.progress(turn + 1, planned);
  }
  if (opt.share) opt.share->finish(plan, blocks);
}

bool GateRows::passes(const int64_t v[3]) const {
  const __int128 floor = -(static_cast<__int128>(1) << floor_bits);
  for (int i = 0; i < 3; ++i) {
    __int128 s = 0;
    for (int j = 0; j < 3; ++j) s += static_cast<__int128>(x[3 * i + j]) * v[j];
    if (s < floor) return false;
  }
  return true;
}

size_t emit_gate(Program& p, unsigned flag, unsigned save) {
  p << ins::flagop(save, map::kFlagSEL, map::kFlagSEL, lut::kA) << ins::flagop(map::kFlagSEL, flag, flag, lut::kA);
  const size_t gate = p.size();
  p << ins::flagop(map::kFlagSEL, save, save, lut::kA);
  return gate;
}

void send_broadcast(Device& dev, PassPlan& plan, size_t k, uint32_t number, const KernelOptions& opt,
                    KernelStats* st) {
  ProgramMarks marks;
  const std::vector<uint64_t>& code = plan.code(k, number, &marks);
  uint64_t c0 = dev.cycles();
  size_t pushed = code.size();
  if (marks.gate != 0 && opt.gates && marks.skip_gate) {
    if (marks.gate < 2 || marks.gate >= code.size()) throw std::logic_error("fmpp::isect: a broadcast's gate out of its code");
    for (size_t i = 0; i < code.size(); ++i) {
      if (i + 2 < marks.gate || i > marks.gate) dev.push(code[i]);
    }
    pushed = code.size() - 3;
  } else if (marks.gate != 0 && opt.gates) {
    if (marks.gate >= code.size()) throw std::logic_error("fmpp::isect: a broadcast's gate past its code");
    for (size_t i = 0; i < marks.gate; ++i) dev.push(code[i]);
    if (!dev.responders().any) {
      pushed = marks.gate + 1;
      ++st->gated;
    }
    for (size_t i = marks.gate; i < pushed; ++i) dev.push(code[i]);
  } else {
    dev.push(code);
  }
  st->instructions += pushed;
  st->compute_cycles += dev.cycles() - c0;
  st->broadcast_steps += pushed;
  st->test_steps += marks.test_steps;
  ++st->broadcasts;
  c0 = dev.cycles();
  plan.after_broadcast(dev, k);
  st->readback_cycles += dev.cycles() - c0;
}

void merge_host(const Ray& r, const std::vector<Triangle>& tris, const std::vector<int>& host, Hit* hit,
                KernelStats* st, bool certain_current) {
  if (host.empty()) return;
  if (certain_current || hit->tri < 0) {
    // Exact comparisons (no rounded t): a certified current hit is evaluated again with
    // them. If it stays the nearest it keeps its own t and bound, so that a host
    // triangle that changes no answer (a distant speck) changes no t either.
    st->host_tests += host.size() + (hit->tri >= 0 ? 1 : 0);
    const Hit h = nearest_reference_among(r, tris, host, hit->tri);
    if (!(hit->tri >= 0 && h.tri == hit->tri)) *hit = h;
    return;
  }
  // An uncertified current hit (a form that answers for other geometry, such as the
  // watertight grid) is kept as it is, and compared by its t.
  st->host_tests += host.size();
  const Hit h = nearest_reference_among(r, tris, host);
  if (h.hit() && (h.t < hit->t || (h.t == hit->t && h.tri < hit->tri))) *hit = h;
}

std::vector<int> all_triangles(const std::vector<Triangle>& tris) {
  std::vector<int> all(tris.size());
  for (size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
  return all;
}

std::vector<bool> read_overflow(Device& dev, unsigned count) {
  std::vector<bool> ovf(count, false);
  if (dev.overflow()) {
    const std::vector<bool> v = dev.read_flag_blocks(map::kFlagV, count);
    for (unsigned b = 0; b < count; ++b) ovf[b] = v[b];
  }
  return ovf;
}

void bad_broadcast_number(unsigned block, uint32_t number, size_t broadcasts) {
  throw std::logic_error("fmpp::isect: block " + std::to_string(block) + " holds broadcast number " +
                         std::to_string(number) + " of " + std::to_string(broadcasts));
}

}  // namespace fmpp::isect
