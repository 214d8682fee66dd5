// The precision plan's cache: a plan is a function of the scene's files and the request,
// so a second render of the same scene with the same options reuses it instead of
// sampling again (docs/raytracer.md, "The precision plan"). One small JSON file per
// plan, named by a 64-bit hash of everything the plan depends on.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "sw/plan/plan.h"
#include "sw/scene/scene.h"

namespace rt {

// The default directory: $XDG_CACHE_HOME/fmpp/plans, else $HOME/.cache/fmpp/plans, else
// "" (no cache).
std::string default_plan_cache_dir();

// The hash of the scene's files (their bytes), the request (sizes, targets, samples,
// overrides, the kernel options the plan uses, the RTL configurations), the plan's own
// version and the running program (its path, size and time: a rebuild plans again), as
// 16 hex digits.
std::string plan_key(const Scene& scene, const PlanRequest& req);
// The request's part of that hash: its fields and every kernel option of req.base with
// the role kPlanKey (sw/isect/pass/options.h).
nlohmann::json request_json(const PlanRequest& req);

// The cached plan of `key` in `dir`, or nothing (none, or a file that does not parse as
// one: it is then planned again and overwritten).
std::optional<Plan> load_plan(const std::string& dir, const std::string& key, const PlanRequest& req);
// Stores the plan (creating the directory); a cache that cannot be written is skipped,
// with the reason in *why.
bool store_plan(const std::string& dir, const std::string& key, const Plan& plan, std::string* why);

// The plan as fmpp-render's report gives it (its "plan": every choice with its reason,
// every candidate and every estimate of the cost model).
nlohmann::json plan_report(const Plan& plan);

}  // namespace rt
