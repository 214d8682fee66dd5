// Constrained-random FMPP access sequences (see progen.h).
#include "tb/progen.h"

#include <stdexcept>

#include "fmpp/isa.h"

namespace fmpp::tb {

namespace {
// The k-th instruction bit outside the OP field, from bit 0 up.
uint64_t non_op_bit(unsigned k) {
  for (unsigned bit = 0; bit < 64; ++bit) {
    if ((map::kFieldOp.mask() >> bit) & 1) continue;
    if (k-- == 0) return uint64_t{1} << bit;
  }
  throw std::logic_error("progen: no such instruction bit outside OP");
}

constexpr uint32_t kEdgeValues[] = {0x00000000u, 0x00000001u, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFFu,
                                    0x7FFFFFFEu, 0x80000001u, 0xFFFFFFFEu, 0x40000000u, 0x55555555u};
}  // namespace

std::string GenStats::missing() const {
  std::string m;
  for (unsigned op = 0; op < map::kNumOpcodes; ++op) {
    if (per_op[op] == 0) m += std::string(m.empty() ? "" : ", ") + map::kOpNames[op];
  }
  for (unsigned e = 0; e < map::kNumErrs; ++e) {
    if (e == static_cast<unsigned>(map::Err::kNone)) continue;
    if (per_error[e] == 0) m += std::string(m.empty() ? "" : ", ") + "error " + map::kErrNames[e];
  }
  return m;
}

ProgramGenerator::ProgramGenerator(const Config& cfg, uint64_t seed) : cfg_(cfg), rng_(seed) { cfg_.validate(); }

uint32_t ProgramGenerator::edge_value() {
  const unsigned pick = std::uniform_int_distribution<unsigned>(0, 15)(rng_);
  if (pick < 10) return kEdgeValues[pick];
  if (pick < 12) return 1u << std::uniform_int_distribution<unsigned>(0, 31)(rng_);
  return static_cast<uint32_t>(rng_());
}

unsigned ProgramGenerator::word_index() {
  const unsigned pick = std::uniform_int_distribution<unsigned>(0, 9)(rng_);
  if (pick == 0) return 0;
  if (pick == 1) return cfg_.words - 1;
  return std::uniform_int_distribution<unsigned>(0, cfg_.words - 1)(rng_);
}

unsigned ProgramGenerator::block_index() {
  const unsigned pick = std::uniform_int_distribution<unsigned>(0, 9)(rng_);
  if (pick == 0) return 0;
  if (pick == 1) return cfg_.blocks - 1;
  if (pick == 2 && cfg_.blocks > 64) return 63;  // last lane of the first tile
  return std::uniform_int_distribution<unsigned>(0, cfg_.blocks - 1)(rng_);
}

unsigned ProgramGenerator::flag_index() {
  const unsigned pick = std::uniform_int_distribution<unsigned>(0, 3)(rng_);
  return pick == 0 ? map::kFlagSEL : std::uniform_int_distribution<unsigned>(0, map::kNumFlags - 1)(rng_);
}

unsigned ProgramGenerator::shift_amount() {
  const unsigned pick = std::uniform_int_distribution<unsigned>(0, 7)(rng_);
  if (pick < 4) return 0;
  if (pick == 4) return 1;
  if (pick == 5) return static_cast<unsigned>(map::kShrA.max());
  return std::uniform_int_distribution<unsigned>(1, static_cast<unsigned>(map::kShrA.max()))(rng_);
}

unsigned ProgramGenerator::legal_code(uint32_t legal) {
  unsigned codes[32], n = 0;
  for (unsigned v = 0; v < 32; ++v) {
    if ((legal >> v) & 1) codes[n++] = v;
  }
  if (n == 0) throw std::logic_error("progen: a sub-field without a legal value");
  return codes[std::uniform_int_distribution<unsigned>(0, n - 1)(rng_)];
}

uint32_t ProgramGenerator::word_addr(unsigned block, unsigned word) const {
  return map::kWinWordsBase + (block << cfg_.word_shift()) + (word << 3);
}

uint64_t ProgramGenerator::random_instruction() {
  using namespace ins;
  const unsigned op = std::uniform_int_distribution<unsigned>(0, map::kNumOpcodes - 1)(rng_);
  const unsigned pred = std::uniform_int_distribution<unsigned>(0, 2)(rng_) == 0 ? flag_index() : map::kFlagSEL;
  Instr i;
  switch (static_cast<Op>(op)) {
    case Op::kNop: i = nop(); break;
    case Op::kMaskset: {
      const unsigned pick = std::uniform_int_distribution<unsigned>(0, 5)(rng_);
      uint32_t m = edge_value();
      if (pick == 0) m = 0;
      if (pick == 1) m = ~0u;
      if (pick == 2) m = ~(1u << std::uniform_int_distribution<unsigned>(0, 31)(rng_));  // one bit compared
      i = maskset(m);
      break;
    }
    case Op::kRef: {
      const auto fn = static_cast<RefFn>(legal_code(map::kRefFnLegal));
      const bool addr = std::uniform_int_distribution<unsigned>(0, 3)(rng_) == 0;
      const uint32_t key = addr ? (std::uniform_int_distribution<unsigned>(0, 3)(rng_) == 0 ? edge_value() : block_index())
                                : edge_value();
      i = ref(fn, addr ? RefPart::kAddr : RefPart::kData, addr ? 0 : word_index(), key, flag_index(), flag_index());
      break;
    }
    case Op::kCmp: {
      // Words often hold edge values, so constants at and next to them hit equality and
      // the ends of the range (INT32_MIN, INT32_MAX) from both sides.
      const uint32_t near = edge_value() + static_cast<uint32_t>(std::uniform_int_distribution<int>(-1, 1)(rng_));
      const bool lt = std::uniform_int_distribution<unsigned>(0, 1)(rng_) == 1;
      i = cmp(static_cast<CmpFn>(legal_code(map::kCmpFnLegal)), lt ? CmpLt::kLt : CmpLt::kGe, word_index(),
              static_cast<int32_t>(near), flag_index(), flag_index());
      break;
    }
    case Op::kFunc:
      i = func(static_cast<FuncFn>(legal_code(map::kFuncFnLegal)), word_index(), word_index(), word_index(), pred);
      break;
    case Op::kAdd: i = add(word_index(), word_index(), word_index(), pred, shift_amount()); break;
    case Op::kSub: i = sub(word_index(), word_index(), word_index(), pred, shift_amount()); break;
    case Op::kBitcopy: {
      std::uniform_int_distribution<unsigned> bit(0, map::kWordW - 1);
      i = bitcopy(word_index(), bit(rng_), word_index(), bit(rng_), pred);
      break;
    }
    case Op::kLshift: i = lshift(word_index(), word_index(), pred); break;
    case Op::kDivstep: i = divstep(word_index(), word_index(), word_index(), pred); break;
    case Op::kRshift: i = rshift(word_index(), word_index(), pred, shift_amount() + 1); break;
    case Op::kWrites: i = writes(word_index(), edge_value(), pred); break;
    case Op::kSets: i = sets(); break;
    case Op::kResets: i = resets(); break;
    case Op::kSetsadr: {
      const unsigned pick = std::uniform_int_distribution<unsigned>(0, 7)(rng_);
      i = setsadr(pick == 0 ? cfg_.blocks + std::uniform_int_distribution<unsigned>(0, 100)(rng_)  // selects none
                            : block_index());
      break;
    }
    case Op::kFlagop:
      i = flagop(flag_index(), flag_index(), flag_index(),
                 static_cast<uint8_t>(std::uniform_int_distribution<unsigned>(0, static_cast<unsigned>(map::kFlagLut.max()))(rng_)),
                 std::uniform_int_distribution<unsigned>(0, 2)(rng_) == 0);
      break;
  }
  return i.encode();
}

void ProgramGenerator::expect(Resp got, Resp want, const char* what, uint32_t addr) {
  if (got != want) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "progen: %s at 0x%08x answered %s, expected %s", what, addr,
                  got == Resp::kOkay ? "OKAY" : "SLVERR", want == Resp::kOkay ? "OKAY" : "SLVERR");
    throw std::runtime_error(buf);
  }
}

void ProgramGenerator::push_instruction(Bus& bus, uint64_t raw) {
  expect(bus.write(map::kRegQueue, raw), Resp::kOkay, "instruction push", map::kRegQueue);
  ++stats_.instructions;
  ++stats_.per_op[map::kFieldOp.get(raw)];
}

void ProgramGenerator::bad_access(Bus& bus) {
  const unsigned kind = std::uniform_int_distribution<unsigned>(0, 12)(rng_);
  uint32_t addr = 0;
  Resp r = Resp::kOkay;
  const map::Err cause = kind < 6 ? bad_register_access(kind, bus, &addr, &r) : bad_window_access(kind, bus, &addr, &r);
  expect(r, Resp::kSlvErr, "bad access", addr);
  ++stats_.bad;
  ++stats_.per_error[static_cast<unsigned>(cause)];
}

map::Err ProgramGenerator::bad_register_access(unsigned kind, Bus& bus, uint32_t* addr, Resp* r) {
  using map::Err;
  uint64_t data = 0;
  switch (kind) {
    case 0: {  // unknown opcode
      const unsigned op_max = static_cast<unsigned>(map::kFieldOp.max());
      const uint64_t op = std::uniform_int_distribution<unsigned>(map::kNumOpcodes, op_max)(rng_);
      *r = bus.write(*addr = map::kRegQueue, map::kFieldOp.put(op));
      return Err::kIllegal;
    }
    case 1: {  // a legal instruction with one bit flipped in a field it must leave zero, or an operand out of range
      uint64_t raw = 0;
      for (int tries = 0; tries < 64; ++tries) {
        raw = random_instruction() ^ non_op_bit(std::uniform_int_distribution<unsigned>(0, 63 - map::kFieldOp.width)(rng_));
        if (!is_legal(raw, cfg_.words)) break;
      }
      if (is_legal(raw, cfg_.words)) raw = map::kFieldOp.put(map::kFieldOp.max());
      *r = bus.write(*addr = map::kRegQueue, raw);
      return Err::kIllegal;
    }
    case 2:  // partial strobe on the queue
      *r = bus.write(*addr = map::kRegQueue, ins::nop().encode(), 0x0F);
      return Err::kStrobe;
    case 3: {  // write to a read-only register
      static const uint32_t kRo[] = {map::kRegId, map::kRegConfig, map::kRegStatus, map::kRegResp,
                                     map::kRegCycles, map::kRegInstret, map::kRegMask};
      *r = bus.write(*addr = kRo[std::uniform_int_distribution<unsigned>(0, 6)(rng_)], edge_value());
      return Err::kReadonly;
    }
    case 4:  // read of the write-only queue
      *r = bus.read(*addr = map::kRegQueue, &data);
      return Err::kWriteonly;
    default:  // 5: unmapped register offset
      *addr = 0x50 + 8 * std::uniform_int_distribution<unsigned>(0, 400)(rng_);
      *r = std::uniform_int_distribution<unsigned>(0, 1)(rng_) ? bus.read(*addr, &data) : bus.write(*addr, 0);
      return Err::kUnmapped;
  }
}

map::Err ProgramGenerator::bad_window_access(unsigned kind, Bus& bus, uint32_t* addr, Resp* r) {
  using map::Err;
  uint64_t data = 0;
  switch (kind) {
    case 6:  // misaligned
      *addr = (std::uniform_int_distribution<unsigned>(0, 1)(rng_) ? map::kRegId : word_addr(block_index(), 0)) +
             std::uniform_int_distribution<unsigned>(1, 7)(rng_);
      *r = std::uniform_int_distribution<unsigned>(0, 1)(rng_) ? bus.read(*addr, &data) : bus.write(*addr, 0);
      return Err::kAlign;
    case 7:  // block past the end, in the WORDS or FLAGS window
      *addr = std::uniform_int_distribution<unsigned>(0, 1)(rng_)
                 ? word_addr(cfg_.blocks + std::uniform_int_distribution<unsigned>(0, 3)(rng_), word_index())
                 : map::kWinFlagsBase + 8 * (cfg_.blocks + std::uniform_int_distribution<unsigned>(0, 3)(rng_));
      *r = std::uniform_int_distribution<unsigned>(0, 1)(rng_) ? bus.read(*addr, &data) : bus.write(*addr, 1, 0x01);
      return Err::kUnmapped;
    case 8: {  // word past NumWords inside the block stride (only exists when NumWords is not a power of 2)
      const unsigned stride_words = 1u << (cfg_.word_shift() - 3);
      if (stride_words == cfg_.words) {
        *addr = map::kWinPlanesBase + 8 * cfg_.tiles();  // a tile past the end instead
      } else {
        *addr = word_addr(block_index(), std::uniform_int_distribution<unsigned>(cfg_.words, stride_words - 1)(rng_));
      }
      *r = bus.read(*addr, &data);
      return Err::kUnmapped;
    }
    case 9:  // bad strobes on the windows
      if (std::uniform_int_distribution<unsigned>(0, 1)(rng_)) {
        static const uint8_t kBad[] = {0x00, 0x10, 0xF0, 0xFF, 0x1F};
        *r = bus.write(*addr = word_addr(block_index(), word_index()), edge_value(),
                      kBad[std::uniform_int_distribution<unsigned>(0, 4)(rng_)]);
      } else {
        static const uint8_t kBad[] = {0x00, 0x02, 0x03, 0xFF};
        *r = bus.write(*addr = map::kWinFlagsBase + 8 * block_index(), 1,
                      kBad[std::uniform_int_distribution<unsigned>(0, 3)(rng_)]);
      }
      return Err::kStrobe;
    case 10:  // write to the read-only plane window
      *r = bus.write(*addr = map::kWinPlanesBase + (flag_index() << map::kWinPlanesFlagShift) +
                           8 * std::uniform_int_distribution<unsigned>(0, cfg_.tiles() - 1)(rng_),
                    ~0ull);
      return Err::kReadonly;
    case 11:  // outside every region
      *addr = 0x10000000u + 8 * std::uniform_int_distribution<unsigned>(0, 1 << 20)(rng_);
      *r = std::uniform_int_distribution<unsigned>(0, 1)(rng_) ? bus.read(*addr, &data) : bus.write(*addr, 0);
      return Err::kUnmapped;
    default:  // partial strobe on CTRL or ERROR
      *r = bus.write(*addr = std::uniform_int_distribution<unsigned>(0, 1)(rng_) ? map::kRegCtrl : map::kRegError, 0,
                    0x01);
      return Err::kStrobe;
  }
}

void ProgramGenerator::step(Bus& bus) {
  ++stats_.accesses;
  uint64_t data = 0;
  if (burst_ > 0) {
    --burst_;
    push_instruction(bus, random_instruction());
    return;
  }
  if (storms_ && stats_.accesses % 1000 < 60) {
    bad_access(bus);
    return;
  }
  const unsigned pick = std::uniform_int_distribution<unsigned>(0, 999)(rng_);
  if (pick < 700) {
    push_instruction(bus, random_instruction());
  } else if (pick < 780) {
    const unsigned b = block_index(), w = word_index();
    const uint8_t strb = std::uniform_int_distribution<unsigned>(0, 4)(rng_) == 0
                             ? static_cast<uint8_t>(std::uniform_int_distribution<unsigned>(1, 15)(rng_))
                             : 0x0F;
    expect(bus.write(word_addr(b, w), edge_value(), strb), Resp::kOkay, "word write", word_addr(b, w));
    ++stats_.window_writes;
  } else if (pick < 800) {
    const uint32_t addr = map::kWinFlagsBase + 8 * block_index();
    expect(bus.write(addr, std::uniform_int_distribution<unsigned>(0, 255)(rng_), 0x01), Resp::kOkay, "flags write",
           addr);
    ++stats_.window_writes;
  } else if (pick < 900) {
    ++stats_.reads;
    const unsigned what = std::uniform_int_distribution<unsigned>(0, 9)(rng_);
    uint32_t addr;
    if (what < 4) {
      addr = word_addr(block_index(), word_index());
    } else if (what < 5) {
      addr = map::kWinFlagsBase + 8 * block_index();
    } else if (what < 6) {
      addr = map::kWinPlanesBase + (flag_index() << map::kWinPlanesFlagShift) +
             8 * std::uniform_int_distribution<unsigned>(0, cfg_.tiles() - 1)(rng_);
    } else {
      static const uint32_t kRegs[] = {map::kRegResp,   map::kRegStatus,  map::kRegError,
                                       map::kRegMask,   map::kRegInstret, map::kRegCycles,
                                       map::kRegCtrl,   map::kRegId,      map::kRegConfig,
                                       map::kRegResp};
      addr = kRegs[std::uniform_int_distribution<unsigned>(0, 9)(rng_)];
    }
    expect(bus.read(addr, &data), Resp::kOkay, "read", addr);
  } else if (pick < 930) {
    bad_access(bus);
  } else if (pick < 945) {
    // Slow the array down and push a burst: the queue fills and back-pressures.
    const unsigned pick_gap = std::uniform_int_distribution<unsigned>(0, 9)(rng_);
    const uint8_t gap = pick_gap < 4 ? 0 : pick_gap < 8 ? std::uniform_int_distribution<unsigned>(1, 3)(rng_)
                                                        : std::uniform_int_distribution<unsigned>(4, 40)(rng_);
    expect(bus.write(map::kRegCtrl, gap), Resp::kOkay, "CTRL write", map::kRegCtrl);
    burst_ = std::uniform_int_distribution<unsigned>(0, 3 * map::kQueueDepth)(rng_);
  } else if (pick < 955) {
    expect(bus.write(map::kRegError, 1), Resp::kOkay, "ERROR clear", map::kRegError);
  } else {
    // Selection edges: none, one, all blocks, then an instruction under it.
    const unsigned sel = std::uniform_int_distribution<unsigned>(0, 2)(rng_);
    const Instr i = sel == 0 ? ins::resets() : sel == 1 ? ins::setsadr(block_index()) : ins::sets();
    push_instruction(bus, i.encode());
  }
}

}  // namespace fmpp::tb
