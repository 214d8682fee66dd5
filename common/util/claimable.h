// Work handed to a thread beside the caller's that the caller does itself when that
// thread has not begun it by the time the result is needed: a leaf header (the standard
// library and the POSIX threads and Linux scheduling calls).
//
// Why: a thread may take milliseconds to start (measured on the 2-core VM the project is
// built on: 0.1 ms to 2.6 ms from std::async to the thread's first line, more than the
// exact reference takes for a small scene's plan samples; see Beside for where it begins).
// Waiting for such a thread can cost more than the work; claiming the work first costs at
// most the work itself, and the result is the same whichever thread computed it.
#pragma once

#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace fmpp {

template <class T>
class Claimable {
 public:
  explicit Claimable(std::function<T()> work) : work_(std::move(work)), done_(finished_.get_future().share()) {}
  Claimable(const Claimable&) = delete;
  Claimable& operator=(const Claimable&) = delete;

  // Does the work on the calling thread unless another has claimed it (then returns at
  // once). An exception the work throws is kept for get().
  void run() {
    if (claimed_.exchange(true)) return;
    try {
      value_.emplace(work_());
    } catch (...) {
      error_ = std::current_exception();
    }
    finished_.set_value();
  }

  // Claims the work without doing it: a later run() does nothing, and get() throws
  // std::logic_error. For work that is no longer needed (the thread beside need not do it).
  // True if it was not claimed before.
  bool drop() {
    if (claimed_.exchange(true)) return false;
    error_ = std::make_exception_ptr(std::logic_error("Claimable: the work was dropped"));
    finished_.set_value();
    return true;
  }

  // The result: the work done here if no thread has claimed it, else waited for (it is
  // then under way). Rethrows the work's exception.
  const T& get() {
    run();
    done_.wait();
    if (error_) std::rethrow_exception(error_);
    return *value_;
  }

  // The result moved out (get() then returns the moved-from value): for its one user.
  T take() {
    get();
    return std::move(*value_);
  }

  // After this the work runs nowhere: dropped if no thread has begun it, else waited for.
  // For work whose captures are about to go (a scope ending, normally or by an exception).
  void settle() {
    if (!drop()) done_.wait();
  }

  // Whether some thread has claimed the work (begun, finished or dropped).
  bool claimed() const { return claimed_.load(); }

 private:
  std::function<T()> work_;
  std::atomic<bool> claimed_{false};
  std::promise<void> finished_;
  std::shared_future<void> done_;
  std::optional<T> value_;
  std::exception_ptr error_;
};

// A thread of its own that runs Claimables one after the other (each unless the caller
// has claimed it first), in the order they were added, from start() on; pieces added after
// start() join the end of the queue. Destroyed, it drops what the thread has not begun (no
// longer needed) and joins it. Should the thread not start, every piece is left to the
// caller's get().
//
// The thread begins on a core other than the caller's, then may run anywhere allowed: a
// new thread is queued on its creator's core, and with the caller busy there it may wait
// milliseconds for the other core to take it (measured on the 2-core VM: the plan's helper
// began after up to 4 ms, or not at all before the plan ended; begun away from the caller,
// within a tenth of a millisecond: the plan of the one-triangle scene at 128 x 128, median
// of 30 interleaved runs each, 2.87 ms against 3.69 ms). Where no other core is allowed,
// it begins as any thread does.
class Beside {
 public:
  Beside() = default;
  // Adds the pieces and starts.
  template <class... T>
  explicit Beside(Claimable<T>&... work) {
    (add(work), ...);
    start();
  }
  Beside(const Beside&) = delete;
  Beside& operator=(const Beside&) = delete;
  ~Beside() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      for (const auto& drop : drops_) drop();
    }
    more_.notify_one();
    if (started_) pthread_join(thread_, nullptr);
  }

  // A piece to run after those added before (it must outlive the Beside).
  template <class T>
  void add(Claimable<T>& work) {
    push([&work] { work.run(); }, [&work] { work.drop(); });
  }
  // The same for a piece shorter-lived than the Beside: kept alive by it. Its work may
  // still run until it is settled (Claimable::settle) or its result taken.
  template <class T>
  void add(std::shared_ptr<Claimable<T>> work) {
    push([work] { work->run(); }, [work] { work->drop(); });
  }

  void start() {
    if (started_) return;
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0) return;
    know_ = sched_getaffinity(0, sizeof allowed_, &allowed_) == 0;
    const int here = sched_getcpu();
    if (know_ && here >= 0 && CPU_ISSET(here, &allowed_) && CPU_COUNT(&allowed_) > 1) {
      cpu_set_t away = allowed_;
      CPU_CLR(here, &away);
      pthread_attr_setaffinity_np(&attr, sizeof away, &away);  // a hint: ignored if refused
    }
    started_ = pthread_create(&thread_, &attr, &Beside::body, this) == 0;
    pthread_attr_destroy(&attr);
  }

 private:
  static void* body(void* self) {
    static_cast<Beside*>(self)->loop();
    return nullptr;
  }

  void loop() {
    if (know_) pthread_setaffinity_np(pthread_self(), sizeof allowed_, &allowed_);  // free to move now
    try {
      for (size_t next = 0;; ++next) {
        std::function<void()> run;
        {
          std::unique_lock<std::mutex> lock(mutex_);
          more_.wait(lock, [&] { return stopping_ || next < runs_.size(); });
          if (next >= runs_.size()) return;  // stopping, and nothing left
          run = runs_[next];
        }
        run();  // does nothing if claimed or dropped
      }
    } catch (...) {
      // Out of memory copying a piece: what is left is the callers' (get() does it).
    }
  }

  void push(std::function<void()> run, std::function<void()> drop) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      runs_.push_back(std::move(run));
      drops_.push_back(std::move(drop));
    }
    more_.notify_one();
  }

  std::mutex mutex_;
  std::condition_variable more_;
  bool stopping_ = false;
  std::vector<std::function<void()>> runs_, drops_;
  pthread_t thread_{};
  bool started_ = false;
  bool know_ = false;
  cpu_set_t allowed_{};
};

}  // namespace fmpp
