// Running a helper program (the plot scripts of fmpp-report) without a shell: a leaf
// header (the standard library and POSIX only).
#pragma once

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace fmpp {

// Runs argv[0] (a full path) with the arguments argv[1..] and waits for it: an argument
// vector through posix_spawn, no shell, so no argument is interpreted (quotes, spaces,
// ';' reach the program as they are). Throws std::runtime_error naming the command if it
// cannot be started, is killed by a signal, or exits non-zero.
inline void run_program(const std::vector<std::string>& argv) {
  if (argv.empty()) throw std::invalid_argument("run_program: no program");
  std::string shown;  // the command line for a message, each argument quoted
  for (const auto& a : argv) shown += (shown.empty() ? "'" : " '") + a + "'";
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(nullptr);
  pid_t pid = 0;
  const int err = ::posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ);
  if (err != 0) throw std::runtime_error("cannot run " + shown + ": " + std::strerror(err));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("waiting for " + shown + ": " + std::strerror(errno));
  }
  if (WIFSIGNALED(status)) throw std::runtime_error(shown + " was killed by signal " + std::to_string(WTERMSIG(status)));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(shown + " failed with exit status " + std::to_string(WEXITSTATUS(status)));
  }
}

}  // namespace fmpp
