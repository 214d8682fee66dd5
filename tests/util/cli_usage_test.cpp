// Usage errors in the tools' own voice (common/util/cli_usage.h): the closest option by
// edit distance, the message of an unexpected argument, and exit status 2 for every
// usage error where CLI11 would give 105, 106, 109 ... (0 for --help).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/util/cli_checks.h"
#include "common/util/cli_usage.h"

namespace {

using fmpp::closest_word;
using fmpp::edit_distance;

TEST(CliUsage, EditDistance) {
  EXPECT_EQ(edit_distance("width", "width"), 0u);
  EXPECT_EQ(edit_distance("widht", "width"), 1u);  // two neighbours swapped: one edit
  EXPECT_EQ(edit_distance("widt", "width"), 1u);
  EXPECT_EQ(edit_distance("wdth", "width"), 1u);
  EXPECT_EQ(edit_distance("height", "width"), 4u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
}

TEST(CliUsage, ClosestWord) {
  const std::vector<std::string> names = {"width", "height", "scene", "seed", "spp", "no-cull", "verify-exact"};
  EXPECT_EQ(closest_word("widht", names), "width");
  EXPECT_EQ(closest_word("sene", names), "scene");
  EXPECT_EQ(closest_word("no-cul", names), "no-cull");
  EXPECT_EQ(closest_word("verify", names), "verify-exact");  // the only name it begins
  EXPECT_EQ(closest_word("frobnicate", names), "");
  EXPECT_EQ(closest_word("x", names), "");
  EXPECT_EQ(closest_word("s", names), "");  // too short to begin one name only
}

// A small tool: --width (1..100), --scene, --config excluding --blocks.
struct Tool {
  CLI::App app{"test tool", "tool"};
  int width = 1, blocks = 1;
  std::string scene, config;
  Tool() {
    app.add_option("--width", width, "width")->check(fmpp::int_range(1, 100));
    app.add_option("--scene", scene, "scene");
    CLI::Option* b = app.add_option("--blocks", blocks, "blocks");
    app.add_option("--config", config, "config")->excludes(b);
  }
  int parse(std::vector<const char*> args) {
    args.insert(args.begin(), "tool");
    return fmpp::parse_command_line(app, static_cast<int>(args.size()), args.data());
  }
};

TEST(CliUsage, ExitStatus) {
  EXPECT_EQ(Tool().parse({"--width", "5"}), -1);  // go on
  EXPECT_EQ(Tool().parse({"--widht", "5"}), 2);     // CLI11: 109 (extras)
  EXPECT_EQ(Tool().parse({"--width", "abc"}), 2);   // CLI11: 105 (validation)
  EXPECT_EQ(Tool().parse({"--width", "500"}), 2);
  EXPECT_EQ(Tool().parse({"--width"}), 2);          // a missing value
  EXPECT_EQ(Tool().parse({"--config", "a", "--blocks", "2"}), 2);  // CLI11: 110 (excludes)
  EXPECT_EQ(Tool().parse({"scene.json"}), 2);
  EXPECT_EQ(Tool().parse({"--help"}), 0);
}

TEST(CliUsage, Messages) {
  Tool t;
  EXPECT_EQ(fmpp::unexpected_argument(t.app, "--widht"), "--widht: unknown option; did you mean --width?");
  EXPECT_EQ(fmpp::unexpected_argument(t.app, "--widht=5"), "--widht: unknown option; did you mean --width?");
  EXPECT_EQ(fmpp::unexpected_argument(t.app, "-width"), "-width: unknown option; did you mean --width?");
  EXPECT_EQ(fmpp::unexpected_argument(t.app, "--frobnicate"), "--frobnicate: unknown option");
  EXPECT_EQ(fmpp::unexpected_argument(t.app, "--"), "--: unknown option");
  EXPECT_EQ(fmpp::unexpected_argument(t.app, "x.json"), "'x.json': unexpected argument (options start with --)");
  // The footer the tools' --help ends with.
  EXPECT_EQ(t.parse({"--help"}), 0);
  EXPECT_NE(t.app.get_footer().find("2 a usage error"), std::string::npos);
}

}  // namespace
