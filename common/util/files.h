// Output files of the tools: checked before any work, written with every error
// reported. A leaf header (the standard library only), usable from any layer.
#pragma once

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include "common/util/output_file.h"

namespace fmpp {

// Checks before any work that `path` (the value of `option`) can be written: not a
// directory, its directory exists, permission. "-" (stdout) passes when `stdout_ok`.
// An existing file is not truncated here, and one this creates is removed again.
inline void check_writable(const std::string& option, const std::string& path, bool stdout_ok = true) {
  if (path == "-") {
    if (stdout_ok) return;
    throw std::invalid_argument(option + " -: this output needs a file name");
  }
  if (path.empty()) throw std::invalid_argument(option + ": empty path");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::invalid_argument(option + " " + path + ": is a directory");
  const bool existed = std::filesystem::exists(path, ec);
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "a");
  if (!f) {
    throw std::runtime_error(option + " " + path + ": cannot write" +
                             (errno ? std::string(" (") + std::strerror(errno) + ")" : std::string()));
  }
  std::fclose(f);
  if (!existed) std::filesystem::remove(path, ec);
}

// Writes `text` to `path`, or to stdout for "-": checked, and atomic for a file
// (write_output, common/util/output_file.h).
inline void write_text(const std::string& path, const std::string& text) { write_output(path, text); }

}  // namespace fmpp
