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
#include "sw/render/render.h"
#include "sw/scene/scene.h"
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

// The command line, as given.
struct Args {
  std::string scene_file, json_file = "-", out;
  int width = 128, height = 128, depth = -1, repeat = 3;
  double check_tests = 2e8, min_seconds = 0;
  bool robust = false, stream = false;
};

// Parses the command line into *a: -1 to go on, else the exit status (help, a usage error).
int parse(int argc, char** argv, Args* a) {
  CLI::App app{"The frame of fmpp-render traced by Embree on one thread: rays per second, hits against the reference"};
  app.add_option("--scene", a->scene_file, "scene JSON file")->required();
  app.add_option("--width", a->width, "image width")->capture_default_str()->check(fmpp::int_range(1, 16384));
  app.add_option("--height", a->height, "image height")->capture_default_str()->check(fmpp::int_range(1, 16384));
  app.add_option("--max-depth", a->depth, "recursion depth (default: the scene's)")->check(fmpp::int_range(1, 16));
  app.add_option("--repeat", a->repeat, "timed renders, at least (the fastest counts)")
      ->capture_default_str()
      ->check(fmpp::int_range(1, 1000));
  app.add_option("--min-seconds", a->min_seconds, "render again until the intersection calls took this long in all")
      ->capture_default_str()
      ->check(fmpp::finite_range(0.0, 3600.0));
  app.add_option("--check-tests", a->check_tests,
                 "reference ray-triangle tests allowed per batch for the hit check (0: no check)")
      ->capture_default_str()
      ->check(fmpp::finite_range(0.0, 1e12));
  app.add_flag("--robust", a->robust, "Embree's robust (watertight) scene flag");
  app.add_flag("--stream", a->stream,
               "each batch as one coherent ray stream (rtcIntersect1M) instead of rtcIntersect1 per ray");
  app.add_option("--json", a->json_file, "JSON report ('-' for stdout)")->capture_default_str();
  app.add_option("--out", a->out, "PNG of Embree's render");
  app.footer(fmpp::exit_status_footer("an error (a scene or output the tool cannot use; the message says which)"));
  return fmpp::parse_command_line(app, argc, argv);
}

// The timed renders (--repeat, and more until --min-seconds of intersection calls): the
// fastest counts, since on a shared machine the others lost time to other processes, not
// to Embree; the median is reported beside it. Returns the last render's picture.
rt::Image timed_renders(const Args& a, const rt::Scene& scene, rt::EmbreeIntersector& embree,
                        const rt::RenderOptions& ro, nlohmann::json* rep) {
  std::vector<double> secs[rt::kNumBatchKinds], total, render_secs;
  uint64_t rays[rt::kNumBatchKinds] = {};
  rt::RenderStats rs;
  std::unique_ptr<rt::Image> img;
  double timed = 0;
  for (int r = 0; r < a.repeat || (timed < a.min_seconds && r < 1000); ++r) {
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
  const size_t best = static_cast<size_t>(std::min_element(total.begin(), total.end()) - total.begin());
  uint64_t all_rays = 0;
  nlohmann::json& r = *rep;
  for (int k = 0; k < rt::kNumBatchKinds; ++k) {
    const double s = secs[k][best];
    all_rays += rays[k];
    r["by_kind"][rt::to_string(static_cast<rt::BatchKind>(k))] = {
        {"rays", rays[k]}, {"seconds", s}, {"rays_per_second", s > 0 ? rays[k] / s : 0.0}};
  }
  r["rays_total"] = all_rays;
  r["intersect_seconds"] = total[best];
  r["rays_per_second"] = total[best] > 0 ? all_rays / total[best] : 0.0;
  r["median_intersect_seconds"] = median(total);
  r["median_rays_per_second"] = median(total) > 0 ? all_rays / median(total) : 0.0;
  r["render_seconds"] = render_secs[best];
  r["repeat"] = total.size();
  for (int k = 0; k < rt::kNumRayKinds; ++k) r["rays"][rt::to_string(static_cast<rt::RayKind>(k))] = rs.rays[k];
  return std::move(*img);
}

// The hit check (untimed): the same frame again, with a sample of each batch's rays also
// traced by the reference; the disagreements by kind.
nlohmann::json hit_check(const Args& a, const rt::Scene& scene, rt::EmbreeIntersector& embree,
                         const rt::RenderOptions& ro) {
  nlohmann::json check;
  rt::CheckingIntersector checker(embree, scene.triangles, static_cast<uint64_t>(a.check_tests));
  const auto t0 = std::chrono::steady_clock::now();
  rt::render(scene, checker, ro, nullptr);
  rt::HitAgreement all;
  for (int k = 0; k < rt::kNumBatchKinds; ++k) {
    const auto kind = static_cast<rt::BatchKind>(k);
    const rt::HitAgreement& h = checker.agreement(kind);
    all.add(h);
    check["by_kind"][rt::to_string(kind)] = {
        {"rays", checker.rays(kind)}, {"checked", h.checked}, {"same", h.same}, {"at_end", h.at_end}, {"tie", h.tie},
        {"near_miss", h.near_miss}, {"other", h.other}, {"max_t_error", h.max_t_error}};
  }
  check["all"] = {{"checked", all.checked},     {"same", all.same},
                  {"at_end", all.at_end},       {"tie", all.tie},
                  {"near_miss", all.near_miss}, {"other", all.other},
                  {"disagreements", all.disagreements()}, {"max_t_error", all.max_t_error}};
  check["max_tests_per_batch"] = a.check_tests;
  check["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return check;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (const int status = parse(argc, argv, &a); status >= 0) return status;
  bool checking_options = true;  // until the scene is read: a refused value is a usage error
  try {
    rt::check_resolution(a.width, a.height);
    fmpp::check_writable("--json", a.json_file);
    if (!a.out.empty()) fmpp::check_writable("--out", a.out, false);
    checking_options = false;
    const rt::Scene scene = rt::load_scene(a.scene_file);
    rt::EmbreeOptions eo;
    eo.robust = a.robust;
    eo.stream = a.stream;
    rt::EmbreeIntersector embree(scene.triangles, rt::float_spawn_margin(scene.triangles), eo);
    rt::RenderOptions ro;
    ro.width = a.width;
    ro.height = a.height;
    ro.max_depth = a.depth;
    nlohmann::json rep;
    rep["scene"] = a.scene_file;
    rep["triangles"] = scene.triangles.size();
    rep["resolution"] = {a.width, a.height};
    rep["embree"] = {{"version", embree.version()}, {"threads", eo.threads}, {"robust", a.robust},
                     {"call", a.stream ? "rtcIntersect1M, one coherent stream per batch" : "rtcIntersect1, one ray per call"}};
    rep["cpu"] = {{"model", cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()}};
    rep["build_seconds"] = embree.build_seconds();
    const rt::Image img = timed_renders(a, scene, embree, ro, &rep);
    if (!a.out.empty()) img.write_png(a.out);
    if (a.check_tests > 0) rep["check"] = hit_check(a, scene, embree, ro);
    fmpp::write_text(a.json_file, rep.dump(2) + "\n");
    return 0;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "fmpp-embree-bench: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    return fmpp::print_error("fmpp-embree-bench", e.what(), fmpp::error_status(e, checking_options));
  }
}
