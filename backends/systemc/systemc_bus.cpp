// The FMPP over SystemC TLM-2.0: initiator, Bus adapter and factories (see systemc_bus.h).
#include "backends/systemc/systemc_bus.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "backends/systemc/kernel.h"

namespace fmpp::sc {

namespace {

const char* response_name(tlm::tlm_response_status st) {
  switch (st) {
    case tlm::TLM_OK_RESPONSE: return "TLM_OK_RESPONSE";
    case tlm::TLM_INCOMPLETE_RESPONSE: return "TLM_INCOMPLETE_RESPONSE";
    case tlm::TLM_GENERIC_ERROR_RESPONSE: return "TLM_GENERIC_ERROR_RESPONSE";
    case tlm::TLM_ADDRESS_ERROR_RESPONSE: return "TLM_ADDRESS_ERROR_RESPONSE";
    case tlm::TLM_COMMAND_ERROR_RESPONSE: return "TLM_COMMAND_ERROR_RESPONSE";
    case tlm::TLM_BURST_ERROR_RESPONSE: return "TLM_BURST_ERROR_RESPONSE";
    case tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE: return "TLM_BYTE_ENABLE_ERROR_RESPONSE";
  }
  return "unknown TLM response";
}

}  // namespace

// ------------------------------------------------------------------ TlmInitiator

TlmInitiator::TlmInitiator(const sc_core::sc_module_name& name) : sc_core::sc_module(name), socket("socket") {
  trans_.set_data_ptr(data_);
  trans_.set_data_length(sizeof data_);
  trans_.set_streaming_width(sizeof data_);
}

tlm::tlm_response_status TlmInitiator::transport(tlm::tlm_command cmd, uint32_t addr, uint64_t* data, uint8_t strb,
                                                 sc_core::sc_time& delay) {
  trans_.set_command(cmd);
  trans_.set_address(addr);
  trans_.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  trans_.set_dmi_allowed(false);
  // The target may change these on a refused payload; restore them every time.
  trans_.set_data_ptr(data_);
  trans_.set_data_length(sizeof data_);
  trans_.set_streaming_width(sizeof data_);
  if (cmd == tlm::TLM_WRITE_COMMAND) {
    std::memcpy(data_, data, sizeof data_);
    if (strb == 0xFF) {
      trans_.set_byte_enable_ptr(nullptr);
      trans_.set_byte_enable_length(0);
    } else {
      for (unsigned i = 0; i < sizeof be_; ++i) be_[i] = ((strb >> i) & 1u) ? TLM_BYTE_ENABLED : TLM_BYTE_DISABLED;
      trans_.set_byte_enable_ptr(be_);
      trans_.set_byte_enable_length(sizeof be_);
    }
  } else {
    std::memset(data_, 0, sizeof data_);
    trans_.set_byte_enable_ptr(nullptr);
    trans_.set_byte_enable_length(0);
  }
  socket->b_transport(trans_, delay);
  if (cmd == tlm::TLM_READ_COMMAND) std::memcpy(data, data_, sizeof data_);
  return trans_.get_response_status();
}

// -------------------------------------------------------------------- SystemCBus

SystemCBus::SystemCBus(std::unique_ptr<Bus> device, const ScOptions& opt) : device_(std::move(device)), opt_(opt) {
  if (!device_) throw std::invalid_argument("fmpp::sc::SystemCBus: no device");
  // Checked here as well as in the target, before any module exists.
  if (opt_.clock_period_ps == 0) throw std::invalid_argument("fmpp::sc::SystemCBus: clock period 0 ps");
  open_elaboration();
  target_ = std::make_unique<TlmTarget>(sc_core::sc_gen_unique_name("fmpp_target"), *device_, opt_.clock_period_ps);
  initiator_ = std::make_unique<TlmInitiator>(sc_core::sc_gen_unique_name("fmpp_host"));
  initiator_->socket.bind(target_->socket);
  quantum_ = sc_core::sc_time::from_value(opt_.quantum_ps * sc_core::sc_time(1, sc_core::SC_PS).value());
  offset_ = sc_core::SC_ZERO_TIME;
  cycles_ = device_->cycles();
}

SystemCBus::~SystemCBus() {
  // Modules first (the target refers to the device), then the device.
  initiator_.reset();
  target_.reset();
}

Resp SystemCBus::finish(tlm::tlm_response_status st, const char* what, uint32_t addr, const sc_core::sc_time& before) {
  const sc_core::sc_time::value_type took = (offset_ - before).value();
  const sc_core::sc_time::value_type period = target_->clock_period().value();
  if (took % period != 0) {
    throw std::logic_error("fmpp::sc::SystemCBus: the target annotated " + (offset_ - before).to_string() +
                           ", not a whole number of " + target_->clock_period().to_string() + " clocks");
  }
  cycles_ += took / period;
  if (cycles_ != device_->cycles()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "0x%08x", addr);
    throw std::logic_error(std::string("fmpp::sc::SystemCBus: after the ") + what + " of " + buf +
                           " the TLM delays add up to " + std::to_string(cycles_) + " clocks but the device is at " +
                           std::to_string(device_->cycles()) +
                           " (was the device driven outside the SystemC path without advance()?)");
  }
  if (offset_ >= quantum_) sync();
  switch (st) {
    case tlm::TLM_OK_RESPONSE: return Resp::kOkay;
    case tlm::TLM_GENERIC_ERROR_RESPONSE: return Resp::kSlvErr;
    default: {
      char buf[64];
      std::snprintf(buf, sizeof buf, "0x%08x", addr);
      throw std::logic_error(std::string("fmpp::sc::SystemCBus: the target answered the ") + what + " of " + buf +
                             " with " + response_name(st) + " (a payload this initiator should never build)");
    }
  }
}

Resp SystemCBus::write(uint32_t addr, uint64_t data, uint8_t strb) {
  close_elaboration();
  const sc_core::sc_time before = offset_;
  const tlm::tlm_response_status st = initiator_->transport(tlm::TLM_WRITE_COMMAND, addr, &data, strb, offset_);
  return finish(st, "write", addr, before);
}

Resp SystemCBus::read(uint32_t addr, uint64_t* data) {
  close_elaboration();
  const sc_core::sc_time before = offset_;
  uint64_t v = 0;
  const tlm::tlm_response_status st = initiator_->transport(tlm::TLM_READ_COMMAND, addr, &v, 0xFF, offset_);
  const Resp r = finish(st, "read", addr, before);
  *data = r == Resp::kOkay ? v : 0;
  return r;
}

void SystemCBus::advance(uint64_t clocks) {
  cycles_ += clocks;
  offset_ += sc_core::sc_time::from_value(clocks * target_->clock_period().value());
  if (offset_ >= quantum_) sync();
}

void SystemCBus::sync() {
  close_elaboration();
  if (offset_ == sc_core::SC_ZERO_TIME) return;  // sc_start(0) would only warn about no activity
  sc_core::sc_start(offset_);
  offset_ = sc_core::SC_ZERO_TIME;
}

sc_core::sc_time SystemCBus::local_time() const { return sc_core::sc_time_stamp() + offset_; }

std::unique_ptr<SystemCBus> make_systemc_bus(std::unique_ptr<Bus> device, const ScOptions& opt) {
  return std::make_unique<SystemCBus>(std::move(device), opt);
}

// --------------------------------------------------------------- SystemCRtlBus

namespace {

class SystemCRtlBus final : public backends::RtlBus {
 public:
  SystemCRtlBus(std::unique_ptr<backends::RtlBus> rtl, const ScOptions& opt) : rtl_(rtl.get()), bus_(std::move(rtl), opt) {}

  Resp write(uint32_t addr, uint64_t data, uint8_t strb) override { return bus_.write(addr, data, strb); }
  Resp read(uint32_t addr, uint64_t* data) override { return bus_.read(addr, data); }
  uint64_t cycles() const override { return bus_.cycles(); }
  std::string name() const override { return "systemc"; }

  const Config& config() const override { return rtl_->config(); }
  backends::ArchState state() const override { return rtl_->state(); }
  ErrorState error_state() const override { return rtl_->error_state(); }
  uint8_t gap() const override { return rtl_->gap(); }
  void set_exec_hook(ExecHook h) override { rtl_->set_exec_hook(std::move(h)); }
  void idle(uint64_t clocks) override {
    rtl_->idle(clocks);
    bus_.advance(clocks);
  }
  std::string failure() const override { return rtl_->failure(); }
  // The TLM side keeps its own clock count; a reset under it is not modelled.
  void reset() override { throw std::logic_error("fmpp::sc: reset is not supported through the SystemC platform"); }
  void withdraw_write_for_test(uint32_t addr, uint64_t data) override {
    rtl_->withdraw_write_for_test(addr, data);
    bus_.advance(2);
  }

 private:
  backends::RtlBus* rtl_;  // owned by bus_ (initialized first: declared first)
  SystemCBus bus_;
};

}  // namespace

std::unique_ptr<backends::RtlBus> make_systemc_rtl_bus(std::unique_ptr<backends::RtlBus> rtl, const ScOptions& opt) {
  if (!rtl) throw std::invalid_argument("fmpp::sc::make_systemc_rtl_bus: no RTL bus");
  return std::make_unique<SystemCRtlBus>(std::move(rtl), opt);
}

}  // namespace fmpp::sc
