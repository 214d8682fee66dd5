// Option parsing and checks, and the sums of the counters (see options.h).
#include "sw/isect/pass/options.h"

#include <stdexcept>


namespace fmpp::isect {

Mapping parse_mapping(const std::string& s) {
  if (s == "ray") return Mapping::kRay;
  if (s == "object") return Mapping::kObject;
  throw std::invalid_argument("mapping '" + s + "' is not one of ray, object");
}
MulMode parse_mul_mode(const std::string& s) {
  if (s == "generic") return MulMode::kGeneric;
  if (s == "const") return MulMode::kConst;
  throw std::invalid_argument("multiply '" + s + "' is not one of generic, const");
}
Origins parse_origins(const std::string& s) {
  if (s == "auto") return Origins::kAuto;
  if (s == "group") return Origins::kGroup;
  if (s == "general") return Origins::kGeneral;
  throw std::invalid_argument("origins '" + s + "' is not one of auto, group, general");
}
bool same_form_options(const KernelOptions& a, const KernelOptions& b) {
  bool same = true;
  for_each_kernel_option([&](const OptionInfo& o, auto member, auto) {
    if (o.has(kFormIdentity)) same = same && a.*member == b.*member;
  });
  return same;
}

const char* to_string(Origins o) { return o == Origins::kAuto ? "auto" : o == Origins::kGroup ? "group" : "general"; }
const char* to_string(Mapping m) { return m == Mapping::kRay ? "ray" : "object"; }
const char* to_string(MulMode m) { return m == MulMode::kGeneric ? "generic" : "const"; }

void KernelStats::add(const KernelStats& o) {
  cycles += o.cycles;
  load_cycles += o.load_cycles;
  compute_cycles += o.compute_cycles;
  readback_cycles += o.readback_cycles;
  instructions += o.instructions;
  broadcasts += o.broadcasts;
  passes += o.passes;
  groups += o.groups;
  general_rays += o.general_rays;
  broadcast_steps += o.broadcast_steps;
  test_steps += o.test_steps;
  overflow_rays += o.overflow_rays;
  overflow_triangles += o.overflow_triangles;
  host_triangles += o.host_triangles;
  degenerate_triangles += o.degenerate_triangles;
  host_tests += o.host_tests;
  culled += o.culled;
  box_tests += o.box_tests;
  fmpp_box_tests += o.fmpp_box_tests;
  read_box_tests += o.read_box_tests;
  box_reads += o.box_reads;
  fmpp_node_tests += o.fmpp_node_tests;
  diagonal_tests += o.diagonal_tests;
  edge_tests += o.edge_tests;
  edge_compares += o.edge_compares;
  box_cycles += o.box_cycles;
  gated += o.gated;
  object_searches += o.object_searches;
  unread_rays += o.unread_rays;
  probe_rounds += o.probe_rounds;
  oracle_any += o.oracle_any;
  oracle_nearest += o.oracle_nearest;
  oracle_any_steps += o.oracle_any_steps;
  oracle_nearest_steps += o.oracle_nearest_steps;
  oracle_box += o.oracle_box;
  oracle_box_steps += o.oracle_box_steps;
  for (int f = 0; f < kForms; ++f) {
    form_rays[f] += o.form_rays[f];
    flagged_rays[f] += o.flagged_rays[f];
    t_bound_rays[f] += o.t_bound_rays[f];
    certify_tests[f] += o.certify_tests[f];
    form_broadcasts[f] += o.form_broadcasts[f];
    form_broadcast_cycles[f] += o.form_broadcast_cycles[f];
    form_io_cycles[f] += o.form_io_cycles[f];
  }
  uncertified_rays += o.uncertified_rays;
}



}  // namespace fmpp::isect
