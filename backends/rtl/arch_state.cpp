// Architectural state snapshots shared by the RTL extractor and the golden model,
// and their comparison (the lockstep checker's "differing state" report).
#include <cstdio>
#include <sstream>

#include "backends/rtl/rtl_bus.h"

namespace fmpp::backends {

uint64_t ArchState::hash() const {
  return state_digest(
      cfg, [this](unsigned b, unsigned w) { return word(b, w); }, [this](unsigned b) { return flags[b]; }, mask);
}

ArchState model_state(const ModelBus& m) {
  ArchState s;
  const Machine& mc = m.machine();
  s.cfg = mc.config();
  s.words.resize(size_t{s.cfg.blocks} * s.cfg.words);
  s.flags.resize(s.cfg.blocks);
  for (unsigned b = 0; b < s.cfg.blocks; ++b) {
    for (unsigned w = 0; w < s.cfg.words; ++w) s.words[size_t{b} * s.cfg.words + w] = mc.word(b, w);
    s.flags[b] = mc.flags(b);
  }
  s.mask = mc.mask();
  s.instret = mc.instret();
  s.gap = m.gap();
  s.error = m.error();
  s.queue_level = static_cast<unsigned>(m.queue_level());
  return s;
}

std::string diff_states(const ArchState& rtl, const ArchState& model, unsigned max_diffs) {
  std::ostringstream o;
  unsigned n = 0;
  char buf[160];
  auto line = [&](const char* text) {
    if (n++ < max_diffs) o << "  " << text << "\n";
  };
  for (unsigned b = 0; b < rtl.cfg.blocks; ++b) {
    for (unsigned w = 0; w < rtl.cfg.words; ++w) {
      if (rtl.word(b, w) != model.word(b, w)) {
        std::snprintf(buf, sizeof buf, "block %u word %u: rtl 0x%08x model 0x%08x", b, w, rtl.word(b, w),
                      model.word(b, w));
        line(buf);
      }
    }
    if (rtl.flags[b] != model.flags[b]) {
      std::snprintf(buf, sizeof buf, "block %u flags: rtl 0x%02x model 0x%02x", b, rtl.flags[b], model.flags[b]);
      line(buf);
    }
  }
  if (rtl.mask != model.mask) {
    std::snprintf(buf, sizeof buf, "mask: rtl 0x%08x model 0x%08x", rtl.mask, model.mask);
    line(buf);
  }
  if (rtl.instret != model.instret) {
    std::snprintf(buf, sizeof buf, "instret: rtl %llu model %llu", static_cast<unsigned long long>(rtl.instret),
                  static_cast<unsigned long long>(model.instret));
    line(buf);
  }
  if (rtl.gap != model.gap) {
    std::snprintf(buf, sizeof buf, "CTRL.GAP: rtl %u model %u", rtl.gap, model.gap);
    line(buf);
  }
  if (!(rtl.error == model.error)) {
    std::snprintf(buf, sizeof buf, "ERROR: rtl 0x%016llx model 0x%016llx", static_cast<unsigned long long>(rtl.error.reg()),
                  static_cast<unsigned long long>(model.error.reg()));
    line(buf);
  }
  if (rtl.queue_level != model.queue_level) {
    std::snprintf(buf, sizeof buf, "queue level: rtl %u model %u", rtl.queue_level, model.queue_level);
    line(buf);
  }
  if (n > max_diffs) o << "  ... " << (n - max_diffs) << " more differences\n";
  return o.str();
}

}  // namespace fmpp::backends
