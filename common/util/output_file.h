// Output files of the host tools (a leaf header: the standard library and POSIX only) (hits, reports, pictures): every write is checked, a
// regular file is replaced atomically (a temporary file beside it, then rename), and
// outputs that would overwrite an input or each other are refused before any work.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace fmpp {

// Writes `data` to `path`; "-" is standard output. A regular file (or a new one) is
// written to a temporary file in the same directory and renamed over `path` only once
// every byte is written and the file closed, so a failed write (a full disk) leaves the
// old file, or none, and never a truncated one. An existing non-regular file (/dev/null,
// a pipe) is written in place. Throws std::runtime_error "<path>: write failed (<reason>)"
// on any failure, with the temporary file removed.
void write_output(const std::string& path, const std::string& data);

// An option of a command line and the path it names.
struct NamedPath {
  std::string option;  // "--out"
  std::string path;
};

// True if `a` and `b` name the same file: the same device and inode when both exist,
// else the same absolute, normalized path (symbolic links of the existing part resolved).
bool same_file(const std::string& a, const std::string& b);

// Refuses, with std::invalid_argument naming both options and the path, an output that
// is the same file as another output or as an input. "-" (standard output) and
// non-regular files (/dev/null) are not compared; empty paths are skipped.
void check_no_alias(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs);


namespace output_detail {

namespace fs = std::filesystem;

[[noreturn]] inline void write_failed(const std::string& path, int err) {
  throw std::runtime_error(path + ": write failed (" + std::strerror(err) + ")");
}

// Writes all of `data` to `fd`; returns 0 or the errno of the failure.
inline int write_all(int fd, const std::string& data) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return EIO;
    done += static_cast<size_t>(n);
  }
  return 0;
}

inline bool is_regular_or_absent(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode);
}

}  // namespace output_detail

inline void write_output(const std::string& path, const std::string& data) {
  if (path.empty()) throw std::runtime_error("'' (empty path): cannot write");
  if (path == "-") {
    std::fflush(stdout);
    const int err = output_detail::write_all(STDOUT_FILENO, data);
    if (err) output_detail::write_failed("stdout", err);
    return;
  }
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw std::runtime_error(path + ": cannot write: is a directory");
  if (exists && !S_ISREG(st.st_mode)) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) output_detail::write_failed(path, errno);
    int err = output_detail::write_all(fd, data);
    if (::close(fd) != 0 && !err) err = errno;
    if (err) output_detail::write_failed(path, err);
    return;
  }
  // Through a symbolic link to its target, so that the rename replaces the file and not
  // the link.
  std::error_code ec;
  const std::string target = exists ? std::filesystem::canonical(path, ec).string() : path;
  const std::string real = ec || target.empty() ? path : target;
  std::string tmp = real + ".tmp-XXXXXX";
  const int fd = ::mkstemp(&tmp[0]);
  if (fd < 0) output_detail::write_failed(path, errno);
  // mkstemp makes the file 0600: give it the mode the file had, or the usual one.
  mode_t mode = st.st_mode & 07777;
  if (!exists) {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  int err = ::fchmod(fd, mode) != 0 ? errno : 0;
  if (!err) err = output_detail::write_all(fd, data);
  if (!err && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && !err) err = errno;
  if (!err && ::rename(tmp.c_str(), real.c_str()) != 0) err = errno;
  if (err) {
    ::unlink(tmp.c_str());
    output_detail::write_failed(path, err);
  }
}

inline bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  const bool ea = ::stat(a.c_str(), &sa) == 0, eb = ::stat(b.c_str(), &sb) == 0;
  if (ea && eb) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (ea != eb) return false;
  std::error_code ec1, ec2;
  const std::filesystem::path pa = std::filesystem::weakly_canonical(std::filesystem::absolute(a), ec1), pb = std::filesystem::weakly_canonical(std::filesystem::absolute(b), ec2);
  if (ec1 || ec2) return std::filesystem::absolute(a).lexically_normal() == std::filesystem::absolute(b).lexically_normal();
  return pa == pb;
}

inline void check_no_alias(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  auto skip = [](const NamedPath& p) { return p.path.empty() || p.path == "-" || !output_detail::is_regular_or_absent(p.path); };
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (skip(outputs[i])) continue;
    for (const NamedPath& in : inputs) {
      if (in.path.empty() || in.path == "-" || !same_file(outputs[i].path, in.path)) continue;
      throw std::invalid_argument(outputs[i].option + " " + outputs[i].path + " is the input " + in.option + " " +
                                  in.path + ": it would be overwritten; give another output path");
    }
    for (size_t j = 0; j < i; ++j) {
      if (skip(outputs[j]) || !same_file(outputs[i].path, outputs[j].path)) continue;
      throw std::invalid_argument(outputs[i].option + " and " + outputs[j].option + " name the same file " +
                                  outputs[i].path + ": one would replace the other; give them different paths");
    }
  }
}

}  // namespace fmpp
