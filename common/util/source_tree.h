// The repository's own files (scenes, data, scripts) as a tool or a test finds them: in
// the source tree the build was configured from, FMPP_SOURCE_DIR, which the CMake target
// fmpp_source_tree defines for whoever links it.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#ifndef FMPP_SOURCE_DIR
#error "FMPP_SOURCE_DIR is not defined: the target must link fmpp_source_tree (common/CMakeLists.txt)"
#endif

namespace fmpp {

// rel (e.g. "scenes/cornell.json") in the source tree.
inline std::string source_file(const std::string& rel) { return std::string(FMPP_SOURCE_DIR) + "/" + rel; }

// A file of the repository for a default path, so that a default does not depend on the
// current directory: the source tree the tool was built from, else the tree around the
// executable (BIN/.. or BIN), else the source tree's path (whose absence the tool then
// names).
inline std::string repo_file(const std::string& rel) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<fs::path> roots = {fs::path(FMPP_SOURCE_DIR)};
  char exe[4096];
  const ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (len > 0) {
    const fs::path bin = fs::path(std::string(exe, static_cast<size_t>(len))).parent_path();
    roots.push_back(bin.parent_path());
    roots.push_back(bin);
  }
  for (const fs::path& root : roots) {
    if (fs::is_regular_file(root / rel, ec)) return (root / rel).lexically_normal().string();
  }
  return (fs::path(FMPP_SOURCE_DIR) / rel).lexically_normal().string();
}

}  // namespace fmpp
