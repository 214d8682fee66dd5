// Architectural state snapshots shared by the RTL extractor and the golden model,
// and their comparison (the lockstep checker's "differing state" report).
#include <algorithm>
#include <array>
#include <cstdio>
#include <sstream>

#include "backends/rtl/rtl_bus.h"

namespace fmpp::backends {

uint64_t ArchState::hash() const {
  return state_digest(
      cfg, [this](unsigned b, unsigned w) { return word(b, w); }, [this](unsigned b) { return flags[b]; }, mask);
}

namespace {

// kSpread[b]: bit i of b moved to bit 8 i (one byte per lane of a group of eight).
constexpr std::array<uint64_t, 256> spread_table() {
  std::array<uint64_t, 256> t{};
  for (unsigned b = 0; b < 256; ++b) {
    for (unsigned i = 0; i < 8; ++i) t[b] |= uint64_t{(b >> i) & 1u} << (8 * i);
  }
  return t;
}
constexpr std::array<uint64_t, 256> kSpread = spread_table();

}  // namespace

void planes_to_words(const uint64_t* planes, unsigned nplanes, uint32_t out[64]) {
  std::fill(out, out + 64, 0u);
  // Eight planes by eight lanes at a time: byte i of acc gathers the eight planes' bits of
  // lane 8 c + i, which then become bits 8 g .. 8 g + 7 of that lane's word.
  for (unsigned g = 0; g * 8 < nplanes; ++g) {
    for (unsigned c = 0; c < 8; ++c) {
      uint64_t acc = 0;
      for (unsigned j = 0; j < 8; ++j) acc |= kSpread[(planes[8 * g + j] >> (8 * c)) & 0xffu] << j;
      for (unsigned i = 0; i < 8; ++i) out[8 * c + i] |= static_cast<uint32_t>((acc >> (8 * i)) & 0xffu) << (8 * g);
    }
  }
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
