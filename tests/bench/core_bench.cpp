// Benchmarks of the FMPP core (figures go to docs/perf.md, never asserted):
//   - golden model: block-instructions per second, per instruction kind and size;
//   - Verilated RTL: clock cycles and block-cycles per second at 1024 and 4096 blocks;
//   - lockstep: the cost of checking and fast mode over an unchecked RTL run.
//
//   build/fmpp_core_bench --benchmark_filter=Model
//   build/fmpp_core_bench --benchmark_filter='Rtl|Lockstep'
#include <benchmark/benchmark.h>

#include <random>

#include "fmpp/machine.h"
#include "fmpp/model_bus.h"
#include "backends/lockstep.h"
#include "tb/progen.h"
#include "backends/rtl/rtl_bus.h"
#include "tests/bench/kernel_mix.h"

namespace {

using namespace fmpp;
using namespace fmpp::ins;
using fmpp::bench::kernel_mix;

void BM_ModelInstr(benchmark::State& state, Instr instr) {
  Machine m(Config{static_cast<unsigned>(state.range(0)), 32});
  m.execute(sets().encode());
  const uint64_t raw = instr.encode();
  for (auto _ : state) m.execute(raw);
  state.counters["block_instr_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * state.range(0), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_ModelInstr, add, add(3, 1, 2))->Arg(4096)->Arg(65536);
BENCHMARK_CAPTURE(BM_ModelInstr, sub, sub(3, 1, 2, 5))->Arg(4096)->Arg(65536);
BENCHMARK_CAPTURE(BM_ModelInstr, rshift, rshift(3, 3))->Arg(4096)->Arg(65536);
BENCHMARK_CAPTURE(BM_ModelInstr, func, func(FuncFn::kXor, 3, 1, 2))->Arg(4096)->Arg(65536);
BENCHMARK_CAPTURE(BM_ModelInstr, ref, ref(RefFn::kAnd, RefPart::kData, 4, 1, 1, 0))->Arg(4096)->Arg(65536);
BENCHMARK_CAPTURE(BM_ModelInstr, writes, writes(5, 0x1234))->Arg(4096)->Arg(65536);
BENCHMARK_CAPTURE(BM_ModelInstr, flagop, flagop(2, 1, 0, lut::kAnd))->Arg(4096)->Arg(65536);

// The kernel mix through the model's bus (queue timing and decode included).
void BM_ModelBusMix(benchmark::State& state) {
  const unsigned blocks = static_cast<unsigned>(state.range(0));
  ModelBus bus(Config{blocks, 32});
  const auto prog = kernel_mix(32, 4096, 1);
  size_t i = 0;
  for (auto _ : state) {
    bus.write(map::kRegQueue, prog[i]);
    i = (i + 1) & 4095;
  }
  state.counters["block_instr_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * blocks, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ModelBusMix)->Arg(1024)->Arg(4096)->Arg(65536);

// The Verilated RTL running the kernel mix, one push per clock.
void BM_RtlMix(benchmark::State& state, const char* config) {
  auto rtl = backends::make_rtl_bus(config);
  const Config cfg = rtl->config();
  const auto prog = kernel_mix(cfg.words, 4096, 1);
  size_t i = 0;
  const uint64_t c0 = rtl->cycles();
  for (auto _ : state) {
    rtl->write(map::kRegQueue, prog[i]);
    i = (i + 1) & 4095;
  }
  const double cycles = static_cast<double>(rtl->cycles() - c0);
  state.counters["cycles_per_s"] = benchmark::Counter(cycles, benchmark::Counter::kIsRate);
  state.counters["block_cycles_per_s"] = benchmark::Counter(cycles * cfg.blocks, benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_RtlMix, medium, "medium")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_RtlMix, large, "large")->Unit(benchmark::kMicrosecond);

// Random regression programs: unchecked RTL, then lockstep in each mode.
void BM_Regression(benchmark::State& state, const char* config, int mode) {
  auto rtl = backends::make_rtl_bus(config);
  const Config cfg = rtl->config();
  ModelBus model(cfg);
  std::unique_ptr<backends::Lockstep> lock;
  if (mode >= 0) {
    backends::LockstepOptions lo;
    lo.mode = static_cast<backends::LockstepOptions::Mode>(mode);
    lo.hash_interval = 4096;
    lock = std::make_unique<backends::Lockstep>(*rtl, model, lo);
  }
  Bus& bus = lock ? static_cast<Bus&>(*lock) : static_cast<Bus&>(*rtl);
  tb::ProgramGenerator gen(cfg, 1);
  for (auto _ : state) gen.step(bus);
  state.counters["accesses_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_Regression, small_unchecked, "small", -1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, small_check, "small", 0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, small_fast, "small", 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, small_off, "small", 2)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, medium_unchecked, "medium", -1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, medium_check, "medium", 0)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, medium_fast, "medium", 1)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Regression, medium_off, "medium", 2)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
