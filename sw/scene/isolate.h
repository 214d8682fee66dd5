// Running an untrusted parser (the mesh library) in a child process: a loop, a crash or
// runaway memory in the library then ends in an error message naming the file, not in a
// hang or a signal of the tool itself.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace rt {

// What run_isolated throws when the child did not finish normally; what() is
// "<label>: <cause>" (timed out after N s, killed by signal N, ran out of memory, ...).
class IsolationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs work() in a forked child with a time limit of `seconds` (and, in builds without
// AddressSanitizer, an address-space limit of `max_bytes`), and returns the string it
// returned. An exception of work() comes back as IsolationError(what()) unless its
// message starts with '!', in which case that text (without the '!') is the message
// thrown. Only for code that touches no threads or open streams of the parent.
// Exception: in an AddressSanitizer build with other threads running, work() runs
// in-process without the limits (that sanitizer's fork() is not safe with threads).
std::string run_isolated(const std::function<std::string()>& work, const std::string& label, double seconds,
                         unsigned long long max_bytes);

}  // namespace rt
