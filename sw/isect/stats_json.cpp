// KernelStats as JSON (see stats_json.h).
#include "sw/isect/stats_json.h"

#include <cmath>
#include <type_traits>

#include "sw/isect/forms/forms.h"

namespace fmpp::isect {
namespace {

template <class T>
nlohmann::json plain(T v) {
  if constexpr (std::is_enum_v<T>) {
    return static_cast<int>(v);
  } else {
    return v;
  }
}
// A value as the reports write it: a choice by its name.
template <class T, class Kind>
nlohmann::json named(T v, Kind) {
  return plain(v);
}
template <class T, class Names>
nlohmann::json named(T v, OptNamed<Names>) {
  for (const auto& [name, value] : Names::kAll) {
    if (value == v) return name;
  }
  return nullptr;
}

}  // namespace

nlohmann::json options_json(const KernelOptions& opt, OptionRole role) {
  nlohmann::json j = nlohmann::json::object();
  for_each_kernel_option([&](const OptionInfo& o, auto member, auto kind) {
    if (!o.has(role)) return;
    if (role == kReported) {
      j[o.report] = named(opt.*member, kind);
    } else {
      j[o.field] = plain(opt.*member);
    }
  });
  return j;
}

nlohmann::json stats_json(const KernelStats& st, double clock_mhz) {
  nlohmann::json forms = nlohmann::json::object();
  for (int f = 0; f < KernelStats::kForms; ++f) {
    if (!st.form_rays[f]) continue;
    forms[form_name(f)] = {{"rays", st.form_rays[f]},
                                {"flagged_rays", st.flagged_rays[f]},
                                {"t_bound_rays", st.t_bound_rays[f]},
                                {"certify_host_tests", st.certify_tests[f]}};
  }
  return {{"cycles", st.cycles},
          {"load_cycles", st.load_cycles},
          {"compute_cycles", st.compute_cycles},
          {"readback_cycles", st.readback_cycles},
          {"instructions", st.instructions},
          {"passes", st.passes},
          {"broadcasts", st.broadcasts},
          {"culled_broadcasts", st.culled},
          {"box_tests", st.box_tests},
          {"fmpp_box_tests", st.fmpp_box_tests},
          {"read_box_tests", st.read_box_tests},
          {"box_reads", st.box_reads},
          {"fmpp_node_tests", st.fmpp_node_tests},
          {"diagonal_tests", st.diagonal_tests},
          {"edge_tests", st.edge_tests},
          {"edge_compares", st.edge_compares},
          {"box_cycles", st.box_cycles},
          {"gated_broadcasts", st.gated},
          {"object_searches", st.object_searches},
          {"unread_rays", st.unread_rays},
          {"probe_rounds", st.probe_rounds},
          {"steps_per_broadcast", st.steps_per_broadcast()},
          {"origin_groups", st.groups},
          {"general_rays", st.general_rays},
          {"overflow_rays", st.overflow_rays},
          {"overflow_triangles", st.overflow_triangles},
          {"overflow_count", st.overflow_rays + st.overflow_triangles},
          {"host_triangles", st.host_triangles},
          {"degenerate_triangles", st.degenerate_triangles},
          {"host_tests", st.host_tests},
          {"flagged_rays", st.flagged_total()},
          {"uncertified_rays", st.uncertified_rays},
          {"certify", forms},
          {"clock_mhz", clock_mhz},
          {"simulated_seconds", static_cast<double>(st.cycles) / (clock_mhz * 1e6)}};
}

nlohmann::json oracle_json(const KernelStats& st) {
  return {{"any_hit_broadcasts", st.oracle_any},
          {"nearest_hit_broadcasts", st.oracle_nearest},
          {"box_broadcasts", st.oracle_box},
          {"box_cycles", static_cast<uint64_t>(std::llround(st.oracle_cycles(st.oracle_box_steps)))},
          {"any_hit_cycles", static_cast<uint64_t>(std::llround(st.oracle_cycles(st.oracle_any_steps)))},
          {"nearest_hit_cycles", static_cast<uint64_t>(std::llround(st.oracle_cycles(st.oracle_nearest_steps)))},
          {"cycles_over_any_hit", st.oracle_any_steps ? static_cast<double>(st.cycles) / st.oracle_cycles(st.oracle_any_steps) : 0.0},
          {"cycles_over_nearest_hit",
           st.oracle_nearest_steps ? static_cast<double>(st.cycles) / st.oracle_cycles(st.oracle_nearest_steps) : 0.0}};
}

}  // namespace fmpp::isect
