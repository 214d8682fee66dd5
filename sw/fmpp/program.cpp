// FMPP programs and microcode (see program.h for the conventions).
#include "sw/fmpp/program.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fmpp {

using namespace ins;

Program& Program::operator<<(const Instr& i) {
  if (i.op == Op::kMaskset) mask_ = i.imm;
  code_.push_back(i.encode());
  return *this;
}

void Program::mask(uint32_t m) {
  if (mask_ && *mask_ == m) return;
  *this << maskset(m);
}

std::vector<int8_t> csd(int64_t x) {
  std::vector<int8_t> d;
  while (x != 0) {
    if (x & 1) {
      const int8_t digit = ((x & 3) == 1) ? 1 : -1;  // x = 1 or 3 (mod 4)
      d.push_back(digit);
      x -= digit;
    } else {
      d.push_back(0);
    }
    x /= 2;  // exact: x is even here
  }
  return d;
}

unsigned csd_weight(int64_t x) {
  unsigned w = 0;
  for (int8_t v : csd(x)) w += v != 0;
  return w;
}

void transfer(Program& p, unsigned block, unsigned w, uint32_t v) {
  p << setsadr(block);
  p.mask(0);
  p << writes(w, v);
}

namespace {

void check_n(unsigned n, const char* who) {
  if (n < 2 || n > 32) throw std::invalid_argument(std::string(who) + ": multiplier bits n = " + std::to_string(n) + " outside [2, 32]");
}

// Digits of a constant at positions 0..n-1, checked to fit.
std::vector<int8_t> digits_of(int64_t c, unsigned n, const char* who) {
  const int64_t lo = -(int64_t{1} << (n - 1)), hi = (int64_t{1} << (n - 1)) - 1;
  if (c < lo || c > hi) {
    throw std::invalid_argument(std::string(who) + ": constant " + std::to_string(c) + " is not an " +
                                std::to_string(n) + "-bit two's complement value");
  }
  std::vector<int8_t> d = csd(c);
  if (d.size() > n) throw std::logic_error(std::string(who) + ": CSD of " + std::to_string(c) + " longer than n");
  d.resize(n, 0);
  return d;
}

}  // namespace

void mul(Program& p, unsigned r, unsigned x, unsigned y, unsigned n, unsigned active, unsigned tmp) {
  check_n(n, "fmpp::mul");
  if (r == x || r == y) throw std::invalid_argument("fmpp::mul: the result word must differ from the operands");
  p << func(FuncFn::kXor, r, r, r, active);  // R <- 0
  for (unsigned k = 0; k < n; ++k) {
    p.mask(~(1u << k));
    p << ref(RefFn::kAnd, RefPart::kData, x, 1u << k, tmp, active);  // tmp <- active and bit k of X
    p << (k == n - 1 ? sub(r, r, y, tmp) : add(r, r, y, tmp));       // the sign bit weighs -2^(n-1)
    p << rshift(r, r, active);
  }
}

void mul_const(Program& p, unsigned r, int64_t c, unsigned y, unsigned n, unsigned active) {
  Row row;
  row.r = r;
  row.terms.push_back(Term{y, c, 0});
  dot_rows_const(p, {row}, n, active);
}

void nonneg(Program& p, unsigned dst, unsigned src, unsigned w) {
  p.mask(0x7FFFFFFFu);  // compare the sign bit only
  p << ref(RefFn::kAnd, RefPart::kData, w, 0, dst, src);
}

void quotient(Program& p, unsigned q, unsigned r, unsigned x, unsigned d, unsigned bits, unsigned active,
              unsigned ones) {
  if (bits < 1 || bits > 31) throw std::invalid_argument("fmpp::quotient: bits = " + std::to_string(bits));
  const unsigned w[5] = {q, r, x, d, ones};
  for (int i = 0; i < 5; ++i) {
    for (int j = i + 1; j < 5; ++j) {
      if (w[i] == w[j]) throw std::invalid_argument("fmpp::quotient: the quotient, remainder, dividend, divisor and constant words must differ");
    }
  }
  // X - D decides the top bit; then each DIVSTEP doubles the partial remainder and
  // subtracts D where it is >= 0, adds D where it is negative.
  p << sub(r, x, d, active) << bitcopy(q, bits - 1, r, 31, active);
  for (int j = static_cast<int>(bits) - 2; j >= 0; --j) {
    p << divstep(r, r, d, active) << bitcopy(q, static_cast<unsigned>(j), r, 31, active);
  }
  p << func(FuncFn::kXor, q, q, ones, active);
}

void max_search(Program& p, unsigned cand, unsigned tmp, unsigned w, unsigned bits) {
  if (bits < 1 || bits > 32) throw std::invalid_argument("fmpp::max_search: bits = " + std::to_string(bits));
  // From the most significant bit down: candidates with a 1 there beat those with a 0,
  // if any candidate has a 1.
  for (int k = static_cast<int>(bits) - 1; k >= 0; --k) {
    p.mask(~(1u << k));
    p << ref(RefFn::kAnd, RefPart::kData, w, 1u << k, tmp, cand);
    p << flagop(cand, tmp, tmp, lut::kA, true);
  }
}

void select_below(Program& p, uint32_t count, uint32_t num_blocks) {
  if (count >= num_blocks) {
    p << sets();
    return;
  }
  p << resets();
  // index < count  <=>  for some bit k set in count: index agrees with count above k
  // and has 0 at k (lower bits free).
  for (int k = 31; k >= 0; --k) {
    if (!((count >> k) & 1)) continue;
    const uint32_t low = (k == 0) ? 0 : ((1u << k) - 1);
    const uint32_t key = count & ~low & ~(1u << k);
    p.mask(low);
    p << ref(RefFn::kOr, RefPart::kAddr, 0, key, map::kFlagSEL, map::kFlagSEL);
  }
}

void dot_rows(Program& p, const std::vector<Row>& rows, unsigned n, unsigned active, unsigned tmp) {
  check_n(n, "fmpp::dot_rows");
  for (const Row& row : rows) {
    for (const Term& t : row.terms) {
      if (row.r == t.x || row.r == t.y) throw std::invalid_argument("fmpp::dot_rows: result word is an operand");
    }
    p << func(FuncFn::kXor, row.r, row.r, row.r, active);
  }
  for (unsigned k = 0; k < n; ++k) {
    p.mask(~(1u << k));
    for (const Row& row : rows) {
      for (const Term& t : row.terms) {
        p << ref(RefFn::kAnd, RefPart::kData, t.x, 1u << k, tmp, active);
        p << (k == n - 1 ? sub(row.r, row.r, t.y, tmp) : add(row.r, row.r, t.y, tmp));
      }
    }
    for (const Row& row : rows) p << rshift(row.r, row.r, active);
  }
}

namespace {

// One ADD or SUB of a row: sign * word, at digit position k.
struct Step {
  unsigned word;
  int sign;
};

// The pair of `pairs` holding y_a and y_b, in either order (*flip: y_b is its first word), or
// nullptr.
const PairWords* find_pair(const std::vector<PairWords>& pairs, unsigned a, unsigned b, bool* flip) {
  for (const PairWords& pw : pairs) {
    if (pw.a == a && pw.b == b) return *flip = false, &pw;
    if (pw.a == b && pw.b == a) return *flip = true, &pw;
  }
  return nullptr;
}

// The steps of one digit position into *out: the non-zero digits of the row's terms
// there, two of them folded into one step wherever `pairs` holds their sum or
// difference. *single and *used are scratch (kept by the caller: no allocation per
// position).
void position_steps(const Row& row, const std::vector<std::vector<int8_t>>& d, unsigned k,
                    const std::vector<PairWords>& pairs, std::vector<Step>* out, std::vector<Step>* single,
                    std::vector<char>* used) {
  single->clear();
  out->clear();
  for (size_t j = 0; j < row.terms.size(); ++j) {
    if (d[j][k] != 0) single->push_back(Step{row.terms[j].y, d[j][k]});
  }
  if (pairs.empty()) {
    out->swap(*single);
    return;
  }
  used->assign(single->size(), 0);
  for (size_t u = 0; u < single->size(); ++u) {
    if ((*used)[u]) continue;
    const Step& a = (*single)[u];
    Step step = a;
    for (size_t v = u + 1; v < single->size(); ++v) {
      bool flip = false;
      const Step& b = (*single)[v];
      const PairWords* pw = (*used)[v] ? nullptr : find_pair(pairs, a.word, b.word, &flip);
      if (pw == nullptr) continue;
      // d_a y_a + d_b y_b = d_a (y_a + d_a d_b y_b), a being the pair's first word.
      step = Step{a.sign == b.sign ? pw->sum : pw->diff, (flip ? b : a).sign};
      (*used)[v] = 1;
      break;
    }
    out->push_back(step);
  }
}

}  // namespace

void dot_rows_const(Program& p, const std::vector<Row>& rows, unsigned n, unsigned active,
                    const std::vector<PairWords>& pairs) {
  check_n(n, "fmpp::dot_rows_const");
  std::vector<Step> steps, single;
  std::vector<char> used;
  for (const Row& row : rows) {
    std::vector<std::vector<int8_t>> d;
    unsigned kmin = n;
    for (const Term& t : row.terms) {
      if (row.r == t.y) throw std::invalid_argument("fmpp::dot_rows_const: result word is an operand");
      d.push_back(digits_of(t.c, n, "fmpp::dot_rows_const"));
      for (unsigned k = 0; k < n; ++k) {
        if (d.back()[k] != 0) kmin = std::min(kmin, k);
      }
    }
    for (const PairWords& pw : pairs) {
      if (row.r == pw.sum || row.r == pw.diff) throw std::invalid_argument("fmpp::dot_rows_const: result word is a pair word");
    }
    if (kmin == n) {  // all constants zero
      p << func(FuncFn::kXor, row.r, row.r, row.r, active);
      continue;
    }
    // The partial sum R stands at digit position `at`: it still owes the shifts of the
    // positions from `at` up to n. Each ADD/SUB first shifts R by the distance from the
    // previous step's position (operand A through the shifter), which is exactly the
    // RSHIFTs of the LSB-first product between the two (floor divisions compose).
    bool zero = true;  // R not yet written: the first positive step copies instead of adding
    unsigned at = kmin;
    for (unsigned k = kmin; k < n; ++k) {
      position_steps(row, d, k, pairs, &steps, &single, &used);
      for (const Step& s : steps) {
        if (zero && s.sign > 0) {
          p << func(FuncFn::kOr, row.r, s.word, s.word, active);
        } else {
          if (zero) p << func(FuncFn::kXor, row.r, row.r, row.r, active);
          const unsigned shr = k - at;
          p << (s.sign > 0 ? add(row.r, row.r, s.word, active, shr) : sub(row.r, row.r, s.word, active, shr));
        }
        zero = false;
        at = k;
      }
    }
    p << rshift(row.r, row.r, active, n - at);  // the shifts after the last digit (1 .. n)
  }
}

void pair_words(Program& p, const std::vector<PairWords>& pairs, unsigned active) {
  for (const PairWords& pw : pairs) p << add(pw.sum, pw.a, pw.b, active) << sub(pw.diff, pw.a, pw.b, active);
}

int64_t dot_reference(const std::vector<int64_t>& c, const std::vector<int64_t>& y, unsigned n) {
  __int128 s = 0;
  for (size_t j = 0; j < c.size(); ++j) s += static_cast<__int128>(c[j]) * y[j];
  // floor division by 2^n
  const __int128 d = static_cast<__int128>(1) << n;
  __int128 q = s / d;
  if (s % d != 0 && s < 0) --q;
  return static_cast<int64_t>(q);
}

}  // namespace fmpp
