// Output files of the host tools (hits, reports, pictures): every write is checked, a
// regular file is replaced atomically (a temporary file beside it, then rename), and
// outputs that would overwrite an input or each other are refused before any work.
#pragma once

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

}  // namespace fmpp
