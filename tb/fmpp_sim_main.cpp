// fmpp-sim: constrained-random RTL regression of one FMPP configuration.
//
// Drives the Verilated RTL through its AXI4-Lite port with a seeded random
// program and runs every access on the golden model in lockstep. Prints one
// summary line and exits 0 only if nothing differed, no RTL assertion fired and,
// for runs of 20,000 accesses or more, every opcode and error cause was exercised
// (a shorter run reports what it missed on stderr but does not fail for it).
//
// --backend systemc sends the RTL side's accesses through the SystemC TLM-2.0
// platform (tb/sc/: initiator socket -> b_transport -> target -> RTL) instead of
// driving the RTL directly; the golden model stays the reference.
// --inject-at N demonstrates a mismatch: before access N it writes a wrong value
// into one word of the RTL only (the model gets the word's current value, so both
// sides spend the same clocks) and the lockstep must report it (docs/debugging.md).
//
//   fmpp-sim --config small --seed 1 --ops 100000 --mode check
//   fmpp-sim --config large --mode fast --hash-interval 2000 --stress
//   fmpp-sim --config small --ops 500 --trace sim.fst
//   fmpp-sim --config small --backend systemc --ops 100000
//   fmpp-sim --config odd --ops 3000 --inject-at 2000 --trace inject.fst
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>

#include "sw/util/cli_checks.h"
#include "tb/lockstep.h"
#include "tb/progen.h"
#include "tb/rtl_bus.h"
#include "tb/sc/systemc_bus.h"

using namespace fmpp;

namespace {

// The RTL side of the lockstep: the Verilated model, directly or behind SystemC.
std::unique_ptr<tb::RtlBus> make_backend(const std::string& backend, const std::string& config,
                                         const tb::RtlOptions& ro) {
  auto rtl = tb::make_rtl_bus(config, ro);
  if (backend == "rtl") return rtl;
  if (backend == "systemc") return sc::make_systemc_rtl_bus(std::move(rtl));
  throw std::invalid_argument("backend '" + backend + "' is not one of rtl, systemc");
}

// Writes `bad` into word `word` of block `block` on the RTL side only; the model gets
// the word's current value, so the two sides stay in step in time but differ in state.
void inject_fault(tb::RtlBus& rtl, ModelBus& model, unsigned block, unsigned word, uint32_t bad) {
  const Config& c = model.config();
  const uint32_t addr = map::kWinWordsBase + (block << c.word_shift()) + (word << 3);
  const uint32_t keep = model.machine().word(block, word);
  const uint32_t wrong = bad != keep ? bad : ~bad;
  std::fprintf(stderr, "inject: block %u word %u: RTL <- 0x%08x, model <- 0x%08x (its value now)\n", block, word,
               wrong, keep);
  const Resp r = rtl.write(addr, wrong, 0x0F);
  const Resp m = model.write(addr, keep, 0x0F);
  if (r != Resp::kOkay || m != Resp::kOkay) throw std::logic_error("inject: the word write was refused");
}

}  // namespace

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
  std::string backend = "rtl";
  uint64_t inject_at = 0;
  int64_t inject_block = -1;
  unsigned inject_word = 0;
  uint32_t inject_value = 0xDEADBEEF;
  uint64_t random_init = 0;
  bool max_backpressure = false, storms = false;
  uint64_t reset_every = 0;
  std::string coverage_out;
  app.add_option("--config", config, "named configuration (see --list)");
  app.add_option("--seed", seed, "random seed")->capture_default_str()->check(non_negative());
  app.add_option("--ops", ops, "bus accesses to generate")->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_option("--mode", mode, "lockstep mode: check (state after every entry), fast (hash), off")
      ->check(CLI::IsMember({"check", "fast", "off"}));
  app.add_option("--hash-interval", hash_interval, "fast mode: queue entries between state hashes")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_flag("--stress", stress, "random bus idle clocks and READY back-pressure (clock counts not compared)");
  CLI::Option* trace_opt = app.add_option("--trace", trace, "write an FST waveform to this file");
  app.add_option("--trace-start", trace_start, "first cycle to trace")->check(non_negative())->needs(trace_opt);
  app.add_option("--trace-end", trace_end, "last cycle to trace")->check(non_negative())->needs(trace_opt);
  app.add_flag("--list", list, "list the built configurations and exit");
  app.add_option("--backend", backend, "RTL side of the lockstep: rtl (direct) or systemc (through TLM-2.0)")
      ->check(CLI::IsMember({"rtl", "systemc"}));
  auto* inject_opt = app.add_option("--inject-at", inject_at,
                                    "before access N, write a wrong word into the RTL only (mismatch demo)")
                         ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 40));
  app.add_option("--inject-block", inject_block, "block of the injected word, from 0 (default: the last block)")
      ->check(non_negative())
      ->needs(inject_opt);
  app.add_option("--inject-word", inject_word, "word of the injected word (default 0)")
      ->check(non_negative())
      ->needs(inject_opt);
  app.add_option("--inject-value", inject_value, "value the RTL gets (default 0xDEADBEEF)")
      ->check(non_negative())
      ->needs(inject_opt);
  app.add_option("--random-init", random_init,
                 "soak: RTL powers up with random values from this seed (words too); the model is preloaded")
      ->check(CLI::Range(uint64_t{1}, uint64_t{0x7FFFFFFF}));
  app.add_flag("--max-backpressure", max_backpressure, "soak: with --stress, READY low 8 clocks after every response");
  app.add_flag("--storms", storms, "soak: bursts of 60 bad accesses in every 1000");
  app.add_option("--reset-every", reset_every,
                 "soak: reset both sides at random, on average once in N accesses (queue not drained)")
      ->check(CLI::Range(uint64_t{2}, uint64_t{1} << 40));
  app.add_option("--coverage-out", coverage_out, "coverage builds: write the Verilator coverage counts here");
  CLI11_PARSE(app, argc, argv);

  if (list) {
    for (const auto& n : tb::rtl_configs()) std::printf("%s %s\n", n.c_str(), named_config(n).str().c_str());
    return 0;
  }

  try {
    check_trace_window(trace_start, trace_end);
    check_trace_file(trace);
    const Config cfg = named_config(config);
    tb::RtlOptions ro;
    ro.trace_file = trace;
    ro.trace_start = trace_start;
    ro.trace_end = trace_end;
    ro.stress = stress;
    ro.stress_seed = seed ^ 0x5EEDull;
    if (max_backpressure && !stress) throw std::invalid_argument("--max-backpressure needs --stress");
    if (reset_every && backend != "rtl") throw std::invalid_argument("--reset-every needs --backend rtl");
    ro.random_init = random_init;
    ro.max_backpressure = max_backpressure;
    ro.coverage_file = coverage_out;
    const bool inject = inject_opt->count() > 0;
    const unsigned iblock = inject_block < 0 ? cfg.blocks - 1 : static_cast<unsigned>(inject_block);
    if (inject && (inject_at >= ops || iblock >= cfg.blocks || inject_word >= cfg.words)) {
      throw std::invalid_argument("--inject-at " + std::to_string(inject_at) + " block " + std::to_string(iblock) +
                                  " word " + std::to_string(inject_word) + " is outside the run (" +
                                  std::to_string(ops) + " accesses, " + cfg.str() + ")");
    }
    auto rtl = make_backend(backend, config, ro);
    ModelBus model(cfg);
    if (random_init != 0) {
      // The words survive the reset with their power-up values: start the model there.
      const tb::ArchState s = rtl->state();
      for (unsigned b = 0; b < cfg.blocks; ++b) {
        for (unsigned w = 0; w < cfg.words; ++w) model.preload_word(b, w, s.word(b, w));
      }
    }
    tb::LockstepOptions lo;
    lo.mode = tb::parse_lockstep_mode(mode);
    lo.hash_interval = hash_interval;
    lo.compare_cycles = !stress;
    tb::Lockstep lock(*rtl, model, lo);
    tb::ProgramGenerator gen(cfg, seed);
    gen.set_storms(storms);

    const auto t0 = std::chrono::steady_clock::now();
    uint64_t mismatches = 0;
    std::string report;
    try {
      std::mt19937_64 reset_rng(seed ^ 0xBE5E7ull);
      for (uint64_t i = 0; i < ops; ++i) {
        if (inject && i == inject_at) inject_fault(*rtl, model, iblock, inject_word, inject_value);
        if (reset_every && reset_rng() % reset_every == 0) lock.reset();
        gen.step(lock);
      }
      lock.final_check();
    } catch (const tb::LockstepMismatch& e) {
      mismatches = 1;
      report = e.what();
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const tb::GenStats& st = gen.stats();
    std::printf(
        "config=%s blocks=%u words=%u backend=%s seed=%llu mode=%s%s accesses=%llu instructions=%llu entries=%llu "
        "cycles=%llu state_checks=%llu bad_accesses=%llu resets=%llu mismatches=%llu seconds=%.1f\n",
        config.c_str(), cfg.blocks, cfg.words, backend.c_str(), static_cast<unsigned long long>(seed), mode.c_str(),
        (std::string(stress ? "+stress" : "") + (max_backpressure ? "+maxbp" : "") + (storms ? "+storms" : "") +
         (random_init ? "+randinit" : "") + (reset_every ? "+resets" : "")).c_str(), static_cast<unsigned long long>(st.accesses),
        static_cast<unsigned long long>(st.instructions), static_cast<unsigned long long>(lock.entries()),
        static_cast<unsigned long long>(rtl->cycles()), static_cast<unsigned long long>(lock.state_checks()),
        static_cast<unsigned long long>(st.bad), static_cast<unsigned long long>(lock.resets()),
        static_cast<unsigned long long>(mismatches), secs);
    if (mismatches) {
      std::string again = " --backend " + backend + (stress ? " --stress" : "") +
                          (max_backpressure ? " --max-backpressure" : "") + (storms ? " --storms" : "") +
                          (random_init ? " --random-init " + std::to_string(random_init) : "") +
                          (reset_every ? " --reset-every " + std::to_string(reset_every) : "");
      if (inject) {
        char value[16];
        std::snprintf(value, sizeof value, "0x%08x", inject_value);
        again += " --inject-at " + std::to_string(inject_at) + " --inject-block " + std::to_string(iblock) +
                 " --inject-word " + std::to_string(inject_word) + " --inject-value " + value;
      }
      std::fprintf(stderr, "%s\nreproduce: fmpp-sim --config %s --seed %llu --ops %llu --mode check%s\n",
                   report.c_str(), config.c_str(), static_cast<unsigned long long>(seed),
                   static_cast<unsigned long long>(ops), again.c_str());
      if (!trace.empty()) {
        // The harness dumps clock low at 10c and the rising edge at 10c + 5 (tb/rtl_bus_impl.h),
        // so the state after the edge that made cycles() = c is visible from 10c - 5.
        const uint64_t c = lock.last_entry_cycle();
        std::fprintf(stderr, "waveform: %s, the entry executed at the clock edge at t = %llu (cycle %llu)\n",
                     trace.c_str(), static_cast<unsigned long long>(c ? 10 * c - 5 : 0),
                     static_cast<unsigned long long>(c));
      }
      return 1;
    }
    const std::string missing = st.missing();
    if (!missing.empty()) {
      std::fprintf(stderr, "coverage hole: never exercised: %s%s\n", missing.c_str(),
                   ops >= 20000 ? "" : " (not an error below 20000 accesses)");
      if (ops >= 20000) return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-sim: %s\n", e.what());
    return 2;
  }
}
