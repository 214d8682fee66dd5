// fmpp-render's precision plan (sw/plan/plan.h): taken from the plan cache or made and
// stored, refused before any work on the frame when it misses its error target (unless
// the user accepts that), one summary line on the console, and the report's "plan".
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "sw/plan/plan.h"
#include "sw/scene/scene.h"

namespace fmpp::tools {

struct PlanCli {
  std::string cache;         // --plan-cache ("": none)
  bool replan = false;       // --replan
  bool accept_miss = false;  // --accept-plan-miss
  bool quiet = false;        // --quiet
};

struct RenderPlan {
  rt::Plan plan;
  double seconds = 0;  // the plan's wall time (0 for a cached plan, about)
  bool cached = false;
};

// The plan of `req` for `scene`; (*report)["plan"] gets it with its key, target and
// seconds. Throws std::runtime_error when it misses the target and cli.accept_miss is off,
// naming the limit the user set that stopped its ladder (plan.h), if any.
RenderPlan plan_render(const rt::Scene& scene, const rt::PlanRequest& req, const PlanCli& cli,
                       nlohmann::json* report);

}  // namespace fmpp::tools
