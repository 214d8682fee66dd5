// libFuzzer target: the golden model's bus (fmpp::ModelBus) under random access
// sequences. The input picks a small configuration, then accesses: read or write, an
// address near a register or inside a window (or anywhere), data and byte strobes.
// Checked after every access: the response is OKAY or SLVERR, the clock never goes
// back, the queue never holds more than its depth, ID and CONFIG always read their
// constants, and a second model fed the same accesses answers exactly the same (no
// state outside the model, no uninitialized reads). The model throwing is a finding.
#include <cstdint>
#include <cstring>

#include "fmpp/model_bus.h"

namespace {

struct Input {
  const uint8_t* p;
  size_t n;
  template <class T>
  T take() {
    T v{};
    const size_t k = n < sizeof(T) ? n : sizeof(T);
    std::memcpy(&v, p, k);
    p += k;
    n -= k;
    return v;
  }
};

uint32_t address(Input& in, const fmpp::Config& cfg) {
  using namespace fmpp::map;
  const uint8_t kind = in.take<uint8_t>();
  const uint32_t off = in.take<uint32_t>();
  switch (kind % 5) {
    case 0: return (off % 0x80) & ~7u;                                                   // registers
    case 1: return kWinPlanesBase + (off % (cfg.tiles() * 8 * kNumFlags + 64)) * 8 % kWinPlanesSize;
    case 2: return kWinFlagsBase + (off % (cfg.blocks * 8 + 64)) % kWinFlagsSize;
    case 3: return kWinWordsBase + ((off % (cfg.blocks + 2)) << cfg.word_shift()) + (off >> 24) * 4 % 512;
    default: return off;                                                                 // anywhere
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Input in{data, size};
  const uint8_t shape = in.take<uint8_t>();
  const fmpp::Config cfg{1u + (shape & 0x7F) % 70u, 2u * (1u + (shape >> 4) % 8u)};
  fmpp::ModelBus a(cfg), b(cfg);
  uint64_t last_cycles = 0;
  for (int k = 0; k < 4000 && in.n > 0; ++k) {
    const uint8_t op = in.take<uint8_t>();
    const uint32_t addr = address(in, cfg);
    if (op & 1) {
      const uint64_t v = in.take<uint64_t>();
      const uint8_t strb = (op & 2) ? 0xFF : in.take<uint8_t>();
      const fmpp::Resp ra = a.write(addr, v, strb), rb = b.write(addr, v, strb);
      if (ra != rb || (ra != fmpp::Resp::kOkay && ra != fmpp::Resp::kSlvErr)) __builtin_trap();
    } else {
      uint64_t va = 0, vb = 0;
      const fmpp::Resp ra = a.read(addr, &va), rb = b.read(addr, &vb);
      if (ra != rb || va != vb || (ra != fmpp::Resp::kOkay && ra != fmpp::Resp::kSlvErr)) __builtin_trap();
      if (ra == fmpp::Resp::kOkay && addr == fmpp::map::kRegId) {
        const uint64_t id = (uint64_t{fmpp::map::kMagic} << 32) | (uint64_t{fmpp::map::kVersionMajor} << 16) |
                            fmpp::map::kVersionMinor;
        if (va != id) __builtin_trap();
      }
      if (ra == fmpp::Resp::kOkay && addr == fmpp::map::kRegConfig) {
        if ((va & 0xFFFFFFFFu) != cfg.blocks || ((va >> 32) & 0xFF) != cfg.words) __builtin_trap();
      }
    }
    if (a.cycles() < last_cycles || a.cycles() != b.cycles()) __builtin_trap();
    last_cycles = a.cycles();
    if (a.queue_level() > fmpp::map::kQueueDepth) __builtin_trap();
  }
  return 0;
}
