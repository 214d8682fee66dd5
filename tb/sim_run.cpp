// One fmpp-sim run (see sim_run.h).
#include "tb/sim_run.h"

#include <chrono>
#include <cstdio>
#include <random>

#include "common/util/cli_checks.h"
#include "backends/lockstep.h"
#include "tb/progen.h"
#include "backends/rtl/rtl_bus.h"
#include "backends/systemc/systemc_bus.h"

namespace fmpp::tb {
using namespace backends;
namespace {

// The RTL side of the lockstep: the Verilated model, directly or behind SystemC.
std::unique_ptr<RtlBus> make_rtl_side(const std::string& backend, const std::string& config, const RtlOptions& ro) {
  auto rtl = make_rtl_bus(config, ro);
  if (backend == "rtl") return rtl;
  if (backend == "systemc") return sc::make_systemc_rtl_bus(std::move(rtl));
  throw std::invalid_argument("backend '" + backend + "' is not one of rtl, systemc");
}

// Writes `bad` into word `word` of block `block` on the RTL side only; the model gets
// the word's current value, so the two sides stay in step in time but differ in state.
void inject_fault(RtlBus& rtl, ModelBus& model, unsigned block, unsigned word, uint32_t bad) {
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

void add_run_options(CLI::App& app, SimOptions* o) {
  app.add_option("--config", o->config, "named configuration (see --list)");
  app.add_option("--seed", o->seed, "random seed")->capture_default_str()->check(non_negative());
  app.add_option("--ops", o->ops, "bus accesses to generate")->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_option("--mode", o->mode, "lockstep mode: check (state after every entry), fast (hash), off")
      ->check(CLI::IsMember({"check", "fast", "off"}));
  app.add_option("--hash-interval", o->hash_interval, "fast mode: queue entries between state hashes")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  app.add_flag("--stress", o->stress, "random bus idle clocks and READY back-pressure (clock counts not compared)");
  CLI::Option* trace_opt = app.add_option("--trace", o->trace, "write an FST waveform to this file");
  app.add_option("--trace-start", o->trace_start, "first cycle to trace")->check(non_negative())->needs(trace_opt);
  app.add_option("--trace-end", o->trace_end, "last cycle to trace")->check(non_negative())->needs(trace_opt);
  app.add_option("--backend", o->backend, "RTL side of the lockstep: rtl (direct) or systemc (through TLM-2.0)")
      ->check(CLI::IsMember({"rtl", "systemc"}));
  auto* inject_opt = app.add_option("--inject-at", o->inject_at,
                                    "before access N, write a wrong word into the RTL only (mismatch demo)")
                         ->check(CLI::Range(uint64_t{0}, uint64_t{1} << 40));
  app.add_option("--inject-block", o->inject_block, "block of the injected word, from 0 (default: the last block)")
      ->check(non_negative())
      ->needs(inject_opt);
  app.add_option("--inject-word", o->inject_word, "word of the injected word (default 0)")
      ->check(non_negative())
      ->needs(inject_opt);
  app.add_option("--inject-value", o->inject_value, "value the RTL gets (default 0xDEADBEEF)")
      ->check(non_negative())
      ->needs(inject_opt);
  app.add_option("--random-init", o->random_init,
                 "soak: RTL powers up with random values from this seed (words too); the model is preloaded")
      ->check(CLI::Range(uint64_t{1}, uint64_t{0x7FFFFFFF}));
  app.add_flag("--max-backpressure", o->max_backpressure, "soak: with --stress, READY low 8 clocks after every response");
  app.add_flag("--storms", o->storms, "soak: bursts of 60 bad accesses in every 1000");
  app.add_option("--reset-every", o->reset_every,
                 "soak: reset both sides at random, on average once in N accesses (queue not drained)")
      ->check(CLI::Range(uint64_t{2}, uint64_t{1} << 40));
  app.add_option("--coverage-out", o->coverage_out, "coverage builds: write the Verilator coverage counts here");
}

void sync_inject(const CLI::App& app, SimOptions* o) { o->inject = app.count("--inject-at") > 0; }

SimOptions parse_run(const std::string& line) {
  SimOptions o;
  CLI::App app{"one run"};
  add_run_options(app, &o);
  try {
    app.parse(line, false);
  } catch (const CLI::ParseError& e) {
    throw std::invalid_argument("'" + line + "': " + e.what());
  }
  sync_inject(app, &o);
  return o;
}

std::string reproduce_command(const SimOptions& o) {
  std::string again = "fmpp-sim --config " + o.config + " --seed " + std::to_string(o.seed) + " --ops " +
                      std::to_string(o.ops) + " --mode check --backend " + o.backend + (o.stress ? " --stress" : "") +
                      (o.max_backpressure ? " --max-backpressure" : "") + (o.storms ? " --storms" : "") +
                      (o.random_init ? " --random-init " + std::to_string(o.random_init) : "") +
                      (o.reset_every ? " --reset-every " + std::to_string(o.reset_every) : "");
  if (o.inject) {
    const Config cfg = named_config(o.config);
    const unsigned iblock = o.inject_block < 0 ? cfg.blocks - 1 : static_cast<unsigned>(o.inject_block);
    char value[16];
    std::snprintf(value, sizeof value, "0x%08x", o.inject_value);
    again += " --inject-at " + std::to_string(o.inject_at) + " --inject-block " + std::to_string(iblock) +
             " --inject-word " + std::to_string(o.inject_word) + " --inject-value " + value;
  }
  return again;
}

namespace {

// The RTL side's options of run o, its combinations checked.
RtlOptions rtl_options(const SimOptions& o) {
  RtlOptions ro;
  ro.trace_file = o.trace;
  ro.trace_start = o.trace_start;
  ro.trace_end = o.trace_end;
  ro.stress = o.stress;
  ro.stress_seed = o.seed ^ 0x5EEDull;
  if (o.max_backpressure && !o.stress) throw std::invalid_argument("--max-backpressure needs --stress");
  if (o.reset_every && o.backend != "rtl") throw std::invalid_argument("--reset-every needs --backend rtl");
  ro.random_init = o.random_init;
  ro.max_backpressure = o.max_backpressure;
  ro.coverage_file = o.coverage_out;
  return ro;
}

// The run's summary line.
std::string summary_line(const SimOptions& o, const Config& cfg, const GenStats& st, const Lockstep& lock,
                         uint64_t cycles, const SimResult& res) {
  char line[1024];
  std::snprintf(
      line, sizeof line,
      "config=%s blocks=%u words=%u backend=%s seed=%llu mode=%s%s accesses=%llu instructions=%llu entries=%llu "
      "cycles=%llu state_checks=%llu bad_accesses=%llu resets=%llu mismatches=%llu seconds=%.1f",
      o.config.c_str(), cfg.blocks, cfg.words, o.backend.c_str(), static_cast<unsigned long long>(o.seed),
      o.mode.c_str(),
      (std::string(o.stress ? "+stress" : "") + (o.max_backpressure ? "+maxbp" : "") + (o.storms ? "+storms" : "") +
       (o.random_init ? "+randinit" : "") + (o.reset_every ? "+resets" : ""))
          .c_str(),
      static_cast<unsigned long long>(st.accesses), static_cast<unsigned long long>(st.instructions),
      static_cast<unsigned long long>(lock.entries()), static_cast<unsigned long long>(cycles),
      static_cast<unsigned long long>(lock.state_checks()), static_cast<unsigned long long>(st.bad),
      static_cast<unsigned long long>(lock.resets()), static_cast<unsigned long long>(res.mismatches), res.seconds);
  return line;
}

}  // namespace

SimResult run_sim(const SimOptions& o) {
  check_trace_window(o.trace_start, o.trace_end);
  check_trace_file(o.trace);
  const Config cfg = named_config(o.config);
  const RtlOptions ro = rtl_options(o);
  const unsigned iblock = o.inject_block < 0 ? cfg.blocks - 1 : static_cast<unsigned>(o.inject_block);
  if (o.inject && (o.inject_at >= o.ops || iblock >= cfg.blocks || o.inject_word >= cfg.words)) {
    throw std::invalid_argument("--inject-at " + std::to_string(o.inject_at) + " block " + std::to_string(iblock) +
                                " word " + std::to_string(o.inject_word) + " is outside the run (" +
                                std::to_string(o.ops) + " accesses, " + cfg.str() + ")");
  }
  auto rtl = make_rtl_side(o.backend, o.config, ro);
  ModelBus model(cfg);
  if (o.random_init != 0) {
    // The words survive the reset with their power-up values: start the model there.
    const ArchState s = rtl->state();
    for (unsigned b = 0; b < cfg.blocks; ++b) {
      for (unsigned w = 0; w < cfg.words; ++w) model.preload_word(b, w, s.word(b, w));
    }
  }
  LockstepOptions lo;
  lo.mode = parse_lockstep_mode(o.mode);
  lo.hash_interval = o.hash_interval;
  lo.compare_cycles = !o.stress;
  Lockstep lock(*rtl, model, lo);
  ProgramGenerator gen(cfg, o.seed);
  gen.set_storms(o.storms);

  SimResult res;
  const auto t0 = std::chrono::steady_clock::now();
  uint64_t i = 0;
  try {
    std::mt19937_64 reset_rng(o.seed ^ 0xBE5E7ull);
    for (; i < o.ops; ++i) {
      if (o.inject && i == o.inject_at) inject_fault(*rtl, model, iblock, o.inject_word, o.inject_value);
      if (o.reset_every && reset_rng() % o.reset_every == 0) lock.reset();
      gen.step(lock);
    }
    lock.final_check();
  } catch (const LockstepMismatch& e) {
    res.mismatches = 1;
    res.report = e.what();
    res.mismatch_access = i;
    res.mismatch_instruction = gen.stats().instructions;
  }
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const GenStats& st = gen.stats();
  res.accesses = st.accesses;
  res.instructions = st.instructions;
  res.cycles = rtl->cycles();
  res.line = summary_line(o, cfg, st, lock, rtl->cycles(), res);
  if (res.mismatches && !o.trace.empty()) {
    // The harness dumps clock low at 10c and the rising edge at 10c + 5 (backends/rtl/rtl_bus_impl.h),
    // so the state after the edge that made cycles() = c is visible from 10c - 5.
    const uint64_t c = lock.last_entry_cycle();
    res.waveform = "waveform: " + o.trace + ", the entry executed at the clock edge at t = " +
                   std::to_string(c ? 10 * c - 5 : 0) + " (cycle " + std::to_string(c) + ")";
  }
  res.missing = st.missing();
  res.coverage_fail = !res.missing.empty() && o.ops >= 20000;
  return res;
}

}  // namespace fmpp::tb
