// Golden model of the FMPP bus interface, instruction queue and pipeline (twin of
// rtl/fmpp_axil_slave.sv, fmpp_addr_decode.sv, fmpp_fifo.sv and the sequencer and
// pipeline of fmpp_array.sv), clock-exact for the bus master described in model_bus.h.
#include "fmpp/model_bus.h"

#include <stdexcept>

namespace fmpp {

using map::Err;

// The Bus interface carries the map's beats and addresses in these types.
static_assert(map::kDataW == 64, "fmpp::Bus moves 64-bit beats (uint64_t)");
static_assert(map::kAddrW == 32, "fmpp::Bus addresses are 32 bits (uint32_t)");

Decoded decode_address(const Config& cfg, uint32_t addr) {
  Decoded d;
  d.aligned = (addr & 7) == 0;
  if ((addr >> 12) == 0) {
    d.region = Decoded::Region::kReg;
    d.reg = addr & 0xFFF;
    return d;
  }
  if (addr >= map::kWinPlanesBase && addr - map::kWinPlanesBase < map::kWinPlanesSize) {
    const uint32_t off = addr - map::kWinPlanesBase;
    d.block = (off & ((1u << map::kWinPlanesFlagShift) - 1)) >> 3;
    d.flag = off >> map::kWinPlanesFlagShift;
    if (d.block < cfg.tiles()) d.region = Decoded::Region::kPlane;
    return d;
  }
  if (addr >= map::kWinFlagsBase && addr - map::kWinFlagsBase < map::kWinFlagsSize) {
    d.block = (addr - map::kWinFlagsBase) >> 3;
    if (d.block < cfg.blocks) d.region = Decoded::Region::kFlags;
    return d;
  }
  if (addr >= map::kWinWordsBase && addr - map::kWinWordsBase < map::kWinWordsSize) {
    const uint32_t off = addr - map::kWinWordsBase;
    const unsigned shift = cfg.word_shift();
    d.block = off >> shift;
    d.word = (off >> 3) & ((1u << (shift - 3)) - 1);
    if (d.block < cfg.blocks && d.word < cfg.words) d.region = Decoded::Region::kWord;
    return d;
  }
  return d;
}

uint64_t ErrorState::reg() const {
  return map::kErrorAddr.put(addr) | map::kErrorCount.put(count) | map::kErrorCause.put(static_cast<uint8_t>(cause)) |
         map::kErrorSticky.put(sticky);
}

void ErrorState::record(Err c, uint32_t a) {
  if (!sticky) {
    cause = c;
    addr = a;
  }
  sticky = true;
  if (count != map::kErrorCount.max()) ++count;
}

bool ErrorState::operator==(const ErrorState& o) const {
  return sticky == o.sticky && cause == o.cause && count == o.count && addr == o.addr;
}

ModelBus::ModelBus(const Config& cfg) : m_(cfg), ring_(map::kQueueDepth) {}

void ModelBus::reset() {
  m_.reset();
  head_ = 0;
  count_ = 0;
  for (bool& v : pipe_valid_) v = false;
  pipe_count_ = 0;
  cycle_ = 0;
  gap_ = 0;
  gap_cnt_ = 0;
  any_wait_ = 0;
  was_busy_ = false;
  err_ = ErrorState{};
  err_event_ = false;
}

Err ModelBus::check_write(uint32_t addr, uint64_t data, uint8_t strb, QueueEntry* push, bool* is_push) const {
  const Decoded d = decode_address(config(), addr);
  *is_push = false;
  if (!d.aligned) return Err::kAlign;
  switch (d.region) {
    case Decoded::Region::kReg:
      switch (d.reg) {
        case map::kRegQueue:
          if (strb != 0xFF) return Err::kStrobe;
          if (!is_legal(map::kQueueInstr.get(data), config().words)) return Err::kIllegal;
          *is_push = true;
          *push = QueueEntry{QueueEntry::Kind::kInstr, 0, 0, 0, map::kQueueInstr.get(data)};
          return Err::kNone;
        case map::kRegCtrl:
        case map::kRegError:
          return strb != 0xFF ? Err::kStrobe : Err::kNone;
        case map::kRegId:
        case map::kRegConfig:
        case map::kRegStatus:
        case map::kRegResp:
        case map::kRegCycles:
        case map::kRegInstret:
        case map::kRegMask:
          return Err::kReadonly;
        default:
          return Err::kUnmapped;
      }
    case Decoded::Region::kPlane:
      return Err::kReadonly;
    case Decoded::Region::kFlags:
      if (strb != 0x01) return Err::kStrobe;
      *is_push = true;
      *push = QueueEntry{QueueEntry::Kind::kFlags, d.block, 0, 0, data};
      return Err::kNone;
    case Decoded::Region::kWord:
      if ((strb & 0xF0) != 0 || (strb & 0x0F) == 0) return Err::kStrobe;
      *is_push = true;
      *push = QueueEntry{QueueEntry::Kind::kWord, d.block, static_cast<uint8_t>(d.word),
                         static_cast<uint8_t>(strb & 0xF), data};
      return Err::kNone;
    case Decoded::Region::kNone:
      break;
  }
  return Err::kUnmapped;
}

bool ModelBus::queued_target(uint32_t addr) const {
  const Decoded d = decode_address(config(), addr);
  if (!d.aligned) return false;
  return (d.region == Decoded::Region::kReg && d.reg == map::kRegQueue) || d.region == Decoded::Region::kFlags ||
         d.region == Decoded::Region::kWord;
}

void ModelBus::execute(const QueueEntry& e) {
  switch (e.kind) {
    case QueueEntry::Kind::kInstr:
      m_.execute(e.data);
      break;
    case QueueEntry::Kind::kWord:
      m_.write_word(e.block, e.word, static_cast<uint32_t>(e.data), e.strb);
      break;
    case QueueEntry::Kind::kFlags:
      m_.write_flags(e.block, static_cast<uint8_t>(e.data));
      break;
  }
}

bool ModelBus::waits_for_any(const QueueEntry& e) {
  return e.kind == QueueEntry::Kind::kInstr && static_cast<map::Op>(map::kFieldOp.get(e.data)) == map::Op::kFlagop &&
         map::kFlagAny.get(map::kFieldImm.get(e.data)) != 0;
}

void ModelBus::push_entry(const QueueEntry* push) {
  if (!push) return;
  if (count_ == ring_.size()) throw std::logic_error("fmpp::ModelBus: push into a full queue");
  ring_[(head_ + count_) % ring_.size()] = *push;
  ++count_;
}

void ModelBus::tick(const QueueEntry* push) {
  err_event_ = false;  // an error event of the last edge lands at this one
  was_busy_ = pipe_count_ > 0;
  // The last stage executes: its effects land at this edge.
  constexpr size_t kLast = kPipeLatency - 1;
  // A FLAGOP with FLAG_ANY in stage 3 holds the pipeline kAnyLatency clocks (the any tree's
  // registers): nothing executes, advances or pops; the GAP counter still counts down.
  if (pipe_valid_[kLast] && any_wait_ < map::kAnyLatency && waits_for_any(pipe_[kLast])) {
    ++any_wait_;
    if (gap_cnt_ > 0) --gap_cnt_;
    push_entry(push);
    ++cycle_;
    return;
  }
  any_wait_ = 0;
  const bool retired = pipe_valid_[kLast];
  const QueueEntry done = pipe_[kLast];
  if (retired) {
    execute(done);
    --pipe_count_;
  }
  // The pipeline advances, and the queue head enters it.
  for (size_t k = kLast; k > 0; --k) {
    pipe_[k] = pipe_[k - 1];
    pipe_valid_[k] = pipe_valid_[k - 1];
  }
  pipe_valid_[0] = false;
  if (count_ > 0 && gap_cnt_ == 0) {
    pipe_[0] = ring_[head_];
    pipe_valid_[0] = true;
    ++pipe_count_;
    head_ = (head_ + 1) % ring_.size();
    --count_;
    gap_cnt_ = gap_;
  } else if (gap_cnt_ > 0) {
    --gap_cnt_;
  }
  push_entry(push);
  ++cycle_;
  // The hook sees the state after the whole edge, as the RTL's observer does.
  if (retired && exec_hook_) exec_hook_(done);
}

void ModelBus::drain() {
  while (count_ > 0 || pipe_count_ > 0) tick(nullptr);
}

void ModelBus::settle() {
  drain();
  if (was_busy_) tick(nullptr);
}

Resp ModelBus::write(uint32_t addr, uint64_t data, uint8_t strb) {
  QueueEntry entry;
  bool is_push = false;
  const Err e = check_write(addr, data, strb, &entry, &is_push);
  // A legal push is a queued target; only a bad write needs the address decoded again.
  if (is_push || (e != Err::kNone && queued_target(addr))) {
    while (count_ == ring_.size()) tick(nullptr);
    if (e == Err::kNone) {
      tick(&entry);
      return Resp::kOkay;
    }
    err_.record(e, addr);
    tick(nullptr);
    err_event_ = true;
    return Resp::kSlvErr;
  }
  settle();
  // Accepted at this edge: register effects land with it.
  if (e != Err::kNone) {
    err_.record(e, addr);
  } else if (addr == map::kRegCtrl) {
    gap_ = static_cast<uint8_t>(map::kCtrlGap.get(data));
  } else if (addr == map::kRegError && map::kErrorSticky.get(data)) {
    err_ = ErrorState{};
  }
  tick(nullptr);
  err_event_ = e != Err::kNone || addr == map::kRegError;
  return e == Err::kNone ? Resp::kOkay : Resp::kSlvErr;
}

uint64_t ModelBus::register_value(uint32_t reg) const {
  const Config& c = config();
  switch (reg) {
    case map::kRegId:
      return map::kIdMagic.put(map::kMagic) | map::kIdMajor.put(map::kVersionMajor) | map::kIdMinor.put(map::kVersionMinor);
    case map::kRegConfig:
      return map::kConfigWshift.put(c.word_shift()) | map::kConfigLanes.put(map::kLaneW) |
             map::kConfigQdepth.put(map::kQueueDepth) | map::kConfigWords.put(c.words) | map::kConfigBlocks.put(c.blocks);
    case map::kRegStatus: {
      const Responders r = m_.responders();
      return map::kStatusAny.put(r.any) | map::kStatusOvf.put(m_.ovf_any()) | map::kStatusErr.put(err_.sticky);
    }
    case map::kRegError:
      return err_.reg();
    case map::kRegCtrl:
      return map::kCtrlGap.put(gap_);
    case map::kRegResp: {
      const Responders r = m_.responders();
      return map::kRespAny.put(r.any) | map::kRespFirst.put(r.first) | map::kRespCount.put(r.count);
    }
    case map::kRegCycles:
      return map::kCyclesValue.put(cycle_);
    case map::kRegInstret:
      return map::kInstretValue.put(m_.instret());
    case map::kRegMask:
      return map::kMaskValue.put(m_.mask());
    default:
      throw std::logic_error("fmpp::ModelBus::register_value: unmapped register");
  }
}

Resp ModelBus::read(uint32_t addr, uint64_t* data) {
  settle();
  if (err_event_) tick(nullptr);
  // RESP and STATUS wait for the responder tree's registers (the RTL's resp_en: the exact
  // register offsets, aligned; the flags do not change while they wait).
  if (addr == map::kRegResp || addr == map::kRegStatus) {
    for (unsigned k = 0; k < map::kRespLatency; ++k) tick(nullptr);
  }
  const Decoded d = decode_address(config(), addr);
  Err e = Err::kNone;
  uint64_t v = 0;
  if (!d.aligned) {
    e = Err::kAlign;
  } else {
    switch (d.region) {
      case Decoded::Region::kReg:
        switch (d.reg) {
          case map::kRegId:
          case map::kRegConfig:
          case map::kRegStatus:
          case map::kRegError:
          case map::kRegCtrl:
          case map::kRegResp:
          case map::kRegCycles:
          case map::kRegInstret:
          case map::kRegMask:
            v = register_value(d.reg);
            break;
          case map::kRegQueue:
            e = Err::kWriteonly;
            break;
          default:
            e = Err::kUnmapped;
            break;
        }
        break;
      case Decoded::Region::kPlane:
        v = m_.plane(d.flag, d.block);
        break;
      case Decoded::Region::kFlags:
        v = m_.flags(d.block);
        break;
      case Decoded::Region::kWord:
        v = m_.word(d.block, d.word);
        break;
      case Decoded::Region::kNone:
        e = Err::kUnmapped;
        break;
    }
  }
  if (e != Err::kNone) {
    err_.record(e, addr);
    v = 0;
  }
  tick(nullptr);
  err_event_ = e != Err::kNone;
  *data = v;
  return e == Err::kNone ? Resp::kOkay : Resp::kSlvErr;
}

}  // namespace fmpp
