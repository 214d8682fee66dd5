// fmpp_fifo alone against a std::deque: random pushes and pops (never a push while
// full or a pop while empty, the contract the slave and the array keep), with the
// head, EMPTY, FULL and the level compared after every clock; and a reset mid-stream.
#include <gtest/gtest.h>
#include <verilated.h>

#include <deque>
#include <random>

#include "Vunit_fifo.h"
#include "Vunit_fifo3.h"

namespace {

// The 95-bit entry as three 32-bit words (VlWide<3>).
struct Entry {
  uint32_t w[3];
  bool operator==(const Entry& o) const { return w[0] == o.w[0] && w[1] == o.w[1] && w[2] == o.w[2]; }
};

template <class V>
class FifoBench {
 public:
  explicit FifoBench(unsigned depth) : depth_(depth) {
    ctx_.fatalOnError(false);
    top_ = std::make_unique<V>(&ctx_, "TOP");
    reset();
  }
  void reset() {
    top_->rst_ni = 0;
    top_->push_i = 0;
    top_->pop_i = 0;
    tick();
    top_->rst_ni = 1;
    top_->eval();
    model_.clear();
  }
  void tick() {
    top_->clk_i = 0;
    top_->eval();
    top_->clk_i = 1;
    top_->eval();
  }
  V& top() { return *top_; }
  std::deque<Entry>& model() { return model_; }
  unsigned depth() const { return depth_; }
  bool assertion_failed() const { return ctx_.gotError(); }

 private:
  VerilatedContext ctx_;
  std::unique_ptr<V> top_;
  std::deque<Entry> model_;
  unsigned depth_;
};

Entry entry_of(const VlWide<3>& v) { return Entry{{v[0], v[1], v[2]}}; }

}  // namespace

TEST(RtlUnitFifo, MatchesAQueueModelUnderRandomTraffic) {
  FifoBench<Vunit_fifo> b(16);
  std::mt19937_64 rng(7);
  uint64_t pushes = 0, pops = 0, fulls = 0;
  for (int i = 0; i < 200000; ++i) {
    auto& t = b.top();
    auto& q = b.model();
    // Phases of mostly pushing and mostly popping, so both FULL and EMPTY happen often.
    const bool fill = (i / 97) % 2 == 0;
    const bool push = q.size() < b.depth() && (rng() % 4 != 0) == fill;
    const bool pop = !q.empty() && (rng() % 4 != 0) != fill;
    Entry e{{static_cast<uint32_t>(rng()), static_cast<uint32_t>(rng()), static_cast<uint32_t>(rng() & 0x7FFFFFFF)}};
    t.push_i = push;
    t.pop_i = pop;
    t.data_i[0] = e.w[0];
    t.data_i[1] = e.w[1];
    t.data_i[2] = e.w[2];
    t.eval();
    if (pop) {
      ASSERT_FALSE(q.empty());
      ASSERT_TRUE(entry_of(t.head_o) == q.front()) << "clock " << i << ": head differs from the queue model";
      q.pop_front();
      ++pops;
    }
    b.tick();
    if (push) {
      q.push_back(e);
      ++pushes;
    }
    t.eval();
    ASSERT_EQ(t.level_o, q.size()) << "clock " << i;
    ASSERT_EQ(t.empty_o != 0, q.empty()) << "clock " << i;
    ASSERT_EQ(t.full_o != 0, q.size() == b.depth()) << "clock " << i;
    if (!q.empty()) ASSERT_TRUE(entry_of(t.head_o) == q.front()) << "clock " << i;
    fulls += t.full_o;
  }
  EXPECT_GT(pushes, 50000u);
  EXPECT_GT(pops, 50000u);
  EXPECT_GT(fulls, 1000u) << "the test never filled the queue";
  EXPECT_FALSE(b.assertion_failed());
}

TEST(RtlUnitFifo, ResetEmptiesAFullQueue) {
  FifoBench<Vunit_fifo> b(16);
  auto& t = b.top();
  for (unsigned i = 0; i < 16; ++i) {
    t.push_i = 1;
    t.data_i[0] = i;
    b.tick();
  }
  t.push_i = 0;
  t.eval();
  ASSERT_TRUE(t.full_o);
  b.reset();
  EXPECT_TRUE(t.empty_o);
  EXPECT_EQ(t.level_o, 0u);
  t.push_i = 1;
  t.data_i[0] = 99;
  b.tick();
  t.push_i = 0;
  t.eval();
  EXPECT_EQ(t.head_o[0], 99u) << "after a reset the next push is the head";
}

TEST(RtlUnitFifo, NonPowerOfTwoDepthWrapsItsPointers) {
  FifoBench<Vunit_fifo3> b(3);
  auto& t = b.top();
  std::deque<uint8_t> q;
  std::mt19937 rng(3);
  for (int i = 0; i < 5000; ++i) {
    const bool push = q.size() < 3 && rng() % 2;
    const bool pop = !q.empty() && rng() % 2;
    const uint8_t d = static_cast<uint8_t>(rng());
    t.push_i = push;
    t.pop_i = pop;
    t.data_i = d;
    t.eval();
    if (pop) {
      ASSERT_EQ(t.head_o, q.front()) << "clock " << i;
      q.pop_front();
    }
    b.tick();
    if (push) q.push_back(d);
    t.eval();
    ASSERT_EQ(t.level_o, q.size());
  }
  EXPECT_FALSE(b.assertion_failed());
}
