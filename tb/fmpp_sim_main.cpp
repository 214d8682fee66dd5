// fmpp-sim: constrained-random RTL regression of one FMPP configuration.
//
// Drives the Verilated RTL through its AXI4-Lite port with a seeded random
// program and runs every access on the golden model in lockstep. Prints one
// summary line and exits 0 only if nothing differed, no RTL assertion fired and
// every opcode and error cause was exercised.
//
//   fmpp-sim --config small --seed 1 --ops 100000 --mode check
//   fmpp-sim --config large --mode fast --hash-interval 2000 --stress
//   fmpp-sim --config small --ops 500 --trace sim.fst
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>

#include "tb/lockstep.h"
#include "tb/progen.h"
#include "tb/rtl_bus.h"

using namespace fmpp;

int main(int argc, char** argv) {
  CLI::App app{"FMPP RTL regression: random programs, RTL in lockstep with the golden model"};
  std::string config = "small";
  uint64_t seed = 1;
  uint64_t ops = 10000;
  std::string mode = "check";
  uint64_t hash_interval = 4096;
  bool stress = false;
  std::string trace;
  uint64_t trace_start = 0, trace_end = ~0ull;
  bool list = false;
  app.add_option("--config", config, "named configuration (see --list)");
  app.add_option("--seed", seed, "random seed");
  app.add_option("--ops", ops, "bus accesses to generate")->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_option("--mode", mode, "lockstep mode: check (state after every entry), fast (hash), off")
      ->check(CLI::IsMember({"check", "fast", "off"}));
  app.add_option("--hash-interval", hash_interval, "fast mode: queue entries between state hashes")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_flag("--stress", stress, "random bus idle clocks and READY back-pressure (clock counts not compared)");
  app.add_option("--trace", trace, "write an FST waveform to this file");
  app.add_option("--trace-start", trace_start, "first cycle to trace");
  app.add_option("--trace-end", trace_end, "last cycle to trace");
  app.add_flag("--list", list, "list the built configurations and exit");
  CLI11_PARSE(app, argc, argv);

  if (list) {
    for (const auto& n : tb::rtl_configs()) std::printf("%s %s\n", n.c_str(), named_config(n).str().c_str());
    return 0;
  }

  try {
    const Config cfg = named_config(config);
    tb::RtlOptions ro;
    ro.trace_file = trace;
    ro.trace_start = trace_start;
    ro.trace_end = trace_end;
    ro.stress = stress;
    ro.stress_seed = seed ^ 0x5EEDull;
    auto rtl = tb::make_rtl_bus(config, ro);
    ModelBus model(cfg);
    tb::LockstepOptions lo;
    lo.mode = tb::parse_lockstep_mode(mode);
    lo.hash_interval = hash_interval;
    lo.compare_cycles = !stress;
    tb::Lockstep lock(*rtl, model, lo);
    tb::ProgramGenerator gen(cfg, seed);

    const auto t0 = std::chrono::steady_clock::now();
    uint64_t mismatches = 0;
    std::string report;
    try {
      for (uint64_t i = 0; i < ops; ++i) gen.step(lock);
      lock.final_check();
    } catch (const tb::LockstepMismatch& e) {
      mismatches = 1;
      report = e.what();
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const tb::GenStats& st = gen.stats();
    std::printf(
        "config=%s blocks=%u words=%u seed=%llu mode=%s%s accesses=%llu instructions=%llu entries=%llu "
        "cycles=%llu state_checks=%llu bad_accesses=%llu mismatches=%llu seconds=%.1f\n",
        config.c_str(), cfg.blocks, cfg.words, static_cast<unsigned long long>(seed), mode.c_str(),
        stress ? "+stress" : "", static_cast<unsigned long long>(st.accesses),
        static_cast<unsigned long long>(st.instructions), static_cast<unsigned long long>(lock.entries()),
        static_cast<unsigned long long>(rtl->cycles()), static_cast<unsigned long long>(lock.state_checks()),
        static_cast<unsigned long long>(st.bad), static_cast<unsigned long long>(mismatches), secs);
    if (mismatches) {
      std::fprintf(stderr, "%s\nreproduce: fmpp-sim --config %s --seed %llu --ops %llu --mode check%s\n",
                   report.c_str(), config.c_str(), static_cast<unsigned long long>(seed),
                   static_cast<unsigned long long>(ops), stress ? " --stress" : "");
      return 1;
    }
    const std::string missing = st.missing();
    if (!missing.empty() && ops >= 20000) {
      std::fprintf(stderr, "coverage hole: never exercised: %s\n", missing.c_str());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-sim: %s\n", e.what());
    return 2;
  }
}
