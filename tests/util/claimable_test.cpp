// Work handed to a thread beside the caller's (common/util/claimable.h): done exactly
// once, by whichever thread claims it first, with the same result and the same
// exception either way; dropped work is never done.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/util/claimable.h"

namespace fmpp {
namespace {

TEST(Claimable, TheCallerDoesWorkNoThreadBegan) {
  int runs = 0;
  Claimable<int> w([&] { return ++runs * 7; });
  EXPECT_FALSE(w.claimed());
  EXPECT_EQ(w.get(), 7);
  EXPECT_EQ(w.get(), 7);  // kept, not done again
  EXPECT_EQ(runs, 1);
  w.run();
  EXPECT_EQ(runs, 1);
  EXPECT_TRUE(w.claimed());
  EXPECT_FALSE(w.drop());  // done already
  EXPECT_EQ(w.get(), 7);
}

TEST(Claimable, OnceWhicheverThreadClaimsIt) {
  for (int round = 0; round < 200; ++round) {
    std::atomic<int> runs{0};
    Claimable<std::vector<int>> a([&] {
      ++runs;
      return std::vector<int>{1, 2, 3};
    });
    Claimable<std::string> b([&] {
      ++runs;
      return std::string("b");
    });
    {
      const Beside beside(a, b);
      if (round % 2) {
        EXPECT_EQ(b.get(), "b");  // maybe before the thread reaches it
      }
      EXPECT_EQ(a.get(), (std::vector<int>{1, 2, 3}));
    }
    // Each at most once; b, wanted on odd rounds, always then; on even rounds it ran on
    // the thread or was dropped at the end.
    if (round % 2) {
      EXPECT_EQ(runs.load(), 2);
    } else {
      EXPECT_TRUE(runs.load() == 1 || runs.load() == 2) << runs.load();
    }
  }
}

TEST(Claimable, TheWorksExceptionReachesGet) {
  Claimable<int> w([]() -> int { throw std::runtime_error("no hits"); });
  const Beside beside(w);
  EXPECT_THROW(
      {
        try {
          w.get();
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "no hits");
          throw;
        }
      },
      std::runtime_error);
  EXPECT_THROW(w.get(), std::runtime_error);  // every time
}

TEST(Claimable, DroppedWorkIsNeverDone) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> first_began{false};
  int second_runs = 0;
  Claimable<int> first([&] {
    first_began = true;
    released.wait();  // holds the thread until the second is dropped
    return 1;
  });
  Claimable<int> second([&] { return ++second_runs; });
  {
    const Beside beside(first, second);
    EXPECT_TRUE(second.drop());
    release.set_value();
    EXPECT_EQ(first.get(), 1);
  }
  EXPECT_EQ(second_runs, 0);
  EXPECT_THROW(second.get(), std::logic_error);
  // Work nobody asked for by the end is dropped by the thread's end, not waited for.
  int late_runs = 0;
  Claimable<int> late([&] { return ++late_runs; });
  late.drop();
  {
    const Beside beside(late);
  }
  EXPECT_EQ(late_runs, 0);
}

TEST(Claimable, PiecesAddedAfterTheStartRunOnce) {
  std::vector<int> order;
  std::mutex m;
  const auto note = [&](int k) {
    const std::lock_guard<std::mutex> lock(m);
    order.push_back(k);
    return k;
  };
  Claimable<int> a([&] { return note(1); });
  Beside beside;
  beside.add(a);
  beside.start();
  EXPECT_EQ(a.get(), 1);
  // Later pieces, kept alive by the Beside; each done once, by whichever thread.
  std::vector<std::shared_ptr<Claimable<int>>> later;
  for (int k = 2; k < 40; ++k) {
    later.push_back(std::make_shared<Claimable<int>>([&, k] { return note(k); }));
    beside.add(later.back());
  }
  for (size_t i = 0; i < later.size(); ++i) EXPECT_EQ(later[i]->get(), static_cast<int>(i) + 2);
  EXPECT_EQ(order.size(), 39u);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());  // none twice
}

TEST(Claimable, SettledWorkRunsNowhere) {
  // Not begun: dropped, never done.
  int runs = 0;
  Claimable<int> w([&] { return ++runs; });
  w.settle();
  EXPECT_EQ(runs, 0);
  EXPECT_THROW(w.get(), std::logic_error);
  // Begun on the thread beside: waited for, so its captures may go after settle().
  std::promise<void> began;
  std::atomic<bool> finished{false};
  auto slow = std::make_shared<Claimable<int>>([&] {
    began.set_value();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    finished = true;
    return 5;
  });
  Beside beside;
  beside.add(slow);
  beside.start();
  began.get_future().wait();
  slow->settle();
  EXPECT_TRUE(finished.load());
  EXPECT_EQ(slow->get(), 5);
}

TEST(Claimable, TakeMovesTheResultOut) {
  Claimable<std::vector<int>> w([] { return std::vector<int>(1000, 5); });
  const std::vector<int> v = w.take();
  EXPECT_EQ(v.size(), 1000u);
  EXPECT_EQ(v[999], 5);
}

}  // namespace
}  // namespace fmpp
