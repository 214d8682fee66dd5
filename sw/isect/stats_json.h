// KernelStats as JSON, for the reports of fmpp-intersect and fmpp-render.
#pragma once

#include <nlohmann/json.hpp>

#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// Every counter of `st`, plus the simulated time at `clock_mhz`.
nlohmann::json stats_json(const KernelStats& st, double clock_mhz = 50);
// The oracles' counts of `st` (KernelOptions::oracle): broadcasts, their clocks in the
// same passes (KernelStats::oracle_cycles) and the measured clocks over them.
nlohmann::json oracle_json(const KernelStats& st);

}  // namespace fmpp::isect
