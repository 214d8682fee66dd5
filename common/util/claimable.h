// Work handed to a thread beside the caller's that the caller does itself when that
// thread has not begun it by the time the result is needed: a leaf header (the standard
// library only).
//
// Why: a thread may take milliseconds to start (measured on the 2-core VM the project is
// built on: 0.1 ms to 2.6 ms from std::async to the thread's first line, more than the
// exact reference takes for a small scene's plan samples). Waiting for such a thread can
// cost more than the work; claiming the work first costs at most the work itself, and the
// result is the same whichever thread computed it.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <future>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <thread>
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
// has claimed it first). Destroyed, it drops what the thread has not begun (no longer
// needed) and joins it. Should the thread not start (std::system_error), every piece of
// work is left to the caller's get().
class Beside {
 public:
  template <class... T>
  explicit Beside(Claimable<T>&... work) {
    (runs_.emplace_back([&work] { work.run(); }), ...);
    (drops_.emplace_back([&work] { work.drop(); }), ...);
    try {
      thread_ = std::thread([this] {
        for (const auto& run : runs_) run();
      });
    } catch (const std::system_error&) {
    }
  }
  Beside(const Beside&) = delete;
  Beside& operator=(const Beside&) = delete;
  ~Beside() {
    for (const auto& drop : drops_) drop();
    if (thread_.joinable()) thread_.join();
  }

 private:
  std::vector<std::function<void()>> runs_, drops_;
  std::thread thread_;
};

}  // namespace fmpp
