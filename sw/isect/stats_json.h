// KernelStats as JSON, for the reports of fmpp-intersect and fmpp-render.
#pragma once

#include <nlohmann/json.hpp>

#include "sw/isect/kernels.h"

namespace fmpp::isect {

// Every counter of `st`, plus the simulated time at `clock_mhz`.
nlohmann::json stats_json(const KernelStats& st, double clock_mhz = 50);

}  // namespace fmpp::isect
