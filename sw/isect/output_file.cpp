// Checked, atomic output files (see output_file.h).
#include "sw/isect/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace fmpp {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void write_failed(const std::string& path, int err) {
  throw std::runtime_error(path + ": write failed (" + std::strerror(err) + ")");
}

// Writes all of `data` to `fd`; returns 0 or the errno of the failure.
int write_all(int fd, const std::string& data) {
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

bool is_regular_or_absent(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode);
}

}  // namespace

void write_output(const std::string& path, const std::string& data) {
  if (path.empty()) throw std::runtime_error("'' (empty path): cannot write");
  if (path == "-") {
    std::fflush(stdout);
    const int err = write_all(STDOUT_FILENO, data);
    if (err) write_failed("stdout", err);
    return;
  }
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw std::runtime_error(path + ": cannot write: is a directory");
  if (exists && !S_ISREG(st.st_mode)) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) write_failed(path, errno);
    int err = write_all(fd, data);
    if (::close(fd) != 0 && !err) err = errno;
    if (err) write_failed(path, err);
    return;
  }
  // Through a symbolic link to its target, so that the rename replaces the file and not
  // the link.
  std::error_code ec;
  const std::string target = exists ? fs::canonical(path, ec).string() : path;
  const std::string real = ec || target.empty() ? path : target;
  std::string tmp = real + ".tmp-XXXXXX";
  const int fd = ::mkstemp(&tmp[0]);
  if (fd < 0) write_failed(path, errno);
  // mkstemp makes the file 0600: give it the mode the file had, or the usual one.
  mode_t mode = st.st_mode & 07777;
  if (!exists) {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode = 0666 & ~mask;
  }
  int err = ::fchmod(fd, mode) != 0 ? errno : 0;
  if (!err) err = write_all(fd, data);
  if (!err && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && !err) err = errno;
  if (!err && ::rename(tmp.c_str(), real.c_str()) != 0) err = errno;
  if (err) {
    ::unlink(tmp.c_str());
    write_failed(path, err);
  }
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  const bool ea = ::stat(a.c_str(), &sa) == 0, eb = ::stat(b.c_str(), &sb) == 0;
  if (ea && eb) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  if (ea != eb) return false;
  std::error_code ec1, ec2;
  const fs::path pa = fs::weakly_canonical(fs::absolute(a), ec1), pb = fs::weakly_canonical(fs::absolute(b), ec2);
  if (ec1 || ec2) return fs::absolute(a).lexically_normal() == fs::absolute(b).lexically_normal();
  return pa == pb;
}

void check_no_alias(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  auto skip = [](const NamedPath& p) { return p.path.empty() || p.path == "-" || !is_regular_or_absent(p.path); };
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
