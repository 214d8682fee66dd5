// Table 1 basic operations (multiply, sign test, maximum search, data transfer) and
// the fused dot products, checked against exact C++ integer arithmetic on the golden
// model and on the RTL in lockstep with it. Operands include negative values, zero,
// the extremes of each format and values that overflow.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "fmpp/model_bus.h"
#include "sw/fmpp/device.h"
#include "sw/fmpp/program.h"
#include "backends/lockstep.h"
#include "backends/rtl/rtl_bus.h"

namespace fmpp {
namespace {

using namespace ins;
constexpr unsigned kSel = 0, kTmp = 3;

// A device on the model alone, or on the RTL with the model in lockstep.
struct Rig {
  explicit Rig(const std::string& backend, const std::string& config = "small") : cfg(named_config(config)), model(cfg) {
    if (backend == "rtl") {
      rtl = backends::make_rtl_bus(config);
      lock = std::make_unique<backends::Lockstep>(*rtl, model, backends::LockstepOptions{});
      dev = std::make_unique<Device>(*lock);
    } else {
      dev = std::make_unique<Device>(model);
    }
  }
  ~Rig() {
    if (lock) lock->final_check();
  }
  Config cfg;
  ModelBus model;
  std::unique_ptr<backends::RtlBus> rtl;
  std::unique_ptr<backends::Lockstep> lock;
  std::unique_ptr<Device> dev;
};

class Microcode : public ::testing::TestWithParam<std::string> {};

int64_t random_signed(std::mt19937_64& rng, unsigned bits) {
  const int64_t lo = -(int64_t{1} << (bits - 1)), hi = (int64_t{1} << (bits - 1)) - 1;
  switch (rng() % 8) {
    case 0: return lo;
    case 1: return hi;
    case 2: return 0;
    case 3: return -1;
    default: return std::uniform_int_distribution<int64_t>(lo, hi)(rng);
  }
}

// Instructions of a constant-multiplier row R <- floor(sum c_j Y_j / 2^n), from the
// canonical signed digits of the constants: one ADD or SUB per non-zero digit (each
// shifting R by the distance from the previous digit on the way in: SHR_A), one RSHIFT
// for the positions above the last digit, one FUNC to clear R first when the first digit
// is negative (a positive one copies Y instead of adding); a row of zero constants is one
// FUNC that clears R.
size_t const_row_instructions(const std::vector<int64_t>& cs, unsigned n) {
  size_t nonzero = 0;
  int first = 0;
  for (unsigned k = 0; k < n; ++k) {
    for (int64_t c : cs) {
      const std::vector<int8_t> d = csd(c);
      const int digit = k < d.size() ? d[k] : 0;
      if (digit == 0) continue;
      ++nonzero;
      if (first == 0) first = digit;
    }
  }
  if (nonzero == 0) return 1;
  return nonzero + 1 + (first < 0 ? 1 : 0);
}

TEST(Csd, DigitsAreCanonicalAndExact) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 20000; ++k) {
    const int64_t x = random_signed(rng, 33);
    const std::vector<int8_t> d = csd(x);
    int64_t v = 0;
    for (size_t i = 0; i < d.size(); ++i) {
      v += d[i] * (int64_t{1} << i);
      if (i > 0) {
        EXPECT_FALSE(d[i] != 0 && d[i - 1] != 0) << x;
      }
    }
    EXPECT_EQ(v, x);
  }
  EXPECT_EQ(csd_weight(0x7FFFFFFF), 2u);  // 2^31 - 1
  EXPECT_EQ(csd_weight(-1), 1u);
}

TEST_P(Microcode, MultiplyMatchesExactArithmetic) {
  Rig r(GetParam());
  const unsigned B = r.cfg.blocks;
  std::mt19937_64 rng(17);
  for (unsigned n : {2u, 8u, 12u, 16u, 24u, 32u}) {
    std::vector<int64_t> xs(B), ys(B);
    for (unsigned b = 0; b < B; ++b) {
      xs[b] = random_signed(rng, n);
      ys[b] = random_signed(rng, 31) / 2;  // |y| < 2^30
      r.dev->write_word(b, 1, static_cast<uint32_t>(xs[b]));
      r.dev->write_word(b, 2, static_cast<uint32_t>(ys[b]));
    }
    Program p;
    p << sets();
    mul(p, 3, 1, 2, n, kSel, kTmp);
    EXPECT_EQ(p.size(), 1 + 4 * n + 1) << "SETS + 4n + 1";
    r.dev->push(p.code());
    for (unsigned b = 0; b < B; ++b) {
      const int64_t want = dot_reference({xs[b]}, {ys[b]}, n);
      EXPECT_EQ(static_cast<int32_t>(r.dev->read_word(b, 3)), want) << "n=" << n << " x=" << xs[b] << " y=" << ys[b];
    }
    EXPECT_FALSE(r.dev->overflow());
    // The constant-specialised multiply gives the same bits with fewer instructions.
    for (unsigned b = 0; b < std::min(B, 4u); ++b) {
      Program q;
      q << setsadr(b);
      mul_const(q, 4, xs[b], 2, n, kSel);
      EXPECT_EQ(q.size(), 1 + const_row_instructions({xs[b]}, n)) << "n=" << n << " c=" << xs[b];
      r.dev->push(q.code());
      EXPECT_EQ(r.dev->read_word(b, 4), r.dev->read_word(b, 3)) << "n=" << n << " c=" << xs[b];
    }
  }
}

TEST_P(Microcode, DotRowsGenericAndConstantAgreeWithExactArithmetic) {
  Rig r(GetParam());
  std::mt19937_64 rng(23);
  const unsigned n = 20;
  const unsigned B = r.cfg.blocks;
  // Words 0..2: y (|y| <= 2^28, the kernels' bound for 3-term sums); 3..11: x.
  std::vector<std::vector<int64_t>> y(B, std::vector<int64_t>(3));
  std::vector<int64_t> c(9);
  for (auto& v : c) v = random_signed(rng, n);
  for (unsigned b = 0; b < B; ++b) {
    for (unsigned j = 0; j < 3; ++j) {
      y[b][j] = random_signed(rng, 29);
      r.dev->write_word(b, j, static_cast<uint32_t>(y[b][j]));
    }
    for (unsigned k = 0; k < 9; ++k) r.dev->write_word(b, 3 + k, static_cast<uint32_t>(c[k]));
  }
  std::vector<Row> gen(3), con(3);
  for (unsigned i = 0; i < 3; ++i) {
    gen[i].r = 12 + i;
    con[i].r = 15 + i;
    for (unsigned j = 0; j < 3; ++j) {
      gen[i].terms.push_back(Term{j, 0, 3 + 3 * i + j});
      con[i].terms.push_back(Term{j, c[3 * i + j], 0});
    }
  }
  Program p;
  p << sets();
  dot_rows(p, gen, n, kSel, kTmp);
  const size_t generic = p.size();
  dot_rows_const(p, con, n, kSel);
  const size_t constant = p.size() - generic;
  r.dev->push(p.code());
  for (unsigned b = 0; b < B; ++b) {
    for (unsigned i = 0; i < 3; ++i) {
      const int64_t want = dot_reference({c[3 * i], c[3 * i + 1], c[3 * i + 2]}, y[b], n);
      EXPECT_EQ(static_cast<int32_t>(r.dev->read_word(b, 12 + i)), want);
      EXPECT_EQ(static_cast<int32_t>(r.dev->read_word(b, 15 + i)), want);
    }
  }
  EXPECT_EQ(generic, 1 + 3 + n * (1 + 18 + 3));
  size_t want_constant = 0;
  for (unsigned i = 0; i < 3; ++i) want_constant += const_row_instructions({c[3 * i], c[3 * i + 1], c[3 * i + 2]}, n);
  EXPECT_EQ(constant, want_constant);
  EXPECT_LT(constant, generic / 2);
  EXPECT_FALSE(r.dev->overflow());
}

// Pair words (the sum and difference of two multiplicands, made once): the same results
// as without them, with one step fewer wherever two digits of a pair share a position,
// and edge multiplicands (|y| up to 2^29, their sums past 2^30) exact too.
TEST_P(Microcode, DotRowsConstWithPairWordsAgreeWithExactArithmetic) {
  Rig r(GetParam());
  std::mt19937_64 rng(31);
  const unsigned B = r.cfg.blocks;
  const std::vector<PairWords> pairs = {{0, 1, 3, 4}, {0, 2, 5, 6}, {1, 2, 7, 8}};
  for (unsigned n : {8u, 20u, 32u}) {
    std::vector<std::vector<int64_t>> y(B, std::vector<int64_t>(3));
    for (unsigned b = 0; b < B; ++b) {
      for (unsigned j = 0; j < 3; ++j) {
        y[b][j] = b % 5 == 0 ? (j == 1 ? -(int64_t{1} << 28) : (int64_t{1} << 28) - 1) : random_signed(rng, 29);
        r.dev->write_word(b, j, static_cast<uint32_t>(y[b][j]));
      }
    }
    std::vector<int64_t> c(9);
    for (auto& v : c) v = random_signed(rng, n);
    c[4] = c[3];   // row 1: the same digits for y_0 and y_1 (the sum word every time)
    c[8] = -c[6];  // row 2: opposite digits for y_0 and y_2 (the difference word)
    std::vector<Row> rows(3);
    for (unsigned i = 0; i < 3; ++i) {
      rows[i].r = 9 + i;
      for (unsigned j = 0; j < 3; ++j) rows[i].terms.push_back(Term{j, c[3 * i + j], 0});
    }
    Program plain, shared;
    dot_rows_const(plain, rows, n, kSel);
    shared << sets();
    pair_words(shared, pairs, kSel);
    const size_t setup = shared.size();
    dot_rows_const(shared, rows, n, kSel, pairs);
    EXPECT_EQ(setup, 1u + 2 * pairs.size());
    EXPECT_LT(shared.size() - setup, plain.size()) << "n=" << n;
    r.dev->push(shared.code());
    for (unsigned b = 0; b < B; ++b) {
      for (unsigned i = 0; i < 3; ++i) {
        const int64_t want = dot_reference({c[3 * i], c[3 * i + 1], c[3 * i + 2]}, y[b], n);
        EXPECT_EQ(static_cast<int32_t>(r.dev->read_word(b, 9 + i)), want) << "n=" << n << " block " << b << " row " << i;
      }
    }
    EXPECT_FALSE(r.dev->overflow());
  }
  Program bad;
  std::vector<Row> clash(1);
  clash[0].r = 3;  // a pair word
  clash[0].terms.push_back(Term{0, 5, 0});
  EXPECT_THROW(dot_rows_const(bad, clash, 8, kSel, pairs), std::invalid_argument);
}

TEST_P(Microcode, SignTestAndMaximumSearch) {
  Rig r(GetParam());
  const unsigned B = r.cfg.blocks;
  std::mt19937_64 rng(29);
  std::vector<int32_t> v(B);
  for (unsigned b = 0; b < B; ++b) {
    v[b] = static_cast<int32_t>(random_signed(rng, 32));
    if (b % 7 == 3) v[b] = v[b / 2];  // ties
    r.dev->write_word(b, 5, static_cast<uint32_t>(v[b]));
  }
  Program p;
  p << sets();
  nonneg(p, 1, kSel, 5);  // f1 <- v >= 0
  r.dev->push(p.code());
  for (unsigned b = 0; b < B; ++b) EXPECT_EQ((r.dev->read_flags(b) >> 1) & 1, v[b] >= 0 ? 1 : 0) << v[b];
  // Maximum of the non-negative values (31 bits): 3 * 31 instructions + the first MASKSET.
  Program q;
  max_search(q, 1, kTmp, 5, 31);
  EXPECT_EQ(q.size(), 3u * 31);
  r.dev->push(q.code());
  int32_t best = -1;
  unsigned first = 0;
  unsigned count = 0;
  for (unsigned b = 0; b < B; ++b) {
    if (v[b] >= 0 && v[b] > best) {
      best = v[b];
      first = b;
    }
  }
  for (unsigned b = 0; b < B; ++b) count += v[b] == best;
  Program copy;
  copy << flagop(kSel, 1, 1, lut::kA);
  r.dev->push(copy.code());
  const Responders resp = r.dev->responders();
  ASSERT_TRUE(resp.any);
  EXPECT_EQ(resp.first, first);
  EXPECT_EQ(resp.count, count);
}

// fmpp::quotient (DIVSTEP): Q = floor(X 2^(bits-1) / D) for 0 <= X < 2 D, 0 < D < 2^30,
// exactly, in 2 bits + 1 instructions; X kept, no overflow, blocks without the predicate
// unchanged.
TEST_P(Microcode, QuotientIsTheExactFloor) {
  Rig r(GetParam());
  const unsigned B = r.cfg.blocks;
  std::mt19937_64 rng(31);
  for (unsigned bits : {1u, 2u, 9u, 20u, 28u, 31u}) {
    std::vector<uint32_t> x(B), d(B), q0(B);
    for (unsigned b = 0; b < B; ++b) {
      const unsigned pick = static_cast<unsigned>(rng() % 6);
      d[b] = pick == 0 ? 1u : pick == 1 ? (1u << 30) - 1 : 1u + static_cast<uint32_t>(rng() % ((1u << 30) - 1));
      const uint32_t pick_x = static_cast<uint32_t>(rng() % 5);
      x[b] = pick_x == 0 ? 0u : pick_x == 1 ? 2 * d[b] - 1 : pick_x == 2 ? d[b] : pick_x == 3 ? d[b] - 1
                                                                          : static_cast<uint32_t>(rng() % (2 * uint64_t{d[b]}));
      q0[b] = bits == 31 ? 0u : static_cast<uint32_t>(rng()) & ((1u << bits) - 1);  // low bits are overwritten
      r.dev->write_word(b, 1, q0[b]);
      r.dev->write_word(b, 3, x[b]);
      r.dev->write_word(b, 4, d[b]);
    }
    Program p;
    p << sets() << maskset(0) << writes(5, (1u << bits) - 1);
    p << ref(RefFn::kThrough, RefPart::kAddr, 0, 0, 2) << flagop(2, 2, 2, lut::kNotA);  // f2: every block but 0
    Program q;
    quotient(q, 1, 6, 3, 4, bits, 2, 5);
    EXPECT_EQ(q.size(), 2u * bits + 1);
    r.dev->push(p.code());
    r.dev->push(q.code());
    for (unsigned b = 0; b < B; ++b) {
      const uint64_t want = (uint64_t{x[b]} << (bits - 1)) / d[b];
      EXPECT_EQ(r.dev->read_word(b, 1), b == 0 ? q0[b] : static_cast<uint32_t>(want))
          << "bits " << bits << " block " << b << ": " << x[b] << " / " << d[b];
      EXPECT_EQ(r.dev->read_word(b, 3), x[b]);
    }
    EXPECT_FALSE(r.dev->overflow());
  }
}

TEST_P(Microcode, OverflowIsDetectedNotSilent) {
  Rig r(GetParam());
  r.dev->write_word(0, 1, 0x007FFFFFu);  // x = 2^23 - 1, the largest 24-bit multiplier
  r.dev->write_word(0, 2, 0x7FFFFFF0u);  // |y| >= 2^30: outside the multiply's contract
  Program p;
  p << setsadr(0);
  mul(p, 3, 1, 2, 24, kSel, kTmp);
  r.dev->push(p.code());
  EXPECT_TRUE(r.dev->overflow());
  EXPECT_EQ(r.dev->read_flags(0) >> map::kFlagV, 1);
}

TEST_P(Microcode, DataTransfer) {
  Rig r(GetParam());
  const unsigned last = r.cfg.blocks - 1;
  Program p;
  transfer(p, last, 7, 0xCAFEBABE);
  EXPECT_EQ(p.size(), 3u);
  r.dev->push(p.code());
  EXPECT_EQ(r.dev->read_word(last, 7), 0xCAFEBABEu);
  if (last > 0) {
    EXPECT_EQ(r.dev->read_word(last - 1, 7), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Microcode, ::testing::Values("cmodel", "rtl"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace fmpp
