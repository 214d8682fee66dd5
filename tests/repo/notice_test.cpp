// The licence and the data notice: LICENSE is the Apache License 2.0, NOTICE names the
// files of others, and docs/data.md names every data file of the scenes and the tests;
// the scanned meshes are still the bytes of the archive they are said to come from.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "common/util/source_tree.h"

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const fs::path kRoot = FMPP_SOURCE_DIR;

TEST(Notice, LicenceAndNoticeExist) {
  const std::string licence = slurp(kRoot / "LICENSE");
  EXPECT_NE(licence.find("Apache License"), std::string::npos);
  EXPECT_NE(licence.find("Version 2.0, January 2004"), std::string::npos);
  const std::string notice = slurp(kRoot / "NOTICE");
  for (const char* s : {"scenes/armadillo.off", "scenes/bunny.off", "libcgal-demo", "data/meshes/bunny00.off",
                        "/usr/share/doc/libcgal-dev/copyright"}) {
    EXPECT_NE(notice.find(s), std::string::npos) << s;
  }
}

TEST(Notice, EveryDataFileIsNamed) {
  const std::string doc = slurp(kRoot / "docs/data.md");
  ASSERT_FALSE(doc.empty());
  size_t files = 0;
  for (const char* d : {"scenes", "tests/data", "tests/fuzz/corpus"}) {
    for (const auto& e : fs::recursive_directory_iterator(kRoot / d)) {
      if (!e.is_regular_file()) continue;
      ++files;
      // By path from the root, or (in a list of one directory's files) by its name.
      const std::string rel = fs::relative(e.path(), kRoot).generic_string();
      const std::string name = "`" + e.path().filename().string() + "`";
      EXPECT_TRUE(doc.find("`" + rel + "`") != std::string::npos || doc.find(name) != std::string::npos)
          << rel << " is not named in docs/data.md";
    }
  }
  EXPECT_GT(files, 20u);
}

TEST(Notice, ScannedMeshesAreTheArchiveBytes) {
  const std::string tar = "/usr/share/doc/libcgal-dev/data.tar.gz";
  if (!fs::exists(tar)) GTEST_SKIP() << tar << " is not installed (make deps installs libcgal-demo)";
  std::string tmp = ::testing::TempDir();
  const std::string cmd =
      "tar -xzf " + tar + " -C " + tmp + " data/meshes/armadillo.off data/meshes/bunny00.off";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_EQ(slurp(kRoot / "scenes/armadillo.off"), slurp(fs::path(tmp) / "data/meshes/armadillo.off"));
  EXPECT_EQ(slurp(kRoot / "scenes/bunny.off"), slurp(fs::path(tmp) / "data/meshes/bunny00.off"));
}

}  // namespace
