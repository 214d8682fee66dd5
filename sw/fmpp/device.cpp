// Host-side FMPP access over a Bus (see device.h).
#include "sw/fmpp/device.h"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace fmpp {

Device::Device(Bus& bus) : bus_(bus) {
  const uint64_t id = read_reg(map::kRegId);
  if (map::kIdMagic.get(id) != map::kMagic) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "fmpp::Device: bus '%s' has no FMPP (ID = 0x%016llx)", bus.name().c_str(),
                  static_cast<unsigned long long>(id));
    throw DeviceError(buf);
  }
  const unsigned major = static_cast<unsigned>(map::kIdMajor.get(id));
  if (major != map::kVersionMajor) {
    throw DeviceError("fmpp::Device: bus '" + bus.name() + "' has an FMPP of major version " + std::to_string(major) +
                      "; this host software speaks version " + std::to_string(map::kVersionMajor));
  }
  const uint64_t c = read_reg(map::kRegConfig);
  cfg_.blocks = static_cast<unsigned>(map::kConfigBlocks.get(c));
  cfg_.words = static_cast<unsigned>(map::kConfigWords.get(c));
  cfg_.validate();
  // The host computes window addresses itself: its block stride must be the device's.
  const unsigned wshift = static_cast<unsigned>(map::kConfigWshift.get(c));
  if (wshift != cfg_.word_shift()) {
    throw DeviceError("fmpp::Device: bus '" + bus.name() + "' reports WSHIFT " + std::to_string(wshift) + " for " +
                      cfg_.str() + "; expected " + std::to_string(cfg_.word_shift()));
  }
  // An error someone else left would be reported as ours later: refuse it now.
  const uint64_t err = read_reg(map::kRegError);
  if (map::kErrorSticky.get(err)) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "fmpp::Device: bus '%s' has an uncleared error (ERROR = 0x%016llx)",
                  bus.name().c_str(), static_cast<unsigned long long>(err));
    throw DeviceError(buf);
  }
}

void Device::fail(const char* what, uint32_t addr) {
  uint64_t err = 0;
  const bool read_ok = bus_.read(map::kRegError, &err) == Resp::kOkay;
  // Clear it, so that the next error's message reports that error's own cause.
  const bool clear_ok = bus_.write(map::kRegError, map::kErrorSticky.put(1)) == Resp::kOkay;
  char buf[240];
  const unsigned cause = static_cast<unsigned>(map::kErrorCause.get(err));
  std::snprintf(buf, sizeof buf, "FMPP bus error: %s at 0x%08x answered SLVERR (ERROR = 0x%016llx: cause %u %s)%s",
                what, addr, static_cast<unsigned long long>(err), cause,
                cause < map::kNumErrs ? map::kErrNames[cause] : "unknown",
                read_ok && clear_ok ? "" : "; the ERROR register could not be read or cleared");
  throw DeviceError(buf);
}

void Device::check_index(const char* what, unsigned index, unsigned limit) const {
  if (index >= limit) {
    throw std::out_of_range(std::string("fmpp::Device: ") + what + " " + std::to_string(index) + " out of range (the " +
                            cfg_.str() + " FMPP has " + std::to_string(limit) + ")");
  }
}

uint64_t Device::read_reg(uint32_t addr) {
  uint64_t v = 0;
  if (bus_.read(addr, &v) != Resp::kOkay) fail("register read", addr);
  return v;
}

void Device::push(uint64_t raw) {
  if (bus_.write(map::kRegQueue, map::kQueueInstr.put(raw)) != Resp::kOkay) {
    const std::string what = "push of " + disasm(raw);
    fail(what.c_str(), map::kRegQueue);
  }
}

void Device::push(const std::vector<uint64_t>& prog) {
  for (uint64_t raw : prog) push(raw);
}

uint32_t Device::word_addr(unsigned block, unsigned word) const {
  check_index("block", block, cfg_.blocks);
  check_index("word", word, cfg_.words);
  return map::kWinWordsBase + (block << cfg_.word_shift()) + (word << 3);
}

void Device::write_word(unsigned block, unsigned word, uint32_t value) {
  const uint32_t a = word_addr(block, word);
  if (bus_.write(a, value, 0x0F) != Resp::kOkay) fail("word write", a);
}

uint32_t Device::read_word(unsigned block, unsigned word) { return static_cast<uint32_t>(read_reg(word_addr(block, word))); }

void Device::write_flags(unsigned block, uint8_t flags) {
  check_index("block", block, cfg_.blocks);
  const uint32_t a = map::kWinFlagsBase + 8 * block;
  if (bus_.write(a, flags, 0x01) != Resp::kOkay) fail("flags write", a);
}

uint8_t Device::read_flags(unsigned block) {
  check_index("block", block, cfg_.blocks);
  return static_cast<uint8_t>(read_reg(map::kWinFlagsBase + 8 * block));
}

uint64_t Device::read_plane(unsigned flag, unsigned tile) {
  check_index("flag", flag, map::kNumFlags);
  check_index("tile", tile, cfg_.tiles());
  return read_reg(map::kWinPlanesBase + (flag << map::kWinPlanesFlagShift) + 8 * tile);
}

std::vector<bool> Device::read_flag_all(unsigned flag) { return read_flag_blocks(flag, cfg_.blocks); }

std::vector<bool> Device::read_flag_blocks(unsigned flag, unsigned count) {
  check_index("block count", count, cfg_.blocks + 1);
  std::vector<bool> out(count);
  for (unsigned t = 0; t * map::kLaneW < count; ++t) {
    const uint64_t p = read_plane(flag, t);
    for (unsigned l = 0; l < map::kLaneW && t * map::kLaneW + l < count; ++l) out[t * map::kLaneW + l] = (p >> l) & 1;
  }
  return out;
}

Responders Device::responders() {
  const uint64_t r = read_reg(map::kRegResp);
  Responders out;
  out.any = map::kRespAny.get(r) != 0;
  out.count = static_cast<uint32_t>(map::kRespCount.get(r));
  out.first = static_cast<uint32_t>(map::kRespFirst.get(r));
  return out;
}

bool Device::overflow() { return map::kStatusOvf.get(read_reg(map::kRegStatus)) != 0; }

uint64_t Device::instret() { return read_reg(map::kRegInstret); }

}  // namespace fmpp
