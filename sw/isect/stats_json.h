// KernelStats and KernelOptions as JSON, for the reports of fmpp-intersect and fmpp-render,
// the precision plan's cache key and the MPI ranks' agreement.
#pragma once

#include <nlohmann/json.hpp>

#include "sw/isect/pass/options.h"

namespace fmpp::isect {

// Every counter of `st`, plus the simulated time at `clock_mhz`.
nlohmann::json stats_json(const KernelStats& st, double clock_mhz = 50);
// The oracles' counts of `st` (KernelOptions::oracle): broadcasts, their clocks in the
// same passes (KernelStats::oracle_cycles) and the measured clocks over them.
nlohmann::json oracle_json(const KernelStats& st);

// The options of `opt` that have `role` (an OptionRole of options.h), by name: for
// kReported the reports' names and values (a choice by its name: "mapping": "ray"), for the
// others each field's name and its value (a choice by its number, as the plan's cache
// key has always had them).
nlohmann::json options_json(const KernelOptions& opt, OptionRole role);

}  // namespace fmpp::isect
