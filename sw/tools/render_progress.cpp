#include "sw/tools/render_progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace fmpp::tools {

namespace {

double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }

// 1234567 -> "1,234,567".
std::string grouped(uint64_t v) {
  std::string s = std::to_string(v);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

std::string duration(double s) {
  char buf[32];
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%.1f s", std::max(0.0, s));
  } else if (s < 3600) {
    std::snprintf(buf, sizeof buf, "%d min %02d s", static_cast<int>(s) / 60, static_cast<int>(s) % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%d h %02d min", static_cast<int>(s) / 3600, static_cast<int>(s) / 60 % 60);
  }
  return buf;
}

// The interval of the plain lines: FMPP_PROGRESS_INTERVAL seconds if set (0.05 .. 3600).
double line_interval() {
  const char* v = std::getenv("FMPP_PROGRESS_INTERVAL");
  if (!v || !*v) return 3.0;
  char* end = nullptr;
  const double s = std::strtod(v, &end);
  if (end == v || *end || !std::isfinite(s)) return 3.0;
  return std::clamp(s, 0.05, 3600.0);
}

}  // namespace

void RayEstimate::add(const rt::BatchProgress& b) {
  depth_ = std::max(1, b.depth);
  primary_total_ = b.primary_total;
  primary_started_ = b.primary_started;
  rays_.resize(static_cast<size_t>(depth_) + 1, 0);
  shadows_.resize(static_cast<size_t>(depth_) + 1, 0);
  const auto l = static_cast<size_t>(std::clamp(b.level, 0, depth_ - 1));
  if (b.kind == rt::BatchKind::kShadow) {
    shadows_[l] += b.rays - b.next_rays;
    rays_[l + 1] += b.next_rays;
  } else {
    rays_[l] += b.rays;
  }
}

// Rays per primary ray: each level's rays per ray of the level before (the last ratio
// seen where a level has not begun; none before any), each level's shadow rays per ray of
// the level (the last seen, else the prior).
double RayEstimate::band_expected() const {
  if (rays_.empty() || rays_[0] == 0) return 1 + shadow_prior_;
  double total = 0, share = 1, ratio = 0, shadow = shadow_prior_;
  for (size_t l = 0; l < static_cast<size_t>(depth_) && share > 0; ++l) {
    if (l > 0) {
      const bool known = rays_[l] > 0 || shadows_[l - 1] > 0;  // level l - 1 shaded
      if (known) ratio = static_cast<double>(rays_[l]) / static_cast<double>(std::max<uint64_t>(1, rays_[l - 1]));
      share *= ratio;
    }
    if (shadows_[l] > 0 && rays_[l] > 0) shadow = static_cast<double>(shadows_[l]) / static_cast<double>(rays_[l]);
    total += share * (1 + shadow);
  }
  return total;
}

uint64_t RayEstimate::expected(uint64_t done) const {
  const double e = static_cast<double>(primary_total_) * band_expected();
  return std::max(done, static_cast<uint64_t>(std::llround(e)));
}

double shadow_prior(const rt::Scene& scene) {
  double s = 0;
  for (const rt::Light& l : scene.lights) s += l.area() ? l.samples : 1;
  return s;
}

RenderProgress::RenderProgress(bool quiet, double prior)
    : quiet_(quiet), tty_(isatty(2) != 0), interval_(line_interval()), est_(prior) {}

RenderProgress::~RenderProgress() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void RenderProgress::start() {
  started_ = true;
  t0_ = drawn_ = std::chrono::steady_clock::now();
  if (!quiet_) ticker_ = std::thread([this] { tick_loop(); });
}

void RenderProgress::batch(const rt::BatchProgress& b) {
  std::lock_guard<std::mutex> lock(mu_);
  if (!started_) start();
  if (b.done) {
    done_ = std::max(done_, b.traced);
    call_rays_ = 0;
    return;
  }
  est_.add(b);
  before_call_ = done_ = std::max(done_, b.traced);
  call_rays_ = b.rays;
  label_ = "depth " + std::to_string(b.level) + ", " + (b.next_rays ? "shadow + secondary" : rt::to_string(b.kind));
  if (tty_ && !quiet_) draw(false);
}

void RenderProgress::pass(uint64_t done, uint64_t planned) {
  std::lock_guard<std::mutex> lock(mu_);
  if (!started_ || planned == 0 || call_rays_ == 0) return;
  // A call may run several kernels, each with its passes: the count only goes up.
  const uint64_t at = before_call_ + call_rays_ * std::min(done, planned) / planned;
  done_ = std::max(done_, std::min(at, before_call_ + call_rays_));
  if (tty_ && !quiet_ && seconds(std::chrono::steady_clock::now() - drawn_) >= 0.1) draw(false);
}

void RenderProgress::finish() {
  std::unique_lock<std::mutex> lock(mu_);
  if (!started_ || stop_) return;
  stop_ = true;
  if (!quiet_) draw(true);
  lock.unlock();
  cv_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void RenderProgress::tick_loop() {
  std::unique_lock<std::mutex> lock(mu_);
  const double every = tty_ ? 0.5 : interval_;
  while (!cv_.wait_for(lock, std::chrono::duration<double>(every), [this] { return stop_; })) draw(false);
}

std::string RenderProgress::line(bool final) const {
  const double t = seconds(std::chrono::steady_clock::now() - t0_);
  const uint64_t expected = est_.expected(done_);
  const double rate = t > 0 ? static_cast<double>(done_) / t : 0;
  std::ostringstream o;
  o << "frame: " << grouped(done_) << " of " << (final ? "" : "~") << grouped(expected) << " rays ("
    << (expected ? 100 * done_ / expected : 100) << " %), " << grouped(static_cast<uint64_t>(rate)) << " rays/s, ";
  if (final) {
    o << "done in " << duration(t);
  } else {
    o << "ETA " << (rate > 0 ? duration(static_cast<double>(expected - done_) / rate) : std::string("?")) << " ["
      << label_ << "]";
  }
  return o.str();
}

void RenderProgress::draw(bool final) {
  drawn_ = std::chrono::steady_clock::now();
  const std::string s = line(final);
  if (tty_) {
    std::fprintf(stderr, "\r%-100s%s", s.c_str(), final ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s\n", s.c_str());
  }
  std::fflush(stderr);
}

namespace {

// "primary 65,536, shadow 120,001, ..." of an object of counts by kind.
std::string by_kind(const nlohmann::json& j) {
  std::string s;
  for (const auto& [kind, v] : j.items()) s += (s.empty() ? "" : ", ") + kind + " " + grouped(v.get<uint64_t>());
  return s;
}

std::string phase_line(const nlohmann::json& ph) {
  char buf[64];
  std::string s;
  for (const char* k : {"load", "plan", "frame", "write", "compare"}) {
    if (!ph.contains(k)) continue;
    std::snprintf(buf, sizeof buf, "%s%s %.2f s", s.empty() ? "" : ", ", k, ph[k].get<double>());
    s += buf;
    if (std::string(k) == "frame") {
      std::snprintf(buf, sizeof buf, " (intersect %.2f s, shade %.2f s)", ph["intersect"].get<double>(),
                    ph["shade"].get<double>());
      s += buf;
    }
  }
  return s;
}

}  // namespace

void print_summary(std::FILE* f, const nlohmann::json& rep) {
  uint64_t rays = 0;
  for (const auto& v : rep["rays"]) rays += v.get<uint64_t>();
  std::fprintf(f, "  rays          %s: %s\n", grouped(rays).c_str(), by_kind(rep["rays"]).c_str());
  if (rep.contains("rays_redone")) {
    uint64_t redone = 0;
    nlohmann::json kinds;
    for (const auto& [kind, v] : rep["rays_redone"].items()) {
      const uint64_t n = v["flagged"].get<uint64_t>() + v["t_from_host"].get<uint64_t>() + v["overflow"].get<uint64_t>();
      redone += n;
      kinds[kind] = n;
    }
    std::fprintf(f, "  redone (host) %s (%.2f %%): %s\n", grouped(redone).c_str(),
                 rays ? 100.0 * static_cast<double>(redone) / static_cast<double>(rays) : 0.0, by_kind(kinds).c_str());
  }
  if (rep.contains("cycles")) {
    std::fprintf(f, "  FMPP          %s clocks in %s passes: %.3f ms at %g MHz\n",
                 grouped(rep["cycles"].get<uint64_t>()).c_str(), grouped(rep["passes"].get<uint64_t>()).c_str(),
                 1e3 * rep["simulated_seconds"].get<double>(), rep["clock_mhz"].get<double>());
  }
  std::fprintf(f, "  wall time     %.2f s: %s\n", rep["phase_seconds"]["total"].get<double>(),
               phase_line(rep["phase_seconds"]).c_str());
}

}  // namespace fmpp::tools
