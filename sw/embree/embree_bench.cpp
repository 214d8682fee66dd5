// fmpp-embree-bench: the frame fmpp-render draws, traced by Embree (one thread) behind
// the same Intersector interface, for the comparison in docs/perf.md ("Against Embree").
//
//   fmpp-embree-bench --scene scenes/spheres_10k.json --width 128 --height 128 --json e.json
//
// Renders the frame --repeat times (and more until --min-seconds of intersection calls);
// the rays per second are those of the rtcIntersect1 (or, with --stream, rtcIntersect1M)
// calls alone in the fastest render (the tracer's shading and the float conversion of
// the rays are not counted), and the BVH build is timed apart. Then renders once more
// with a sample of every batch's rays checked against the exact reference
// (hit_check.h) and reports the disagreements by kind. tools/bench_embree.py sets the
// FMPP's rays per second (from fmpp-render --report) beside these.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "sw/embree/embree_intersector.h"
#include "sw/embree/hit_check.h"
#include "sw/rt/render.h"
#include "sw/rt/scene.h"
#include "common/util/cli_checks.h"
#include "common/util/cli_usage.h"
#include "common/util/files.h"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// The CPU's model name from /proc/cpuinfo ("unknown" elsewhere), for the record.
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const size_t c = line.find(':');
      if (c != std::string::npos) return line.substr(line.find_first_not_of(' ', c + 1));
    }
  }
  return "unknown";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The frame of fmpp-render traced by Embree on one thread: rays per second, hits against the reference"};
  std::string scene_file, json_file = "-", out;
  int width = 128, height = 128, depth = -1, repeat = 3;
  double check_tests = 2e8;
  bool robust = false;
  app.add_option("--scene", scene_file, "scene JSON file")->required();
  app.add_option("--width", width, "image width")->capture_default_str()->check(fmpp::int_range(1, 16384));
  app.add_option("--height", height, "image height")->capture_default_str()->check(fmpp::int_range(1, 16384));
  app.add_option("--max-depth", depth, "recursion depth (default: the scene's)")->check(fmpp::int_range(1, 16));
  app.add_option("--repeat", repeat, "timed renders, at least (the fastest counts)")
      ->capture_default_str()
      ->check(fmpp::int_range(1, 1000));
  double min_seconds = 0;
  app.add_option("--min-seconds", min_seconds, "render again until the intersection calls took this long in all")
      ->capture_default_str()
      ->check(fmpp::finite_range(0.0, 3600.0));
  app.add_option("--check-tests", check_tests,
                 "reference ray-triangle tests allowed per batch for the hit check (0: no check)")
      ->capture_default_str()
      ->check(fmpp::finite_range(0.0, 1e12));
  app.add_flag("--robust", robust, "Embree's robust (watertight) scene flag");
  bool stream = false;
  app.add_flag("--stream", stream, "each batch as one coherent ray stream (rtcIntersect1M) instead of rtcIntersect1 per ray");
  app.add_option("--json", json_file, "JSON report ('-' for stdout)")->capture_default_str();
  app.add_option("--out", out, "PNG of Embree's render");
  app.footer(fmpp::exit_status_footer(
      "an error (a scene or output the tool cannot use; the message says which)"));
  if (const int status = fmpp::parse_command_line(app, argc, argv); status >= 0) return status;

  bool checking_options = true;  // until the scene is read: a refused value is a usage error
  try {
    rt::check_resolution(width, height);
    fmpp::check_writable("--json", json_file);
    if (!out.empty()) fmpp::check_writable("--out", out, false);
    checking_options = false;
    const rt::Scene scene = rt::load_scene(scene_file);
    rt::EmbreeOptions eo;
    eo.robust = robust;
    eo.stream = stream;
    rt::EmbreeIntersector embree(scene.triangles, rt::float_spawn_margin(scene.triangles), eo);
    rt::RenderOptions ro;
    ro.width = width;
    ro.height = height;
    ro.max_depth = depth;

    nlohmann::json rep;
    rep["scene"] = scene_file;
    rep["triangles"] = scene.triangles.size();
    rep["resolution"] = {width, height};
    rep["embree"] = {{"version", embree.version()}, {"threads", eo.threads}, {"robust", robust},
                     {"call", stream ? "rtcIntersect1M, one coherent stream per batch" : "rtcIntersect1, one ray per call"}};
    rep["cpu"] = {{"model", cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()}};
    rep["build_seconds"] = embree.build_seconds();

    // Timed renders.
    std::vector<double> secs[rt::kNumBatchKinds], total, render_secs;
    uint64_t rays[rt::kNumBatchKinds] = {};
    rt::RenderStats rs;
    std::unique_ptr<rt::Image> img;
    double timed = 0;
    for (int r = 0; r < repeat || (timed < min_seconds && r < 1000); ++r) {
      embree.reset_counts();
      rs = rt::RenderStats();
      const auto t0 = std::chrono::steady_clock::now();
      img = std::make_unique<rt::Image>(rt::render(scene, embree, ro, &rs));
      render_secs.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      double all = 0;
      for (int k = 0; k < rt::kNumBatchKinds; ++k) {
        const auto kind = static_cast<rt::BatchKind>(k);
        secs[k].push_back(embree.seconds(kind));
        rays[k] = embree.rays(kind);
        all += embree.seconds(kind);
      }
      total.push_back(all);
      timed += all;
    }
    // The fastest render counts: on a shared machine the others lost time to other
    // processes, not to Embree. The median is reported beside it.
    const size_t best = static_cast<size_t>(std::min_element(total.begin(), total.end()) - total.begin());
    uint64_t all_rays = 0;
    for (int k = 0; k < rt::kNumBatchKinds; ++k) {
      const double s = secs[k][best];
      all_rays += rays[k];
      rep["by_kind"][rt::to_string(static_cast<rt::BatchKind>(k))] = {
          {"rays", rays[k]}, {"seconds", s}, {"rays_per_second", s > 0 ? rays[k] / s : 0.0}};
    }
    rep["rays_total"] = all_rays;
    rep["intersect_seconds"] = total[best];
    rep["rays_per_second"] = total[best] > 0 ? all_rays / total[best] : 0.0;
    rep["median_intersect_seconds"] = median(total);
    rep["median_rays_per_second"] = median(total) > 0 ? all_rays / median(total) : 0.0;
    rep["render_seconds"] = render_secs[best];
    rep["repeat"] = total.size();
    for (int k = 0; k < rt::kNumRayKinds; ++k) rep["rays"][rt::to_string(static_cast<rt::RayKind>(k))] = rs.rays[k];
    if (!out.empty()) img->write_png(out);

    // The hit check (untimed): the same frame again, with a sample of each batch's rays
    // also traced by the reference.
    if (check_tests > 0) {
      rt::CheckingIntersector checker(embree, scene.triangles, static_cast<uint64_t>(check_tests));
      const auto t0 = std::chrono::steady_clock::now();
      rt::render(scene, checker, ro, nullptr);
      rt::HitAgreement all;
      for (int k = 0; k < rt::kNumBatchKinds; ++k) {
        const auto kind = static_cast<rt::BatchKind>(k);
        const rt::HitAgreement& a = checker.agreement(kind);
        all.add(a);
        rep["check"]["by_kind"][rt::to_string(kind)] = {
            {"rays", checker.rays(kind)}, {"checked", a.checked}, {"same", a.same}, {"at_end", a.at_end}, {"tie", a.tie},
            {"near_miss", a.near_miss}, {"other", a.other}, {"max_t_error", a.max_t_error}};
      }
      rep["check"]["all"] = {{"checked", all.checked}, {"same", all.same}, {"at_end", all.at_end}, {"tie", all.tie}, {"near_miss", all.near_miss},
                             {"other", all.other}, {"disagreements", all.disagreements()},
                             {"max_t_error", all.max_t_error}};
      rep["check"]["max_tests_per_batch"] = check_tests;
      rep["check"]["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    fmpp::write_text(json_file, rep.dump(2) + "\n");
    return 0;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "fmpp-embree-bench: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    return fmpp::print_error("fmpp-embree-bench", e.what(), fmpp::error_status(e, checking_options));
  }
}
