// KernelStats as JSON (see stats_json.h).
#include "sw/isect/stats_json.h"

namespace fmpp::isect {

nlohmann::json stats_json(const KernelStats& st, double clock_mhz) {
  return {{"cycles", st.cycles},
          {"load_cycles", st.load_cycles},
          {"compute_cycles", st.compute_cycles},
          {"readback_cycles", st.readback_cycles},
          {"instructions", st.instructions},
          {"passes", st.passes},
          {"broadcasts", st.broadcasts},
          {"culled_broadcasts", st.culled},
          {"steps_per_broadcast", st.steps_per_broadcast()},
          {"origin_groups", st.groups},
          {"general_rays", st.general_rays},
          {"overflow_rays", st.overflow_rays},
          {"overflow_triangles", st.overflow_triangles},
          {"overflow_count", st.overflow_rays + st.overflow_triangles},
          {"host_triangles", st.host_triangles},
          {"host_tests", st.host_tests},
          {"snapped_degenerate", st.snapped_degenerate},
          {"clock_mhz", clock_mhz},
          {"simulated_seconds", static_cast<double>(st.cycles) / (clock_mhz * 1e6)}};
}

}  // namespace fmpp::isect
