// Driver of the map_moved test (tests/map/map_moved_test.py): built inside a scratch copy
// of the repository whose map moved every instruction field and renumbered the codes, it
// runs the Verilated tiny FMPP in lockstep with the golden model - a Device with
// directed microcode first, then random accesses of every kind - and fails if RTL and
// model disagree, or if either disagrees with host arithmetic.
//
// Usage: moved_lockstep [accesses] [seed] [coverage.dat]
//   (the binary is Verilated with --prefix Vfmpp_tiny; with --coverage-user and
//   FMPP_COVERAGE, the RTL's cover points are written to coverage.dat at the end)
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "Vfmpp_tiny.h"
#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "backends/lockstep.h"
#include "tb/progen.h"
#include "backends/rtl/rtl_bus_impl.h"

namespace {

using namespace fmpp;

int failures = 0;

// The k-th flag without a fixed meaning (not SEL, C or V, wherever the map puts them).
unsigned free_flag(unsigned k) {
  for (unsigned f = 0; f < map::kNumFlags; ++f) {
    if (f == map::kFlagSEL || f == map::kFlagC || f == map::kFlagV) continue;
    if (k-- == 0) return f;
  }
  throw std::logic_error("no free flag");
}

void expect(bool ok, const std::string& what) {
  if (!ok) {
    std::fprintf(stderr, "moved_lockstep: FAIL: %s\n", what.c_str());
    ++failures;
  }
}

// Microcode through the Device: every builder, register decode and field the host uses.
void directed(Device& dev) {
  using namespace ins;
  const int32_t x = -12345, y = 67890;
  const unsigned n = 16;
  dev.write_word(0, 0, static_cast<uint32_t>(x));
  dev.write_word(0, 1, static_cast<uint32_t>(y));
  const unsigned tmp = free_flag(0), f2 = free_flag(1), f3 = free_flag(2);
  Program p;
  p << sets();
  mul(p, 2, 0, 1, n, map::kFlagSEL, tmp);  // REF, ADD, SUB, RSHIFT, MASKSET
  p.mask(0);
  p << bitcopy(3, 30, 0, 0) << lshift(4, 1) << writes(5, 0xDEADBEEF);
  p << ref(RefFn::kThrough, RefPart::kData, 0, 0x5A5A5A5A, f2) << flagop(f3, f2, f2, lut::kNotA);
  p << Instr::decode(with_imm(writes(6, 0).encode(), 0x13572468u));  // IMM patched in place
  const unsigned f4 = free_flag(3), f5 = free_flag(4);
  p << cmp(CmpFn::kThrough, CmpLt::kLt, 0, x + 1, f4);  // x < x + 1
  p << cmp(CmpFn::kAnd, CmpLt::kGe, 1, y, f4, f4);      // and y >= y
  p << cmp(CmpFn::kOr, CmpLt::kGe, 0, x + 1, f5, f2);   // f2 (0) or x >= x + 1
  dev.push(p.code());
  const int64_t want = dot_reference({x}, {y}, n);
  expect(static_cast<int32_t>(dev.read_word(0, 2)) == want,
         "mul: " + std::to_string(static_cast<int32_t>(dev.read_word(0, 2))) + ", host " + std::to_string(want));
  expect(((dev.read_word(0, 3) >> 30) & 1) == (static_cast<uint32_t>(x) & 1), "BITCOPY bit 0 to bit 30");
  expect(dev.read_word(0, 4) == static_cast<uint32_t>(y) << 1, "LSHIFT");
  expect(dev.read_word(0, 5) == 0xDEADBEEFu, "WRITES");
  expect(dev.read_word(0, 6) == 0x13572468u, "ins::with_imm");
  expect(((dev.read_flags(0) >> f3) & 1) == 1 && ((dev.read_flags(0) >> f2) & 1) == 0,
         "REF.through (no match) then FLAGOP not-a");
  expect(((dev.read_flags(0) >> f4) & 1) == 1 && ((dev.read_flags(0) >> f5) & 1) == 0,
         "CMP.through <, CMP.and >= (equal), CMP.or >=");
  const Responders r = dev.responders();
  expect(r.any && r.count == 1 && r.first == 0, "RESP after SETS");
  expect(!dev.overflow(), "STATUS.OVF");
  try {
    dev.push(add(9, 0, 0).encode() | map::kFieldX.put(1));  // a reserved field set
    expect(false, "an illegal push was accepted");
  } catch (const DeviceError& e) {
    expect(std::string(e.what()).find("ILLEGAL") != std::string::npos, std::string("error names its cause: ") + e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  const unsigned long accesses = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 20000;
  const unsigned long seed = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 1;
  try {
    const Config cfg = named_config("tiny");
    backends::RtlOptions ro;
    if (argc > 3) ro.coverage_file = argv[3];
    backends::RtlBusImpl<Vfmpp_tiny> rtl(cfg, ro);
    ModelBus model(cfg);
    backends::Lockstep ls(rtl, model, backends::LockstepOptions{});
    Device dev(ls);
    directed(dev);
    tb::ProgramGenerator gen(cfg, seed);
    for (unsigned long k = 0; k < accesses; ++k) gen.step(ls);
    ls.final_check();
    const std::string missing = gen.stats().missing();
    expect(missing.empty(), "random accesses never exercised: " + missing);
    std::printf("moved_lockstep: %lu random accesses (%llu instructions, %llu bad) in lockstep, %d failures\n",
                accesses, static_cast<unsigned long long>(gen.stats().instructions),
                static_cast<unsigned long long>(gen.stats().bad), failures);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "moved_lockstep: FAIL: %s\n", e.what());
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
