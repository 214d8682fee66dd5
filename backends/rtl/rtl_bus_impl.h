// RtlBus for one Verilated configuration (V = the generated class, e.g. Vfmpp_small).
// Included only by the generated per-configuration file (backends/rtl/rtl_config.cpp.in), once per configuration.
#pragma once

#include <verilated.h>
#include <verilated_fst_c.h>
#include <verilated_syms.h>
#if VM_COVERAGE
#include <verilated_cov.h>
#endif

#include <algorithm>
#include <cstring>
#include <string>
#include <stdexcept>

#include "backends/rtl/rtl_bus.h"

namespace fmpp::backends {

// A public_flat_rd RTL variable located by scope and name; bits read little-endian.
class VarView {
 public:
  VarView() = default;
  VarView(VerilatedContext* ctx, const std::string& scope, const char* name) {
    const VerilatedScopeNameMap* scopes = ctx->scopeNameMap();
    const auto it = scopes->find(scope.c_str());
    if (it == scopes->end()) throw std::logic_error("fmpp tb: RTL scope not found: " + scope);
    const VerilatedVar* v = it->second->varFind(name);
    if (!v) throw std::logic_error("fmpp tb: RTL variable not public: " + scope + "." + name);
    data_ = static_cast<const uint8_t*>(v->datap());
    ent_ = v->entSize();
  }
  uint64_t u64(size_t elem = 0) const {
    uint64_t v = 0;
    std::memcpy(&v, data_ + elem * ent_, ent_ < 8 ? ent_ : 8);
    return ent_ < 8 ? v & ((1ull << (8 * ent_)) - 1) : v;
  }
  // 64 bits starting at bit `lsb` (a multiple of 64) of element `elem`.
  uint64_t plane64(size_t elem, size_t lsb) const {
    uint64_t v = 0;
    std::memcpy(&v, data_ + elem * ent_ + lsb / 8, 8);
    return v;
  }
  // n <= 64 bits starting at bit `lsb` of element `elem` (read within the element).
  uint64_t bits(size_t elem, size_t lsb, unsigned n) const {
    uint8_t buf[16] = {};
    const size_t first = lsb / 8;
    const size_t len = std::min<size_t>(ent_ - first, (lsb % 8 + n + 7) / 8);
    std::memcpy(buf, data_ + elem * ent_ + first, len);
    uint64_t lo = 0, hi = 0;
    std::memcpy(&lo, buf, 8);
    std::memcpy(&hi, buf + 8, 8);
    const unsigned sh = lsb % 8;
    const uint64_t v = sh ? (lo >> sh) | (hi << (64 - sh)) : lo;
    return n == 64 ? v : v & ((uint64_t{1} << n) - 1);
  }

 private:
  const uint8_t* data_ = nullptr;
  uint32_t ent_ = 0;
};

template <class V>
class RtlBusImpl final : public RtlBus {
 public:
  RtlBusImpl(const Config& cfg, const RtlOptions& opt) : cfg_(cfg), opt_(opt), rng_(opt.stress_seed) {
    if (opt.trace_start > opt.trace_end) {
      throw std::invalid_argument("trace window: first cycle " + std::to_string(opt.trace_start) +
                                  " is after the last cycle " + std::to_string(opt.trace_end));
    }
#if !VM_COVERAGE
    if (!opt.coverage_file.empty()) {
      throw std::invalid_argument("coverage file " + opt.coverage_file +
                                  ": this build has no coverage (configure with -DFMPP_COVERAGE=ON: make coverage)");
    }
#endif
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->fatalOnError(false);  // an assertion failure is reported by failure(), not abort()
    ctx_->randReset(0);         // memories start at zero, as in the golden model
    if (opt_.random_init != 0) {
      ctx_->randReset(2);       // random power-up values (the soak preloads the model with them)
      ctx_->randSeed(static_cast<int>(opt_.random_init & 0x7FFFFFFF));
    }
    ctx_->traceEverOn(!opt_.trace_file.empty());
    top_ = std::make_unique<V>(ctx_.get(), "TOP");
    if (!opt_.trace_file.empty()) {
      fst_ = std::make_unique<VerilatedFstC>();
      top_->trace(fst_.get(), 99);
      fst_->open(opt_.trace_file.c_str());
      if (!fst_->isOpen()) throw std::runtime_error(opt_.trace_file + ": cannot open the waveform file");
    }
    const std::string arr = "TOP.fmpp_top.u_array";
    const std::string slv = "TOP.fmpp_top.u_slave";
    const std::string err = slv + ".u_err";
    for (unsigned t = 0; t < cfg_.tiles(); ++t) {
      const std::string tile = arr + ".g_tile[" + std::to_string(t) + "].u_tile";
      const unsigned lanes = std::min(map::kLaneW, cfg_.blocks - t * map::kLaneW);
      tiles_.push_back(Tile{VarView(ctx_.get(), tile, "mem_q"), VarView(ctx_.get(), tile, "flag_q"), lanes});
    }
    mask_ = VarView(ctx_.get(), arr, "mask_q");
    instret_ = VarView(ctx_.get(), arr, "instret_q");
    pop_ = VarView(ctx_.get(), arr, "retire");  // an entry executes at the next edge
    gap_ = VarView(ctx_.get(), slv, "gap_q");
    err_sticky_ = VarView(ctx_.get(), err, "err_sticky_q");
    err_cause_ = VarView(ctx_.get(), err, "err_cause_q");
    err_count_ = VarView(ctx_.get(), err, "err_count_q");
    err_addr_ = VarView(ctx_.get(), err, "err_addr_q");
    ev_clear_ = VarView(ctx_.get(), err, "ev_clear_q");
    ev_w_ = VarView(ctx_.get(), err, "ev_w_q");
    ev_r_ = VarView(ctx_.get(), err, "ev_r_q");
    ev_wcause_ = VarView(ctx_.get(), err, "ev_wcause_q");
    ev_rcause_ = VarView(ctx_.get(), err, "ev_rcause_q");
    ev_waddr_ = VarView(ctx_.get(), err, "ev_waddr_q");
    ev_raddr_ = VarView(ctx_.get(), err, "ev_raddr_q");
    level_ = VarView(ctx_.get(), "TOP.fmpp_top.u_queue", "level_q");
    reset();
  }

  ~RtlBusImpl() override {
    activate();
    top_->final();
    if (fst_) fst_->close();
#if VM_COVERAGE
    if (!opt_.coverage_file.empty()) ctx_->coveragep()->write(opt_.coverage_file.c_str());
#endif
  }

  const Config& config() const override { return cfg_; }
  uint64_t cycles() const override { return cycle_; }
  void set_exec_hook(ExecHook h) override { hook_ = std::move(h); }
  std::string failure() const override { return failure_; }

  void idle(uint64_t clocks) override {
    activate();
    for (uint64_t i = 0; i < clocks; ++i) clock();
  }

  Resp write(uint32_t addr, uint64_t data, uint8_t strb) override {
    activate();
    if (opt_.stress) stress_idle();
    top_->s_axil_awvalid_i = 1;
    top_->s_axil_wvalid_i = 1;
    top_->s_axil_awaddr_i = addr;
    top_->s_axil_awprot_i = 0;
    top_->s_axil_wdata_i = data;
    top_->s_axil_wstrb_i = strb;
    wait_accept([this] { return top_->s_axil_awready_o != 0; }, "write", addr);
    top_->s_axil_awvalid_i = 0;
    top_->s_axil_wvalid_i = 0;
    if (!top_->s_axil_bvalid_o) fail("BVALID low after an accepted write", addr);
    const Resp r = static_cast<Resp>(top_->s_axil_bresp_o);
    if (opt_.stress) stress_hold(bhold_, &top_->s_axil_bready_i, &top_->s_axil_bvalid_o);
    return r;
  }

  void withdraw_write_for_test(uint32_t addr, uint64_t data) override {
    activate();
    top_->s_axil_awvalid_i = 1;
    top_->s_axil_wvalid_i = 1;
    top_->s_axil_awaddr_i = addr;
    top_->s_axil_wdata_i = data;
    top_->s_axil_wstrb_i = 0xFF;
    clock();
    top_->s_axil_awvalid_i = 0;
    top_->s_axil_wvalid_i = 0;
    clock();
  }

  Resp read(uint32_t addr, uint64_t* data) override {
    activate();
    if (opt_.stress) stress_idle();
    top_->s_axil_arvalid_i = 1;
    top_->s_axil_araddr_i = addr;
    top_->s_axil_arprot_i = 0;
    wait_accept([this] { return top_->s_axil_arready_o != 0; }, "read", addr);
    top_->s_axil_arvalid_i = 0;
    if (!top_->s_axil_rvalid_o) fail("RVALID low after an accepted read", addr);
    *data = top_->s_axil_rdata_o;
    const Resp r = static_cast<Resp>(top_->s_axil_rresp_o);
    if (opt_.stress) stress_hold(rhold_, &top_->s_axil_rready_i, &top_->s_axil_rvalid_o);
    return r;
  }

  ArchState state() const override {
    ArchState s;
    s.cfg = cfg_;
    s.words.assign(size_t{cfg_.blocks} * cfg_.words, 0);
    s.flags.assign(cfg_.blocks, 0);
    uint64_t planes[32];
    uint32_t lane_words[64];
    for (unsigned t = 0; t < tiles_.size(); ++t) {
      const Tile& tile = tiles_[t];
      const unsigned base = t * map::kLaneW;
      for (unsigned w = 0; w < cfg_.words; ++w) {
        for (unsigned k = 0; k < 32; ++k) planes[k] = plane_bits(tile.mem, w, k, tile.lanes);
        planes_to_words(planes, 32, lane_words);
        for (unsigned l = 0; l < tile.lanes; ++l) s.words[size_t{base + l} * cfg_.words + w] = lane_words[l];
      }
      static_assert(map::kNumFlags == 8, "the flags are read as one group of eight planes");
      for (unsigned f = 0; f < map::kNumFlags; ++f) planes[f] = plane_bits(tile.flags, 0, f, tile.lanes);
      planes_to_words(planes, 8, lane_words);
      for (unsigned l = 0; l < tile.lanes; ++l) s.flags[base + l] = static_cast<uint8_t>(lane_words[l]);
    }
    s.mask = static_cast<uint32_t>(mask_.u64());
    s.instret = instret_.u64();
    s.gap = static_cast<uint8_t>(gap_.u64());
    s.error = error_state();
    s.queue_level = static_cast<unsigned>(level_.u64());
    return s;
  }

  // ERROR as a read shows it: the register with the event of the last access applied
  // (the slave registers an access's error or clear and applies it one edge later).
  ErrorState error_state() const override {
    ErrorState e;
    e.sticky = err_sticky_.u64() != 0;
    e.cause = static_cast<map::Err>(err_cause_.u64());
    e.count = static_cast<uint16_t>(err_count_.u64());
    e.addr = static_cast<uint32_t>(err_addr_.u64());
    if (ev_clear_.u64() != 0) e = ErrorState{};
    if (ev_w_.u64() != 0) e.record(static_cast<map::Err>(ev_wcause_.u64()), static_cast<uint32_t>(ev_waddr_.u64()));
    if (ev_r_.u64() != 0) e.record(static_cast<map::Err>(ev_rcause_.u64()), static_cast<uint32_t>(ev_raddr_.u64()));
    return e;
  }
  uint8_t gap() const override { return static_cast<uint8_t>(gap_.u64()); }

 private:
  struct Tile {
    VarView mem;
    VarView flags;
    unsigned lanes;
  };

  // Plane k (lanes bits) of element `elem` of a tile variable.
  static uint64_t plane_bits(const VarView& v, size_t elem, unsigned k, unsigned lanes) {
    if (lanes == 64) return v.plane64(elem, size_t{k} * 64);
    return v.bits(elem, size_t{k} * lanes, lanes);
  }

  // Parts of the Verilator runtime ($error, scope teardown) use the thread's current
  // context rather than the model's; point it at ours whenever several models coexist.
  void activate() { Verilated::threadContextp(ctx_.get()); }

  void reset() override {
    activate();
    bhold_ = Hold{};
    rhold_ = Hold{};
    top_->clk_i = 0;
    top_->rst_ni = 0;
    top_->s_axil_bready_i = 1;
    top_->s_axil_rready_i = 1;
    // No request pending: with random power-up values (RtlOptions::random_init) the
    // inputs would otherwise start with a random request on the bus.
    top_->s_axil_awvalid_i = 0;
    top_->s_axil_wvalid_i = 0;
    top_->s_axil_arvalid_i = 0;
    top_->eval();
    for (int i = 0; i < 2; ++i) {
      top_->clk_i = 1;
      top_->eval();
      top_->clk_i = 0;
      top_->eval();
    }
    top_->rst_ni = 1;
    top_->eval();
    cycle_ = 0;
  }

  // One clock: settle the inputs with the clock low, then the rising edge.
  void clock() {
    settle();
    rise();
  }

  void settle() {
    if (opt_.stress) release_ready();
    top_->clk_i = 0;
    top_->eval();
    dump(cycle_ * 10);
  }

  void rise() {
    const bool popping = pop_.u64() != 0;
    ctx_->time(cycle_ * 10 + 5);  // so assertion messages carry the time (10 units per clock)
    top_->clk_i = 1;
    top_->eval();
    dump(cycle_ * 10 + 5);
    ++cycle_;
    if (ctx_->gotError() && failure_.empty()) {
      failure_ = "RTL assertion failed at cycle " + std::to_string(cycle_);
      if (fst_) fst_->flush();
    }
    if (popping && hook_) hook_();
  }

  void dump(uint64_t t) {
    if (fst_ && cycle_ >= opt_.trace_start && cycle_ <= opt_.trace_end) fst_->dump(t);
  }

  template <class Ready>
  void wait_accept(Ready ready, const char* what, uint32_t addr) {
    for (uint64_t waited = 0;; ++waited) {
      settle();
      const bool accepted = ready();
      rise();
      if (accepted) return;
      if (waited >= opt_.timeout) {
        fail(std::string(what) + " not accepted within " + std::to_string(opt_.timeout) + " clocks", addr);
        throw std::runtime_error(failure_);
      }
    }
  }

  // Stress mode: sometimes idle before an access ...
  void stress_idle() {
    if (std::uniform_int_distribution<unsigned>(0, 3)(rng_) == 3) {
      idle(std::uniform_int_distribution<unsigned>(1, 4)(rng_));
    }
  }

  // ... and sometimes hold BREADY/RREADY low for a few clocks after a response
  // appears, possibly into the next access, which must then wait for it.
  struct Hold {
    uint8_t* ready = nullptr;
    const uint8_t* valid = nullptr;
    unsigned clocks = 0;
  };

  void stress_hold(Hold& h, uint8_t* ready, const uint8_t* valid) {
    if (opt_.max_backpressure) {
      *ready = 0;
      h = Hold{ready, valid, 8};
      return;
    }
    if (std::uniform_int_distribution<unsigned>(0, 1)(rng_) == 0) return;
    *ready = 0;
    h = Hold{ready, valid, std::uniform_int_distribution<unsigned>(1, 4)(rng_)};
  }

  void release_ready() {
    for (Hold* h : {&bhold_, &rhold_}) {
      if (!h->ready) continue;
      if (!*h->valid) fail("response VALID dropped while READY was low", 0);
      if (--h->clocks == 0) {
        *h->ready = 1;
        h->ready = nullptr;
      }
    }
  }

  void fail(const std::string& msg, uint32_t addr) {
    if (failure_.empty()) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "0x%08x", addr);
      failure_ = msg + " (address " + buf + ", cycle " + std::to_string(cycle_) + ")";
    }
  }

  Config cfg_;
  RtlOptions opt_;
  std::mt19937_64 rng_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> top_;
  std::unique_ptr<VerilatedFstC> fst_;
  std::vector<Tile> tiles_;
  VarView mask_, instret_, pop_, gap_, err_sticky_, err_cause_, err_count_, err_addr_, level_;
  VarView ev_clear_, ev_w_, ev_r_, ev_wcause_, ev_rcause_, ev_waddr_, ev_raddr_;
  ExecHook hook_;
  Hold bhold_, rhold_;  // READY inputs held low (stress mode)
  uint64_t cycle_ = 0;
  std::string failure_;
};

}  // namespace fmpp::backends
