// fmpp-render's command line (fmpp_render.cpp): the flags, the values given, and the checks
// made before any work.
#pragma once

#include <cstdint>
#include <string>

#include "backends/backend.h"
#include "sw/isect/pass/options.h"
#include "sw/mpi/render_chips.h"
#include "sw/plan/plan_cache.h"
#include "sw/tools/cli_options.h"
#include "sw/tools/kernel_flags.h"

namespace render_cli {

// The command line, as given.
struct Args {
  // The default scene is the repository's Cornell box wherever the tool is started; the
  // picture goes to the path given, by default render.png in the current directory.
  std::string scene_file = fmpp::repo_file("scenes/cornell.json"), backend = "rtl", config, out = "render.png", report_file;
  int width = 128, height = 128, depth = -1;
  unsigned blocks = 4096, words = 32;  // the plan decides unless given
  double clock_mhz = 50, target = 0.002;
  bool compare = false, quiet = false, replan = false, accept_miss = false, verify = false, no_shadow_stop = false;
  std::string plan_cache = rt::default_plan_cache_dir(), shadow_calls, rank0 = "work";
  int sample_pixels = 3000, spp = 0;
  uint64_t seed = 0;
  fmpp::BackendOptions bo;
  fmpp::tools::KernelFlags kernel_flags;  // the kernel options' flags (sw/tools/kernel_flags.h)
  // Once parsed: the kernel options given, which of the plan's choices the user made, and
  // the command line itself (for --verify-exact's message).
  fmpp::isect::KernelOptions given;
  bool spp_given = false, seed_given = false, bits_given = false, mapping_given = false, order_given = false,
       merge_given = false, blocks_given = false, words_given = false;
  std::string command = "The command:";
};

// Parses the command line into *a: -1 to go on, else the exit status (help, a usage error).
int parse(int argc, char** argv, Args* a);

// Every option and output checked before any work.
void check(const Args& a, const fmpp::mpi::Session& session);

}  // namespace render_cli
