// Outputs: a failed write is an error (never "wrote" and exit 0), a file is
// replaced atomically, outputs may not alias inputs or each other, and helper programs
// get their arguments without a shell.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <fstream>

#include "common/util/output_file.h"
#include "common/util/process.h"
#include "sw/render/image.h"

namespace fmpp {
namespace {

std::string tmp() {
  static const std::string d = [] {
    std::string t = ::testing::TempDir();
    while (t.size() > 1 && t.back() == '/') t.pop_back();
    std::string p = t + "/outputs-XXXXXX";
    if (!::mkdtemp(&p[0])) std::abort();
    return p;
  }();
  return d;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(OutputFile, FullDiskIsAnError) {
  EXPECT_EQ(error_of([] { write_output("/dev/full", "x"); }), "/dev/full: write failed (No space left on device)");
  const rt::Image img(4, 4);
  EXPECT_EQ(error_of([&] { img.write_png("/dev/full"); }), "/dev/full: write failed (No space left on device)");
  EXPECT_EQ(error_of([] { write_output("/dev/null", "x"); }), "no error");
}

TEST(OutputFile, ReplacesAtomicallyAndLeavesNoTemporary) {
  const std::string p = tmp() + "/a.txt";
  write_output(p, "first");
  write_output(p, "second");
  std::ifstream in(p);
  std::string got((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(got, "second");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(tmp())) files += e.path().filename().string().rfind("a.txt", 0) == 0;
  EXPECT_EQ(files, 1);
  EXPECT_EQ(error_of([&] { write_output(tmp(), "x"); }), tmp() + ": cannot write: is a directory");
}

TEST(OutputFile, AliasesAreRefused) {
  const std::string in = tmp() + "/in.obj";
  std::ofstream(in) << "v 0 0 0\n";
  EXPECT_EQ(error_of([&] { check_no_alias({{"--out", tmp() + "/./in.obj"}}, {{"--scene", in}}); }),
            "--out " + tmp() + "/./in.obj is the input --scene " + in + ": it would be overwritten; give another output path");
  EXPECT_EQ(error_of([&] { check_no_alias({{"--out", tmp() + "/x.png"}, {"--report", tmp() + "/../" +
                                                std::filesystem::path(tmp()).filename().string() + "/x.png"}}, {}); }),
            "--report and --out name the same file " + tmp() + "/../" + std::filesystem::path(tmp()).filename().string() +
                "/x.png: one would replace the other; give them different paths");
  EXPECT_EQ(error_of([&] { check_no_alias({{"--out", "/dev/null"}, {"--report", "/dev/null"}}, {}); }), "no error");
  EXPECT_EQ(error_of([&] { check_no_alias({{"--out", tmp() + "/o.png"}, {"--report", "-"}}, {{"--scene", in}}); }), "no error");
}

TEST(RunProgram, ArgumentsReachTheProgramUninterpreted) {
  // Through a shell, this name would run "touch PWNED-14" in the working directory.
  const std::string odd = tmp() + "/x'; touch PWNED-14; echo '";
  run_program({"/usr/bin/touch", odd});
  EXPECT_TRUE(std::filesystem::exists(odd));
  EXPECT_FALSE(std::filesystem::exists("PWNED-14"));
  const std::string spaced = tmp() + "/bob's plots";
  run_program({"/bin/mkdir", spaced});
  EXPECT_TRUE(std::filesystem::is_directory(spaced));
  EXPECT_NE(error_of([] { run_program({"/bin/false"}); }).find("failed with exit status 1"), std::string::npos);
  EXPECT_NE(error_of([] { run_program({"/no/such/program"}); }).find("cannot run '/no/such/program'"),
            std::string::npos);
}

}  // namespace
}  // namespace fmpp
