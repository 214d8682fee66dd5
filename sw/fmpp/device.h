// Host-side view of one FMPP over any Bus: instruction pushes, window accesses,
// responders and status, with every bus error turned into an exception that says
// what was accessed and what the ERROR register recorded. Nothing is silent.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fmpp/bus.h"
#include "fmpp/config.h"
#include "fmpp/isa.h"

namespace fmpp {

class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Device {
 public:
  // Reads CONFIG from the device to learn its size.
  explicit Device(Bus& bus);

  Bus& bus() { return bus_; }
  const Config& config() const { return cfg_; }

  void push(uint64_t raw);
  void push(const Instr& i) { push(i.encode()); }
  void push(const std::vector<uint64_t>& prog);

  void write_word(unsigned block, unsigned word, uint32_t value);
  uint32_t read_word(unsigned block, unsigned word);
  void write_flags(unsigned block, uint8_t flags);
  uint8_t read_flags(unsigned block);
  // Flag f of blocks 64*tile .. 64*tile+63 (bit i = block 64*tile + i).
  uint64_t read_plane(unsigned flag, unsigned tile);
  // Flag f of every block, one bool per block (NumBlocks / 64 reads).
  std::vector<bool> read_flag_all(unsigned flag);
  // Flag f of blocks 0 .. count - 1 (count <= NumBlocks), one bool per block: the
  // ceil(count / 64) reads of the tiles that hold them.
  std::vector<bool> read_flag_blocks(unsigned flag, unsigned count);

  Responders responders();
  bool overflow();  // STATUS.OVF: some block has V set
  uint64_t cycles() const { return bus_.cycles(); }
  uint64_t instret();

  // Every block, word, flag and tile index is checked against the device's size:
  // std::out_of_range, never an access to some other address.
  uint32_t word_addr(unsigned block, unsigned word) const;

 private:
  // Throws DeviceError with ERROR's cause, after clearing ERROR for the next one.
  [[noreturn]] void fail(const char* what, uint32_t addr);
  void check_index(const char* what, unsigned index, unsigned limit) const;
  uint64_t read_reg(uint32_t addr);

  Bus& bus_;
  Config cfg_;
};

}  // namespace fmpp
