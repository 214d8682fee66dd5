// fmpp-render's precision plan (see render_plan.h).
#include "sw/tools/render_plan.h"

#include <chrono>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "sw/plan/plan_cache.h"

namespace fmpp::tools {

RenderPlan plan_render(const rt::Scene& scene, const rt::PlanRequest& req, const PlanCli& cli,
                       nlohmann::json* report) {
  const std::string key = rt::plan_key(scene, req);
  std::optional<rt::Plan> cached = cli.replan ? std::nullopt : rt::load_plan(cli.cache, key, req);
  RenderPlan rp;
  rp.cached = cached.has_value();
  if (rp.cached && !cli.quiet) {
    std::fprintf(stderr, "plan: reused %s/%s.json (same scene files and options; --replan plans again)\n",
                 cli.cache.c_str(), key.c_str());
  }
  const auto t0 = std::chrono::steady_clock::now();
  rp.plan = rp.cached ? *cached : rt::make_plan(scene, req);
  rp.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const rt::Plan& plan = rp.plan;
  if (!rp.cached && !cli.cache.empty()) {
    std::string why;
    if (!rt::store_plan(cli.cache, key, plan, &why) && !cli.quiet) {
      std::fprintf(stderr, "plan: not cached (%s)\n", why.c_str());
    }
  }
  if (!plan.met_target && !cli.accept_miss) {
    std::ostringstream t;
    t << req.target_wrong_rate;
    // The limit that stopped the ladder, named with the way around it.
    const std::string limit = req.base.t_accuracy > 0 ? "drop --t-accuracy, " : "";
    throw std::runtime_error("the precision plan cannot keep --error-target " + t.str() + ": " + plan.why_check +
                             "; no picture written (" + limit + "raise --error-target, or give --accept-plan-miss "
                             "to render anyway)");
  }
  if (!plan.met_target && !cli.quiet) {
    std::fprintf(stderr, "warning: rendering although the plan missed its target (--accept-plan-miss): %s\n",
                 plan.why_check.c_str());
  }
  (*report)["plan"] = rt::plan_report(plan);
  (*report)["plan"].update({{"error_target", req.target_wrong_rate},
                            {"accepted_miss", !plan.met_target && cli.accept_miss},
                            {"cached", rp.cached},
                            {"key", key},
                            {"seconds", rp.seconds}});
  if (!cli.quiet) {
    // One short line; the reasons, every candidate and the cost model's estimates are in
    // the report's "plan".
    const bool escalated = plan.escalation != rt::Rung::kFrameMachine;
    const std::string how = req.bits ? "n set by the user"
                            : !plan.met_target ? "nothing the plan may do keeps the error target"
                            : escalated ? std::string("escalated to keep the error target: ") + rt::to_string(plan.escalation)
                            : plan.why_bits.rfind("smallest n", 0) == 0 ? "the smallest n keeping the error target"
                                                                       : "the widest n; some costs over their limits";
    std::string object = rt::object_kinds(plan);
    if (!object.empty()) object = ", " + object + " rays object-parallel";
    if (plan.options.t_accuracy > 0) {
      std::ostringstream t;
      t << plan.options.t_accuracy;
      object += ", t accuracy " + (plan.options.t_accuracy == rt::kExactT ? std::string("exact") : t.str());
    }
    std::fprintf(stderr, "plan: n = %u, %u blocks x %u words%s (%s; %.1f s%s); the reasons are in --report's plan\n",
                 plan.options.n, plan.config.blocks, plan.config.words, object.c_str(), how.c_str(), rp.seconds,
                 rp.cached ? ", cached" : "");
  }
  return rp;
}

}  // namespace fmpp::tools
