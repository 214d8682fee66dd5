// The precision plan's cache (see plan_cache.h).
#include "sw/plan/plan_cache.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "sw/isect/stats_json.h"

namespace rt {
namespace {

// Bumped whenever what a plan decides, or how, changes.
constexpr const char* kPlanVersion = "plan-9";

uint64_t fnv1a(const std::string& s, uint64_t h) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream o;
  o << f.rdbuf();
  return o.str();
}

Rung rung_named(const std::string& name) {
  for (Rung r : {Rung::kFrameMachine, Rung::kLargerSample, Rung::kWiderN, Rung::kTighterT, Rung::kExactT}) {
    if (name == to_string(r)) return r;
  }
  throw std::invalid_argument("unknown rung " + name);
}

nlohmann::json check_json(const PlanCheck& c) {
  return {{"rung", to_string(c.rung)}, {"n", c.n}, {"t_accuracy", c.t_accuracy}, {"pixels", c.pixels},
          {"pixels_off", c.pixels_off}, {"bound", c.bound}, {"kept", c.kept}, {"rays", c.rays},
          {"rays_redone", c.redone}, {"cycles", c.clocks}, {"seconds", c.seconds}};
}

PlanCheck check_from(const nlohmann::json& j) {
  PlanCheck c;
  c.rung = rung_named(j.at("rung").get<std::string>());
  c.n = j.at("n").get<unsigned>();
  c.t_accuracy = j.at("t_accuracy").get<double>();
  c.pixels = j.at("pixels").get<size_t>();
  c.pixels_off = j.at("pixels_off").get<size_t>();
  c.bound = j.at("bound").get<double>();
  c.kept = j.at("kept").get<bool>();
  c.rays = j.at("rays").get<uint64_t>();
  c.redone = j.at("rays_redone").get<uint64_t>();
  c.clocks = j.at("cycles").get<uint64_t>();
  c.seconds = j.at("seconds").get<double>();
  return c;
}

// What the escalation cost: the share of the sample's rays redone on the rung taken and
// on the first rung (the frame pays the difference), and the plan's clocks and seconds
// on the rungs after the first.
nlohmann::json escalation_json(const Plan& p) {
  // "none": nothing checked (n set by the user).
  nlohmann::json j = {{"taken", p.checks.empty() ? "none" : to_string(p.escalation)}, {"why", p.why_check}};
  size_t first = 0;
  for (size_t i = 0; i < p.checks.size(); ++i) {
    if (p.checks[i].rung == Rung::kFrameMachine) first = i;
  }
  if (p.checks.empty()) return j;
  const auto share = [](const PlanCheck& c) { return c.rays ? static_cast<double>(c.redone) / static_cast<double>(c.rays) : 0; };
  uint64_t clocks = 0;
  double seconds = 0;
  for (size_t i = first + 1; i < p.checks.size(); ++i) {
    clocks += p.checks[i].clocks;
    seconds += p.checks[i].seconds;
  }
  j.update({{"rays_redone_share", share(p.checks.back())},
            {"rays_redone_share_before", share(p.checks[first])},
            {"cycles", clocks},
            {"seconds", seconds}});
  return j;
}

}  // namespace

// The request's fields and every kernel option with the role kPlanKey
// (sw/isect/pass/options.h) of its base.
nlohmann::json request_json(const PlanRequest& r) {
  nlohmann::json j = fmpp::isect::options_json(r.base, fmpp::isect::kPlanKey);
  j.update({{"width", r.width},
            {"height", r.height},
            {"max_depth", r.max_depth},
            {"target", r.target_wrong_rate},
            {"max_host_share", r.max_host_share},
            {"max_flagged_share", r.max_flagged_share},
            {"sample_rays", r.sample_rays},
            {"sample_pixels", r.sample_pixels},
            {"confidence", r.confidence},
            {"rtl_configs", r.rtl_configs},
            {"bits", r.bits ? static_cast<int>(*r.bits) : -1},
            {"blocks", r.blocks ? static_cast<int>(*r.blocks) : -1},
            {"words", r.words ? static_cast<int>(*r.words) : -1},
            {"choose_mapping", r.choose_mapping},
            {"shadow_stop", r.shadow_stop},
            {"user_coherent", r.coherent ? static_cast<int>(*r.coherent) : -1},
            {"user_kinds_together", r.kinds_together ? static_cast<int>(*r.kinds_together) : -1},
            {"user_merge_below", r.merge_below ? static_cast<long long>(*r.merge_below) : -1}});
  return j;
}

std::string default_plan_cache_dir() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::string(x) + "/fmpp/plans";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.cache/fmpp/plans";
  return "";
}

std::string plan_key(const Scene& scene, const PlanRequest& req) {
  uint64_t h = fnv1a(kPlanVersion, 14695981039346656037ull);
  // The program itself: another build may plan differently.
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto size = std::filesystem::file_size(exe, ec);
    const auto when = std::filesystem::last_write_time(exe, ec).time_since_epoch().count();
    h = fnv1a(exe.string() + ":" + std::to_string(size) + ":" + std::to_string(when), h);
  }
  for (const std::string& f : scene.files) h = fnv1a(read_all(f) + '\0', h);
  h = fnv1a(request_json(req).dump(), h);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

namespace {

// A list of the plan as plan_report writes it (a list with no entry is left out).
nlohmann::json list_of(const nlohmann::json& j, const char* name) {
  return j.contains(name) ? j.at(name) : nlohmann::json::array();
}

// The plan's choices and their reasons, as plan_report writes them, into *p (whose
// options are the request's); false for a pass order or a kind of batch it does not know.
bool read_choices(const nlohmann::json& j, Plan* p) {
  p->config = fmpp::Config{j.at("blocks").get<unsigned>(), j.at("words").get<unsigned>()};
  p->config.validate();
  p->options.n = j.at("bits").get<unsigned>();
  const std::string order = j.at("pass_order").get<std::string>();
  if (order != "coherent" && order != "batch") return false;
  p->options.coherent = order == "coherent";
  p->options.merge_below = j.at("merge_below").get<unsigned>();
  p->why_merge = j.at("why_merge").get<std::string>();
  p->met_target = j.at("met_target").get<bool>();
  p->why_bits = j.at("why_bits").get<std::string>();
  p->why_words = j.at("why_words").get<std::string>();
  p->why_blocks = j.at("why_blocks").get<std::string>();
  p->why_order = j.at("why_pass_order").get<std::string>();
  p->why_mapping = j.at("why_mapping").get<std::string>();
  p->kinds_together = j.at("shadow_calls").get<std::string>() == "together";
  p->options.t_accuracy = j.at("t_accuracy").get<double>();
  const std::string taken = j.at("escalation").at("taken").get<std::string>();
  p->escalation = taken == "none" ? Rung::kFrameMachine : rung_named(taken);
  p->why_check = j.at("escalation").at("why").get<std::string>();
  p->kinds_apart_clocks = j.at("shadow_calls_apart_cycles").get<double>();
  p->kinds_together_clocks = j.at("shadow_calls_together_cycles").get<double>();
  p->why_kinds = j.at("why_shadow_calls").get<std::string>();
  for (const auto& k : j.at("object_parallel")) {
    bool known = false;
    for (int i = 0; i < kNumBatchKinds; ++i) {
      if (k.get<std::string>() == to_string(static_cast<BatchKind>(i))) p->object[i] = known = true;
    }
    if (!known) return false;
  }
  return true;
}

// The candidates and the checks, as plan_report writes them, into *p.
void read_candidates(const nlohmann::json& j, Plan* p) {
  for (const auto& c : list_of(j, "candidates")) {
    PlanCandidate pc;
    pc.n = c.at("n").get<unsigned>();
    pc.wrong_rate = c.at("wrong_rate").get<double>();
    pc.host_share = c.at("host_share").get<double>();
    pc.pixel_rate = c.at("pixel_rate").get<double>();
    pc.pixel_bound = c.at("pixel_bound").get<double>();
    pc.pixels_sampled = c.at("pixels_sampled").get<size_t>();
    pc.flagged_share = c.at("flagged_share").get<double>();
    pc.primary_redone = c.at("primary_redone").get<double>();
    pc.primary_sampled = c.at("primary_sampled").get<size_t>();
    pc.sample_cycles = c.at("sample_cycles").get<uint64_t>();
    p->candidates.push_back(pc);
  }
  for (const auto& c : list_of(j, "checks")) p->checks.push_back(check_from(c));
}

// The cost model's estimates (pass sizes, merges, mappings), as plan_report writes them,
// into *p.
void read_estimates(const nlohmann::json& j, Plan* p) {
  for (const auto& e : list_of(j, "pass_sizes")) {
    PassSizeEstimate s;
    s.blocks = e.at("blocks").get<unsigned>();
    s.passes = e.at("passes").get<size_t>();
    s.broadcasts = e.at("estimated_broadcasts").get<uint64_t>();
    s.clocks = e.at("estimated_cycles").get<double>();
    p->pass_sizes.push_back(s);
  }
  for (const auto& e : list_of(j, "merges")) {
    MergeEstimate m;
    m.below = e.at("below").get<unsigned>();
    m.broadcasts = e.at("estimated_broadcasts").get<uint64_t>();
    m.clocks = e.at("estimated_cycles").get<double>();
    m.merged_rays = e.at("merged_rays").get<size_t>();
    p->merges.push_back(m);
  }
  for (const auto& e : list_of(j, "mappings")) {
    MappingEstimate m;
    const std::string kind = e.at("kind").get<std::string>();
    m.kind = kind == "primary" ? BatchKind::kPrimary : kind == "shadow" ? BatchKind::kShadow : BatchKind::kSecondary;
    m.rays = e.at("rays").get<size_t>();
    m.ray_clocks = e.at("ray_parallel_cycles").get<double>();
    m.object_clocks = e.at("object_parallel_cycles").get<double>();
    m.searched = e.at("search_measured").get<bool>();
    m.chosen = e.at("chosen").get<bool>();
    p->mappings.push_back(m);
  }
}

}  // namespace

std::optional<Plan> load_plan(const std::string& dir, const std::string& key, const PlanRequest& req) {
  if (dir.empty()) return std::nullopt;
  std::ifstream f(dir + "/" + key + ".json");
  if (!f) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(f);
    Plan p;
    p.options = req.base;
    if (!read_choices(j, &p)) return std::nullopt;
    read_candidates(j, &p);
    read_estimates(j, &p);
    if (p.options.n < 2 || p.options.n > 32) return std::nullopt;
    return p;
  } catch (const std::exception&) {
    return std::nullopt;  // not a plan of this version: planned again
  }
}

bool store_plan(const std::string& dir, const std::string& key, const Plan& p, std::string* why) {
  if (dir.empty()) return false;
  const nlohmann::json j = plan_report(p);  // the report's "plan" is the cached plan
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string path = dir + "/" + key + ".json", tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << j.dump(1) << "\n";
    if (!f) {
      if (why) *why = "cannot write " + tmp;
      return false;
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    if (why) *why = "cannot write " + path + ": " + ec.message();
    return false;
  }
  return true;
}

nlohmann::json plan_report(const Plan& p) {
  nlohmann::json j = {{"bits", p.options.n}, {"why_bits", p.why_bits}, {"blocks", p.config.blocks},
                      {"why_blocks", p.why_blocks}, {"words", p.config.words}, {"why_words", p.why_words},
                      {"met_target", p.met_target}, {"pass_order", p.options.coherent ? "coherent" : "batch"},
                      {"why_pass_order", p.why_order}, {"merge_below", p.options.merge_below},
                      {"why_merge", p.why_merge}, {"object_parallel", nlohmann::json::array()},
                      {"why_mapping", p.why_mapping}, {"shadow_calls", p.kinds_together ? "together" : "apart"},
                      {"shadow_calls_apart_cycles", p.kinds_apart_clocks},
                      {"shadow_calls_together_cycles", p.kinds_together_clocks}, {"why_shadow_calls", p.why_kinds},
                      {"t_accuracy", p.options.t_accuracy}, {"escalation", escalation_json(p)}};
  for (const PlanCheck& c : p.checks) j["checks"].push_back(check_json(c));
  for (int k = 0; k < kNumBatchKinds; ++k) {
    if (p.object[k]) j["object_parallel"].push_back(to_string(static_cast<BatchKind>(k)));
  }
  for (const MappingEstimate& e : p.mappings) {
    j["mappings"].push_back({{"kind", to_string(e.kind)}, {"rays", e.rays}, {"ray_parallel_cycles", e.ray_clocks},
                             {"object_parallel_cycles", e.object_clocks}, {"search_measured", e.searched},
                             {"chosen", e.chosen}});
  }
  for (const MergeEstimate& e : p.merges) {
    j["merges"].push_back({{"below", e.below}, {"merged_rays", e.merged_rays}, {"estimated_broadcasts", e.broadcasts},
                           {"estimated_cycles", e.clocks}});
  }
  for (const PassSizeEstimate& e : p.pass_sizes) {
    j["pass_sizes"].push_back({{"blocks", e.blocks}, {"passes", e.passes}, {"estimated_broadcasts", e.broadcasts},
                               {"estimated_cycles", e.clocks}});
  }
  for (const PlanCandidate& c : p.candidates) {
    j["candidates"].push_back({{"n", c.n}, {"wrong_rate", c.wrong_rate}, {"host_share", c.host_share},
                               {"pixel_rate", c.pixel_rate}, {"pixel_bound", c.pixel_bound},
                               {"pixels_sampled", c.pixels_sampled}, {"flagged_share", c.flagged_share},
                               {"primary_redone", c.primary_redone}, {"primary_sampled", c.primary_sampled},
                               {"sample_cycles", c.sample_cycles}});
  }
  return j;
}

}  // namespace rt
