// Lockstep cross-check of the Verilated RTL against the golden model.
#include "backends/lockstep.h"

#include <cstdio>

namespace fmpp::backends {

LockstepOptions::Mode parse_lockstep_mode(const std::string& s) {
  if (s == "check") return LockstepOptions::Mode::kCheck;
  if (s == "fast") return LockstepOptions::Mode::kFast;
  if (s == "off") return LockstepOptions::Mode::kOff;
  throw std::invalid_argument("lockstep mode '" + s + "' is not one of check, fast, off");
}

std::string describe(const QueueEntry& e) {
  char buf[200];
  switch (e.kind) {
    case QueueEntry::Kind::kInstr:
      std::snprintf(buf, sizeof buf, "instr 0x%016llx %s", static_cast<unsigned long long>(e.data),
                    disasm(e.data).c_str());
      break;
    case QueueEntry::Kind::kWord:
      std::snprintf(buf, sizeof buf, "window write block %u word %u = 0x%08x strb 0x%x", e.block, e.word,
                    static_cast<uint32_t>(e.data), e.strb);
      break;
    case QueueEntry::Kind::kFlags:
      std::snprintf(buf, sizeof buf, "window write block %u flags = 0x%02x", e.block,
                    static_cast<unsigned>(e.data & 0xFF));
      break;
  }
  return buf;
}

Lockstep::Lockstep(RtlBus& rtl, ModelBus& model, const LockstepOptions& opt) : rtl_(rtl), model_(model), opt_(opt) {
  if (rtl_.config().blocks != model_.config().blocks || rtl_.config().words != model_.config().words) {
    throw std::invalid_argument("fmpp::backends::Lockstep: RTL is " + rtl_.config().str() + " but the model is " +
                                model_.config().str());
  }
  const bool check = opt_.mode == LockstepOptions::Mode::kCheck;
  rtl_.set_exec_hook([this, check] {
    ++rtl_entries_;
    if (check) rtl_snapshots_.push_back(rtl_.state());
  });
  model_.set_exec_hook([this, check](const QueueEntry& e) {
    ++model_entries_;
    last_entry_ = e;
    last_entry_cycle_ = model_.cycles();
    if (!check) return;
    if (rtl_snapshots_.empty()) mismatch("the model executed this entry but the RTL has not");
    ArchState r = std::move(rtl_snapshots_.front());
    rtl_snapshots_.pop_front();
    const ArchState m = model_state(model_);
    if (!opt_.compare_cycles) {
      // In stress mode the timing differs: the queue's level, and when a bad write to a
      // queued target (accepted while entries execute) lands in ERROR relative to them.
      // after_access() compares ERROR after every access instead.
      r.queue_level = m.queue_level;
      r.error = m.error;
    }
    const std::string d = diff_states(r, m);
    if (!d.empty()) mismatch("state differs after this entry:\n" + d);
    ++state_checks_;
  });
}

void Lockstep::mismatch(const std::string& what) {
  std::string msg = "LOCKSTEP MISMATCH after queue entry #" + std::to_string(model_entries_) + " (" +
                    describe(last_entry_) + ", executed at cycle " + std::to_string(last_entry_cycle_) +
                    ") at cycle " + std::to_string(rtl_.cycles()) + ": " + what;
  if (!rtl_.failure().empty()) msg += "\nRTL: " + rtl_.failure();
  throw LockstepMismatch(msg);
}

void Lockstep::check_hash(const char* where) {
  const ArchState r = rtl_.state();
  if (r.hash() != model_.machine().state_hash() || !(r.error == model_.error()) || r.gap != model_.gap() ||
      r.instret != model_.machine().instret()) {
    mismatch(std::string("state differs ") + where + " (fast mode: the bad entry is one of #" +
             std::to_string(last_hash_entries_ + 1) + "..#" + std::to_string(model_entries_) + "):\n" +
             diff_states(r, model_state(model_)));
  }
  last_hash_entries_ = model_entries_;
  ++state_checks_;
}

void Lockstep::after_access(const char* what, uint32_t addr) {
  char where[96];
  std::snprintf(where, sizeof where, "after %s of 0x%08x", what, addr);
  if (!rtl_.failure().empty()) mismatch(std::string(where) + ": " + rtl_.failure());
  if (opt_.mode != LockstepOptions::Mode::kOff) {
    // The slave's own state changes at the access itself, queue or no queue: an error
    // recorded differently and cleared again before the next queue entry shows only here.
    const ErrorState re = rtl_.error_state();
    if (!(re == model_.error()) || rtl_.gap() != model_.gap()) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "ERROR: RTL 0x%016llx, model 0x%016llx; GAP: RTL %u, model %u",
                    static_cast<unsigned long long>(re.reg()), static_cast<unsigned long long>(model_.error().reg()),
                    rtl_.gap(), model_.gap());
      mismatch(std::string(where) + ": " + buf);
    }
  }
  if (opt_.compare_cycles && rtl_.cycles() != model_.cycles()) {
    mismatch(std::string(where) + ": RTL at cycle " + std::to_string(rtl_.cycles()) + ", model at cycle " +
             std::to_string(model_.cycles()));
  }
  // With matching clocks after every access; in stress mode (the clocks differ) after a
  // read, when both queues are drained.
  if ((opt_.compare_cycles || in_read_) && rtl_entries_ != model_entries_) {
    mismatch(std::string(where) + ": RTL executed " + std::to_string(rtl_entries_) + " entries, model " +
             std::to_string(model_entries_));
  }
  if (opt_.mode == LockstepOptions::Mode::kFast) {
    // Without matching clocks the two sides agree only once both queues are drained.
    const bool aligned = opt_.compare_cycles || in_read_;
    if (aligned && model_entries_ - last_hash_entries_ >= opt_.hash_interval) check_hash(where);
  }
}

Resp Lockstep::write(uint32_t addr, uint64_t data, uint8_t strb) {
  const Resp r = rtl_.write(addr, data, strb);
  const Resp m = model_.write(addr, data, strb);
  if (r != m) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "write 0x%016llx strb 0x%02x to 0x%08x answered %s by the RTL, %s by the model",
                  static_cast<unsigned long long>(data), strb, addr, r == Resp::kOkay ? "OKAY" : "SLVERR",
                  m == Resp::kOkay ? "OKAY" : "SLVERR");
    mismatch(buf);
  }
  after_access("write", addr);
  return r;
}

Resp Lockstep::read(uint32_t addr, uint64_t* data) {
  uint64_t rv = 0, mv = 0;
  const Resp r = rtl_.read(addr, &rv);
  const Resp m = model_.read(addr, &mv);
  // CYCLES is the one value that legitimately differs when the RTL master stalls at random.
  const bool compare_data = opt_.compare_cycles || addr != map::kRegCycles;
  if (r != m || (compare_data && rv != mv)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "read of 0x%08x: RTL %s 0x%016llx, model %s 0x%016llx", addr,
                  r == Resp::kOkay ? "OKAY" : "SLVERR", static_cast<unsigned long long>(rv),
                  m == Resp::kOkay ? "OKAY" : "SLVERR", static_cast<unsigned long long>(mv));
    mismatch(buf);
  }
  in_read_ = true;
  after_access("read", addr);
  in_read_ = false;
  *data = rv;
  return r;
}

void Lockstep::reset() {
  if (!opt_.compare_cycles) {
    uint64_t id = 0;
    read(map::kRegId, &id);
  }
  rtl_.reset();
  model_.reset();
  rtl_snapshots_.clear();  // entries dropped from the queues never executed on either side
  rtl_entries_ = model_entries_;
  last_hash_entries_ = model_entries_;
  ++resets_;
  if (!rtl_.failure().empty()) mismatch("at reset: " + rtl_.failure());
  const std::string d = diff_states(rtl_.state(), model_state(model_));
  if (!d.empty()) mismatch("state differs after a reset:\n" + d);
  ++state_checks_;
}

void Lockstep::final_check() {
  uint64_t id = 0;
  read(map::kRegId, &id);  // drains both queues
  if (!rtl_snapshots_.empty()) {
    mismatch("the RTL executed " + std::to_string(rtl_snapshots_.size()) + " entries the model did not");
  }
  const ArchState r = rtl_.state();
  ArchState m = model_state(model_);
  const std::string d = diff_states(r, m);
  if (!d.empty()) mismatch("final state differs:\n" + d);
  ++state_checks_;
}

}  // namespace fmpp::backends
