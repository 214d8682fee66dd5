// fmpp-render: Whitted ray tracing with every intersection computed on the FMPP.
//
//   fmpp-render --scene scenes/cornell.json --backend rtl --width 128 --height 128
//               --out cornell.png --report cornell.json
//
// Backends: reference (double precision on the host), cmodel (golden model), rtl
// (Verilated RTL), lockstep (both, cross-checked). The JSON report counts rays by type,
// broadcasts, FMPP cycles, passes, wall time, the simulated time at a clock, overflows,
// the same by batch kind (primary, shadow, secondary), with --oracle the counts culling
// is measured against (docs/raytracer.md), and with --compare-reference the pixels that
// differ from the reference render.
//
// Started by mpirun, every rank drives one FMPP and the passes are handed out among them
// (sw/mpi/, docs/multichip.md); rank 0 writes the picture and the report.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "backends/backend.h"
#include "sw/isect/form_cache.h"
#include "sw/isect/stats_json.h"
#include "common/util/cli_usage.h"
#include "sw/tools/cli_options.h"
#include "sw/tools/kernel_flags.h"
#include "sw/tools/render_args.h"
#include "sw/tools/render_plan.h"
#include "sw/tools/render_progress.h"
#include "sw/plan/plan.h"
#include "sw/plan/plan_cache.h"
#include "sw/render/exact_check.h"
#include "sw/render/render.h"
#include "sw/mpi/render_chips.h"

using namespace fmpp;

namespace {

using render_cli::Args;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }


// Wall time by phase: the report's "phase_seconds" and the summary. From its creation,
// the "total".
class Phases {
 public:
  // Runs f, its wall time kept as phase `name`; returns what f returns.
  template <class F>
  auto time(const char* name, F&& f) {
    struct Stopwatch {
      Phases* p;
      const char* name;
      Clock::time_point t = Clock::now();
      ~Stopwatch() { p->set(name, seconds_since(t)); }
    } watch{this, name};
    return f();
  }
  void set(const char* name, double seconds) { j_[name] = seconds; }
  nlohmann::json with_total() {
    j_["total"] = seconds_since(start_);
    return j_;
  }

 private:
  Clock::time_point start_ = Clock::now();
  nlohmann::json j_;
};

// The scene with --spp and --seed in place of its own (for the plan's sample as for the
// frame); no output may be one of its files.
rt::Scene load(const Args& a) {
  rt::Scene scene = rt::load_scene(a.scene_file);
  if (a.spp_given) scene.spp = a.spp;
  if (a.seed_given) scene.seed = a.seed;
  std::vector<NamedPath> inputs;
  for (const auto& f : scene.files) inputs.push_back({f == a.scene_file ? "--scene" : "mesh of --scene", f});
  check_no_alias({{"--out", a.out}, {"--report", a.report_file}, {"--trace", a.bo.trace_file}}, inputs);
  return scene;
}

// The report's head: the scene, the frame and the lights.
nlohmann::json scene_report(const Args& a, const rt::Scene& scene) {
  nlohmann::json rep;
  rep["scene"] = a.scene_file;
  rep["triangles"] = scene.triangles.size();
  rep["resolution"] = {a.width, a.height};
  rep["backend"] = a.backend;
  rep["spp"] = scene.spp;
  rep["seed"] = scene.seed;
  for (const rt::Light& l : scene.lights) {
    nlohmann::json jl = {{"type", rt::to_string(l.type)}};
    if (l.area()) {
      jl["samples"] = l.samples;
      jl["pool"] = l.pool;
    }
    rep["lights"].push_back(jl);
  }
  return rep;
}

// The frame rendered through `isect`, every answer checked against the exact reference
// where `verify`: the report's "verify_exact" (with the plan's checked renders, `plan`).
rt::Image render_frame(const rt::Scene& scene, rt::Intersector& isect, const rt::RenderOptions& ro, rt::RenderStats* rs,
                       bool verify, const std::string& command, const rt::ExactCheckStats& plan, nlohmann::json* rep) {
  rt::ExactCheckStats st;
  rt::Image img = rt::render_checked(scene, isect, ro, rs, verify, command, &st);
  if (verify) (*rep)["verify_exact"] = rt::exact_check_json(st, plan);
  return img;
}

// The frame on the host, every ray through the double-precision reference.
rt::Image render_on_host(const Args& a, const rt::Scene& scene, const rt::RenderOptions& ro, Phases* phases,
                         rt::RenderStats* rs, nlohmann::json* rep) {
  rt::ReferenceIntersector ref(scene.triangles);
  return phases->time("frame", [&] { return render_frame(scene, ref, ro, rs, a.verify, a.command, {}, rep); });
}

// What the precision plan is asked: it chooses what the options leave open. It starts from
// the defaults of what it chooses (n, the pass order, merge_below: the user's, where
// given, go in the request) and never counts for the oracle.
rt::PlanRequest plan_request(const Args& a, const mpi::Session& session) {
  const isect::KernelOptions defaults;
  rt::PlanRequest pr;
  pr.base = a.given;
  pr.base.n = defaults.n;
  pr.base.coherent = defaults.coherent;
  pr.base.merge_below = defaults.merge_below;
  pr.base.oracle = false;
  pr.width = a.width;
  pr.height = a.height;
  pr.max_depth = a.depth;
  pr.target_wrong_rate = a.target;
  pr.sample_pixels = a.sample_pixels;
  if (a.backend != "cmodel") pr.rtl_configs = backends::rtl_configs();
  pr.choose_mapping = !a.mapping_given && session.size() == 1;
  if (a.bits_given) pr.bits = a.given.n;
  if (!a.quiet) pr.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  if (!a.config.empty()) {
    const Config c = named_config(a.config);
    pr.blocks = c.blocks;
    pr.words = c.words;
  }
  if (a.blocks_given) pr.blocks = a.blocks;
  if (a.words_given) pr.words = a.words;
  // The frame's settings the plan's check renders with (plan.h).
  pr.shadow_stop = !a.no_shadow_stop;
  if (a.order_given) pr.coherent = a.given.coherent;
  if (a.merge_given) pr.merge_below = a.given.merge_below;
  if (!a.shadow_calls.empty()) pr.kinds_together = a.shadow_calls == "together";
  pr.verify_exact = a.verify;
  return pr;
}

// The machine's part of the report: its size and options, its counters in all and by kind
// of batch, and each chip's on several.
void report_machine(const Args& a, const Config& cfg, const isect::KernelOptions& ko, const rt::FmppIntersector& fi,
                    const mpi::RenderChips& chips, bool together, nlohmann::json* rep) {
  nlohmann::json& r = *rep;
  r["fmpp"] = isect::options_json(ko, isect::kReported);
  r["fmpp"].update({{"blocks", cfg.blocks}, {"words", cfg.words}, {"shadow_stop", !a.no_shadow_stop},
                    {"object_parallel", r["plan"]["object_parallel"]},
                    {"shadow_calls", together ? "together" : "apart"}});
  const isect::KernelStats st = chips.total(fi.stats());  // one chip's: its own
  r.update(isect::stats_json(st, a.clock_mhz));
  if (ko.oracle) r["oracle"] = isect::oracle_json(st);
  for (int k = 0; k < rt::kNumBatchKinds; ++k) {
    const auto kind = static_cast<rt::BatchKind>(k);
    const isect::KernelStats kst = chips.total(fi.stats(kind));
    nlohmann::json j = isect::stats_json(kst, a.clock_mhz);
    if (ko.oracle) j["oracle"] = isect::oracle_json(kst);
    r["by_kind"][rt::to_string(kind)] = j;
  }
  // The calls of shadow and secondary rays together (--shadow-calls together): not
  // in either kind's counters above, in the totals.
  if (fi.stats_together().cycles > 0) {
    nlohmann::json j = isect::stats_json(chips.total(fi.stats_together()), a.clock_mhz);
    if (ko.oracle) j["oracle"] = isect::oracle_json(fi.stats_together());
    r["by_kind"]["shadow_and_secondary"] = j;
  }
  if (nlohmann::json c = chips.report(fi.stats(), a.clock_mhz); !c.is_null()) r["chips"] = c;
}

// The frame on the FMPP: the precision plan, then the frame with the plan's machine and
// choices (the frame's kernel options are the plan's), and the machine's report.
rt::Image render_on_fmpp(const Args& a, const rt::Scene& scene, mpi::Session& session, const rt::RenderOptions& ro,
                         tools::RenderProgress& progress, Phases* phases, rt::RenderStats* rs, nlohmann::json* rep) {
  rt::PlanRequest pr = plan_request(a, session);
  // The forms the plan's golden-model runs prepare are kept for the frame: those of the
  // chosen n it finds (the same answers and clocks) come off the plan's seconds.
  isect::FormCache forms(scene.triangles, rt::kPlanFormBytes);
  pr.forms = &forms;
  rt::ExactCheckStats plan_checked;
  pr.verified = &plan_checked;
  const tools::RenderPlan rp = phases->time("plan", [&] {
    return tools::plan_render(scene, pr, {a.plan_cache, a.replan, a.accept_miss, a.quiet}, rep);
  });
  const rt::Plan& plan = rp.plan;
  forms.next_phase();
  const Config cfg = plan.config;
  mpi::RenderChips chips(session);
  auto be = make_backend(a.backend, cfg, a.bo);
  Device dev(be->bus());
  isect::KernelOptions ko = pr.base;
  ko.n = plan.options.n;
  ko.coherent = plan.options.coherent;  // the user's where given (PlanRequest), else the plan's
  ko.merge_below = plan.options.merge_below;
  ko.t_accuracy = plan.options.t_accuracy;  // the user's, or the plan's escalation
  ko.oracle = a.given.oracle;
  ko.progress = [&](uint64_t done, uint64_t planned) { progress.pass(done, planned); };
  ko.forms = &forms;
  chips.agree(scene.triangles, cfg, ko);
  ko.share = chips.attach(dev, a.rank0 == "work");
  rt::FmppIntersector fi(dev, scene.triangles, ko);
  fi.set_shadow_stop(!a.no_shadow_stop);
  for (int k = 0; k < rt::kNumBatchKinds; ++k) {
    if (plan.object[k]) fi.set_mapping(static_cast<rt::BatchKind>(k), isect::Mapping::kObject);
  }
  fi.set_kinds_together(plan.kinds_together);
  rt::Image img = phases->time("frame", [&] {
    rt::Image frame = render_frame(scene, chips.wrap(fi), ro, rs, a.verify, a.command, plan_checked, rep);
    be->finish();
    return frame;
  });
  // The plan's own seconds: its wall time less the preparation the frame reused.
  (*rep)["plan"]["wall_seconds"] = rp.seconds;
  (*rep)["plan"]["reused_by_frame_seconds"] = forms.carried_seconds();
  (*rep)["plan"]["seconds"] = rp.seconds - forms.carried_seconds();
  report_machine(a, cfg, ko, fi, chips, plan.kinds_together, rep);
  return img;
}

// The rays by kind in the report, and those the host redid.
void report_rays(const Args& a, const rt::RenderStats& rs, nlohmann::json* rep) {
  (*rep)["intersect_seconds"] = rs.intersect_seconds;
  for (int k = 0; k < rt::kNumRayKinds; ++k) {
    const char* kind = rt::to_string(static_cast<rt::RayKind>(k));
    (*rep)["rays"][kind] = rs.rays[k];
    if (a.backend != "reference") {
      (*rep)["rays_redone"][kind] = {
          {"flagged", rs.flagged[k]}, {"t_from_host", rs.t_from_host[k]}, {"overflow", rs.overflow[k]}};
    }
  }
}

// The picture, the comparison with the reference (--compare-reference), the report and
// the console's summary.
void write_outputs(const Args& a, const rt::Scene& scene, const rt::Image& img, const rt::RenderOptions& ro,
                   Phases* phases, nlohmann::json* rep) {
  phases->time("write", [&] { img.write(a.out); });
  if (a.compare) {
    phases->time("compare", [&] {
      rt::ReferenceIntersector ref(scene.triangles);
      rt::RenderOptions quiet_ro = ro;
      quiet_ro.progress = nullptr;
      const rt::Image want = rt::render(scene, ref, quiet_ro, nullptr);
      const rt::ImageDiff d = rt::compare(img, want);
      (*rep)["reference_diff"] = {
          {"pixels", d.pixels}, {"pixels_over_8_levels", d.pixels_over}, {"max_delta", d.max_delta}};
    });
  }
  (*rep)["phase_seconds"] = phases->with_total();
  if (!a.report_file.empty()) write_text(a.report_file, rep->dump(2) + "\n");
  if (!a.quiet) {
    std::fprintf(stderr, "wrote %s (%dx%d, %s)\n", a.out.c_str(), a.width, a.height, a.backend.c_str());
    tools::print_summary(stderr, *rep);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::unique_ptr<mpi::Session> session;  // MPI only under a launcher (docs/multichip.md)
  try {
    session = std::make_unique<mpi::Session>(&argc, &argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-render: %s\n", e.what());
    return 1;
  }
  Args a;
  if (const int status = render_cli::parse(argc, argv, &a); status >= 0) return status;
  a.quiet = a.quiet || !session->leader();
  std::string stage = "checking the options";  // for an out-of-memory message
  try {
    render_cli::check(a, *session);
    stage = "loading " + a.scene_file;
    Phases phases;
    const rt::Scene scene = phases.time("load", [&] { return load(a); });
    nlohmann::json rep = scene_report(a, scene);
    tools::RenderProgress progress(a.quiet, tools::shadow_prior(scene));
    rt::RenderOptions ro;
    ro.width = a.width;
    ro.height = a.height;
    ro.max_depth = a.depth;
    ro.progress = [&](const rt::BatchProgress& b) { progress.batch(b); };
    rt::RenderStats rs;
    stage = "rendering " + std::to_string(a.width) + "x" + std::to_string(a.height);
    const auto t0 = Clock::now();
    const rt::Image img = a.backend == "reference" ? render_on_host(a, scene, ro, &phases, &rs, &rep)
                                                   : render_on_fmpp(a, scene, *session, ro, progress, &phases, &rs, &rep);
    progress.finish();
    rep["wall_seconds"] = seconds_since(t0);
    phases.set("intersect", rs.intersect_seconds);
    phases.set("shade", rs.shade_seconds);
    report_rays(a, rs, &rep);
    if (!session->leader()) return 0;  // rank 0 writes
    stage = "writing " + a.out;
    write_outputs(a, scene, img, ro, &phases, &rep);
    return 0;
  } catch (const std::bad_alloc&) {
    if (session->size() > 1) session->abort("fmpp-render", "out of memory while " + stage, 1);
    std::fprintf(stderr, "fmpp-render: out of memory while %s (limits: docs/reliability.md)\n", stage.c_str());
    return 1;
  } catch (const std::exception& e) {
    // On several ranks: the rank and the cause, and every rank ends (no picture is written).
    const int status = error_status(e, stage == "checking the options");  // 2: a usage error
    if (session->size() > 1) session->abort("fmpp-render", e.what(), status);
    return print_error("fmpp-render", e.what(), status);
  }
}
