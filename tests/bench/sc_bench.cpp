// Benchmarks of the SystemC TLM-2.0 platform (backends/systemc/) against the direct drivers
// (figures go to docs/perf.md, never asserted). Each pair runs the same access
// sequence on the same configuration, once on the direct Bus and once through
// initiator socket -> b_transport -> target -> the same kind of Bus:
//   - Push: instruction pushes of the kernel mix, one per clock (as BM_RtlMix);
//   - Program: the regression's random programs (reads, window writes, errors, GAP);
//   - the model rows isolate the SystemC cost per access, which the RTL rows hide;
//     systemc_model_sync hands the time to the SystemC kernel (sc_start) after every
//     access instead of once per 10 us quantum.
//
//   build/fmpp_sc_bench
//   build/fmpp_sc_bench --benchmark_filter='Program/.*/medium'
#include <benchmark/benchmark.h>

#include <memory>
#include <random>

#include "fmpp/model_bus.h"
#include "tb/progen.h"
#include "backends/rtl/rtl_bus.h"
#include "backends/systemc/systemc_bus.h"
#include "tests/bench/kernel_mix.h"

namespace {

using namespace fmpp;
using namespace fmpp::ins;
using fmpp::bench::kernel_mix;

enum class Backend { kRtl, kSystemCRtl, kModel, kSystemCModel, kSystemCModelSync };

std::unique_ptr<Bus> make(Backend b, const std::string& config) {
  switch (b) {
    case Backend::kRtl: return backends::make_rtl_bus(config);
    case Backend::kSystemCRtl: return sc::make_systemc_bus(backends::make_rtl_bus(config));
    case Backend::kModel: return std::make_unique<ModelBus>(named_config(config));
    case Backend::kSystemCModel: return sc::make_systemc_bus(std::make_unique<ModelBus>(named_config(config)));
    case Backend::kSystemCModelSync: {
      sc::ScOptions opt;
      opt.quantum_ps = 0;  // sc_start() after every access
      return sc::make_systemc_bus(std::make_unique<ModelBus>(named_config(config)), opt);
    }
  }
  return nullptr;
}


void BM_Push(benchmark::State& state, Backend backend, const char* config) {
  auto bus = make(backend, config);
  const auto prog = kernel_mix(named_config(config).words, 4096, 1);
  size_t i = 0;
  const uint64_t c0 = bus->cycles();
  for (auto _ : state) {
    bus->write(map::kRegQueue, prog[i]);
    i = (i + 1) & 4095;
  }
  state.counters["accesses_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["cycles_per_s"] =
      benchmark::Counter(static_cast<double>(bus->cycles() - c0), benchmark::Counter::kIsRate);
}

void BM_Program(benchmark::State& state, Backend backend, const char* config) {
  auto bus = make(backend, config);
  tb::ProgramGenerator gen(named_config(config), 1);
  for (auto _ : state) gen.step(*bus);
  state.counters["accesses_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

#define FMPP_SC_PAIR(fn, config)                                                                        \
  BENCHMARK_CAPTURE(fn, rtl/config, Backend::kRtl, #config)->Unit(benchmark::kMicrosecond);            \
  BENCHMARK_CAPTURE(fn, systemc/config, Backend::kSystemCRtl, #config)->Unit(benchmark::kMicrosecond); \
  BENCHMARK_CAPTURE(fn, model/config, Backend::kModel, #config)->Unit(benchmark::kMicrosecond);        \
  BENCHMARK_CAPTURE(fn, systemc_model/config, Backend::kSystemCModel, #config)->Unit(benchmark::kMicrosecond)

FMPP_SC_PAIR(BM_Push, small);
FMPP_SC_PAIR(BM_Push, medium);
FMPP_SC_PAIR(BM_Program, small);
FMPP_SC_PAIR(BM_Program, medium);
BENCHMARK_CAPTURE(BM_Push, systemc_model_sync/small, Backend::kSystemCModelSync, "small")
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
