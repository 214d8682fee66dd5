// The instruction mix the benchmarks push: the instructions the intersection kernels
// use most, with random operands (shared by core_bench.cpp and sc_bench.cpp).
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "fmpp/isa.h"

namespace fmpp::bench {

inline std::vector<uint64_t> kernel_mix(unsigned words, size_t n, uint64_t seed) {
  using namespace fmpp::ins;
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<unsigned> w(0, words - 1);
  std::vector<uint64_t> prog;
  for (size_t i = 0; i < n; ++i) {
    switch (rng() % 6) {
      case 0: prog.push_back(add(w(rng), w(rng), w(rng), 1).encode()); break;
      case 1: prog.push_back(sub(w(rng), w(rng), w(rng)).encode()); break;
      case 2: prog.push_back(rshift(w(rng), w(rng)).encode()); break;
      case 3: prog.push_back(ref(RefFn::kAnd, RefPart::kData, w(rng), 1u << (rng() % 32), 1, 0).encode()); break;
      case 4: prog.push_back(maskset(~(1u << (rng() % 32))).encode()); break;
      default: prog.push_back(flagop(2, 1, 0, lut::kAnd).encode()); break;
    }
  }
  return prog;
}

}  // namespace fmpp::bench
