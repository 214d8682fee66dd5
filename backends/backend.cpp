// Backend selection by name (see backend.h).
#include "backends/backend.h"

#include <stdexcept>

namespace fmpp {

namespace {

SystemcWrapper& systemc_wrapper() {
  static SystemcWrapper w;
  return w;
}

}  // namespace

bool register_systemc_backend(SystemcWrapper wrap) {
  systemc_wrapper() = std::move(wrap);
  return true;
}

std::vector<std::string> backend_names() {
  std::vector<std::string> n = {"cmodel", "rtl", "lockstep"};
  if (systemc_wrapper()) n.push_back("systemc");
  return n;
}

namespace {

// The Verilated model records an assertion or handshake failure without stopping.
void stop_on_failure(const backends::RtlBus& rtl) {
  if (!rtl.failure().empty()) throw std::runtime_error("RTL: " + rtl.failure());
}

}  // namespace

void Backend::finish() {
  if (lock_) lock_->final_check();
  if (rtl_view_) stop_on_failure(*rtl_view_);
}

namespace {

// The rtl and systemc backends' bus: forwards every access and throws once the RTL has
// failed an assertion or a handshake (lockstep reports these with its own context).
class CheckedBus final : public Bus {
 public:
  CheckedBus(Bus& inner, const backends::RtlBus& rtl) : inner_(inner), rtl_(rtl) {}
  Resp write(uint32_t addr, uint64_t data, uint8_t strb) override {
    const Resp r = inner_.write(addr, data, strb);
    check();
    return r;
  }
  Resp read(uint32_t addr, uint64_t* data) override {
    const Resp r = inner_.read(addr, data);
    check();
    return r;
  }
  uint64_t cycles() const override { return inner_.cycles(); }
  std::string name() const override { return inner_.name(); }

 private:
  void check() const { stop_on_failure(rtl_); }
  Bus& inner_;
  const backends::RtlBus& rtl_;
};

std::unique_ptr<backends::RtlBus> exact_rtl(const Config& cfg, const BackendOptions& opt) {
  backends::RtlOptions ro;
  ro.trace_file = opt.trace_file;
  ro.trace_start = opt.trace_start;
  ro.trace_end = opt.trace_end;
  std::string built;
  for (const std::string& n : backends::rtl_configs()) {
    const Config c = named_config(n);
    if (c.blocks == cfg.blocks && c.words == cfg.words) return backends::make_rtl_bus(n, ro);
    built += (built.empty() ? "" : ", ") + n + " " + c.str();
  }
  throw std::invalid_argument("no Verilated FMPP of " + cfg.str() + " (blocks x words) is built; built: " + built);
}

}  // namespace

std::unique_ptr<Backend> make_backend(const std::string& name, const Config& cfg, const BackendOptions& opt) {
  cfg.validate();
  auto b = std::unique_ptr<Backend>(new Backend);
  b->name_ = name;
  b->cfg_ = cfg;
  if (name == "cmodel") {
    if (!opt.trace_file.empty()) {
      throw std::invalid_argument("backend 'cmodel' has no waveform: a trace needs rtl, lockstep or systemc");
    }
    b->model_ = std::make_unique<ModelBus>(cfg);
    b->bus_ = b->model_.get();
  } else if (name == "rtl") {
    b->rtl_ = exact_rtl(cfg, opt);
    b->rtl_view_ = b->rtl_.get();
    b->checked_ = std::make_unique<CheckedBus>(*b->rtl_, *b->rtl_view_);
    b->bus_ = b->checked_.get();
  } else if (name == "lockstep") {
    b->rtl_ = exact_rtl(cfg, opt);
    b->rtl_view_ = b->rtl_.get();
    b->model_ = std::make_unique<ModelBus>(cfg);
    backends::LockstepOptions lo;
    lo.mode = backends::parse_lockstep_mode(opt.lockstep_mode);
    b->lock_ = std::make_unique<backends::Lockstep>(*b->rtl_, *b->model_, lo);
    b->bus_ = b->lock_.get();
  } else if (name == "systemc" && systemc_wrapper()) {
    std::unique_ptr<backends::RtlBus> rtl = exact_rtl(cfg, opt);
    b->rtl_view_ = rtl.get();
    b->owned_ = systemc_wrapper()(std::move(rtl));
    b->checked_ = std::make_unique<CheckedBus>(*b->owned_, *b->rtl_view_);
    b->bus_ = b->checked_.get();
  } else {
    std::string known;
    for (const auto& n : backend_names()) known += (known.empty() ? "" : ", ") + n;
    if (name == "systemc") {
      throw std::invalid_argument("backend 'systemc' is not built into this program; it offers " + known);
    }
    throw std::invalid_argument("backend '" + name + "' is not one of " + known);
  }
  return b;
}

}  // namespace fmpp
