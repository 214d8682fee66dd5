// fmpp-render's console: one progress display for the whole frame (rays traced of the
// rays expected, the rate and an ETA) and the closing summary.
//
// The rays expected: the frame's primary rays are known from the start; its shadow and
// secondary rays are estimated from what the frame has shown so far (each level's rays
// per ray of the level before, each level's shadow rays per ray of the level), so the
// total is refined as the frame goes and is exact once the last batch has begun. Within
// a call of the intersector, its passes advance the count.
//
// On a terminal: one line redrawn in place. Otherwise: a plain line every interval (3 s;
// the environment variable FMPP_PROGRESS_INTERVAL, in seconds, sets another, for tests),
// each with its ETA, from a thread of its own so that a long pass cannot silence it.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "sw/render/render.h"

namespace fmpp::tools {

// The frame's rays expected from what its batches have shown (see above).
class RayEstimate {
 public:
  // shadow_prior: shadow rays per primary ray before any are cast (the lights' samples).
  explicit RayEstimate(double shadow_prior) : shadow_prior_(shadow_prior) {}
  void add(const rt::BatchProgress& b);  // a call begun (done false)
  uint64_t expected(uint64_t done) const;

 private:
  double shadow_prior_;
  uint64_t primary_total_ = 0, primary_started_ = 0, band_ = 0;
  int depth_ = 1;
  std::vector<uint64_t> rays_, shadows_;  // per level, over the frame's bands so far
  double band_expected() const;           // rays per primary ray
};

class RenderProgress {
 public:
  RenderProgress(bool quiet, double shadow_prior);
  ~RenderProgress();
  RenderProgress(const RenderProgress&) = delete;
  RenderProgress& operator=(const RenderProgress&) = delete;
  void batch(const rt::BatchProgress& b);         // RenderOptions::progress
  void pass(uint64_t done, uint64_t planned);     // KernelOptions::progress
  void finish();                                  // the frame's end: the last line

 private:
  void start();
  void tick_loop();
  void draw(bool final);  // with mu_ held
  std::string line(bool final) const;

  bool quiet_, tty_;
  double interval_;
  RayEstimate est_;
  std::chrono::steady_clock::time_point t0_, drawn_;
  uint64_t before_call_ = 0, call_rays_ = 0, done_ = 0;
  std::string label_ = "starting";
  bool started_ = false, stop_ = false;
  std::mutex mu_;
  std::condition_variable cv_;
  std::thread ticker_;
};

// Shadow rays per primary ray before any are cast: each light's samples (1 for a point
// or directional light), as if every primary ray hit.
double shadow_prior(const rt::Scene& scene);

// The closing summary (rays by kind, rays redone, FMPP clocks and simulated time, wall
// time by phase) from fmpp-render's report.
void print_summary(std::FILE* f, const nlohmann::json& rep);

}  // namespace fmpp::tools
