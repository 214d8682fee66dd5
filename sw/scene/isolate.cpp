// Forked, time- and memory-limited execution of a parser (see isolate.h).
#include "sw/scene/isolate.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <cstring>

#if defined(__SANITIZE_ADDRESS__)
#define FMPP_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FMPP_UNDER_ASAN 1
#endif
#endif

namespace rt {
namespace {

bool write_all(int fd, const char* p, size_t n) {
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    n -= static_cast<size_t>(k);
  }
  return true;
}

#ifdef FMPP_UNDER_ASAN
// Threads of this process besides the caller (/proc/self/task has one entry per thread).
bool other_threads_running() {
  std::error_code ec;
  int n = 0;
  for (std::filesystem::directory_iterator it("/proc/self/task", ec), end; !ec && it != end; it.increment(ec)) ++n;
  return n > 1;
}

// The work in this process, its exceptions as the child's would read.
std::string in_process(const std::function<std::string()>& work, const std::string& label) {
  try {
    return work();
  } catch (const std::bad_alloc&) {
    throw IsolationError(label + ": ran out of memory");
  } catch (const IsolationError&) {
    throw;
  } catch (const std::exception& e) {
    const std::string what = e.what();
    if (!what.empty() && what[0] == '!') throw IsolationError(what.substr(1));
    throw IsolationError(label + ": " + what);
  }
}
#endif

// The child: the work under the memory limit, its result ("R...") or error ("E...") on fd.
[[noreturn]] void child(const std::function<std::string()>& work, unsigned long long max_bytes, int fd) {
#ifndef FMPP_UNDER_ASAN
  // ASan reserves terabytes of address space up front: no limit under it.
  const rlimit lim{max_bytes, max_bytes};
  ::setrlimit(RLIMIT_AS, &lim);
#endif
  std::string out;
  try {
    out = "R" + work();
  } catch (const std::bad_alloc&) {
    out = "Eran out of memory (over " + std::to_string(max_bytes >> 20) + " MiB)";
  } catch (const std::exception& e) {
    out = std::string("E") + e.what();
  } catch (...) {
    out = "Ean unknown exception";
  }
  _exit(write_all(fd, out.data(), out.size()) ? 0 : 3);
}

// What the child writes on fd until it closes it or `seconds` pass (*timed_out).
std::string read_until(int fd, double seconds, bool* timed_out) {
  std::string got;
  char buf[65536];
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  *timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      *timed_out = true;
      break;
    }
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got.append(buf, static_cast<size_t>(n));
  }
  return got;
}

// The child's result from what it wrote and how it ended; an IsolationError otherwise.
std::string result_of(const std::string& got, int status, bool timed_out, const std::string& label, double seconds) {
  if (timed_out) throw IsolationError(label + ": gave no result within " + std::to_string(static_cast<int>(seconds)) + " s");
  if (WIFSIGNALED(status)) {
    throw IsolationError(label + ": the reader crashed (signal " + std::to_string(WTERMSIG(status)) + ")");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || got.empty()) {
    throw IsolationError(label + ": the reader failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
  }
  if (got[0] == 'E') {
    if (got.size() > 1 && got[1] == '!') throw IsolationError(got.substr(2));
    throw IsolationError(label + ": " + got.substr(1));
  }
  return got.substr(1);
}

}  // namespace

std::string run_isolated(const std::function<std::string()>& work, const std::string& label, double seconds,
                         unsigned long long max_bytes) {
#ifdef FMPP_UNDER_ASAN
  // This compiler's AddressSanitizer takes no allocator locks around fork(): a child
  // forked while another thread (Embree's, MPI's) holds one waits for ever in its first
  // malloc. With other threads running, an ASan build reads in-process, without the
  // time and memory limits; exceptions keep their meaning.
  if (other_threads_running()) return in_process(work, label);
#endif
  int fds[2];
  if (::pipe(fds) != 0) throw IsolationError(label + ": cannot create a pipe (" + std::strerror(errno) + ")");
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw IsolationError(label + ": cannot start the reader process (" + std::strerror(errno) + ")");
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(work, max_bytes, fds[1]);
  }
  ::close(fds[1]);
  bool timed_out = false;
  const std::string got = read_until(fds[0], seconds, &timed_out);
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return result_of(got, status, timed_out, label, seconds);
}

}  // namespace rt
