// fmpp-report precision, reading the measurements (precision.h): per scene the smallest
// n meeting each accuracy criterion, and the JSON data behind the report and the plots
// (tools/plot_precision.py).
#include <cmath>
#include <functional>

#include "sw/report/precision.h"

namespace fmpp::report::precision {
namespace {

using json = nlohmann::json;

json to_json(const Row& r) {
  return {{"n", r.n},
          {"form", r.form},
          {"steps", r.steps},
          {"broadcasts", r.broadcasts},
          {"raw_cycles", r.raw_cycles},
          {"raw_wrong", r.raw.wrong},
          {"raw_hitmiss", r.raw.hitmiss},
          {"raw_depth_median", r.raw.depth_median},
          {"raw_depth_max", r.raw.depth_max},
          {"cycles", r.cycles},
          {"wrong", r.fallback.wrong},
          {"hitmiss", r.fallback.hitmiss},
          {"depth_median", r.fallback.depth_median},
          {"depth_max", r.fallback.depth_max},
          {"host_triangles", r.host_triangles},
          {"host_tests", r.host_tests},
          {"overflow_rays", r.overflow_rays},
          {"render_cycles", r.render_cycles},
          {"render_host_tests", r.render_host_tests},
          {"flagged", r.flagged},
          {"t_redone", r.t_redone},
          {"certified_rays", r.certified_rays},
          {"render_redone", r.render_redone()},
          {"render_flagged", r.render_flagged},
          {"render_t_host", r.render_t_host},
          {"render_certified", r.render_certified},
          {"render_rays", r.render_rays},
          {"psnr", std::isfinite(r.psnr) ? json(r.psnr) : json(nullptr)},
          {"pixels_off", r.pixels_off}};
}

json to_json(const LeakRow& l) {
  return {{"n", l.n}, {"form", l.form}, {"steps", l.steps}, {"edge_leaks", l.edge_leaks},
          {"edge_rays", l.edge_rays}, {"uniform_leaks", l.uniform_leaks}, {"uniform_rays", l.uniform_rays},
          {"host_triangles", l.host_triangles}};
}

// The first row (smallest n: rows are in increasing n) of `form` meeting `pred`.
const Row* first(const SceneTable& t, const char* form, const std::function<bool(const Row&)>& pred) {
  for (const Row& r : t.rows) {
    if (r.form == form && pred(r)) return &r;
  }
  return nullptr;
}

}  // namespace

std::vector<Choice> choose_n(const SceneResults& res) {
  std::vector<Choice> out;
  for (const SceneTable& t : res.tables) {
    const double ntris = static_cast<double>(t.triangles);
    Choice c;
    c.scene = t.name;
    c.raw = first(t, "const", [](const Row& r) { return r.raw.wrong + r.raw.hitmiss <= 1e-3; });
    c.host = first(t, "const", [&](const Row& r) { return static_cast<double>(r.host_triangles) <= 0.01 * ntris; });
    c.image = first(t, "const", [](const Row& r) { return !(r.psnr < 40); });
    auto redone_ok = [](const Row& r) {
      return static_cast<double>(r.render_redone()) <= 0.01 * static_cast<double>(r.render_rays);
    };
    c.redone = first(t, "const", redone_ok);
    auto all_ok = [&](const Row& r) {
      return r.raw.wrong + r.raw.hitmiss <= 1e-3 && static_cast<double>(r.host_triangles) <= 0.01 * ntris &&
             !(r.psnr < 40) && redone_ok(r);
    };
    c.all = first(t, "const", all_ok);
    c.wt = first(t, "watertight", all_ok);
    out.push_back(c);
  }
  return out;
}

std::string n_of(const Row* r) { return r ? std::to_string(r->n) : std::string("-"); }

json report_data(const Setup& s, const SceneResults& res, const Leaks& leaks, const std::vector<Choice>& choices) {
  json data;
  data["size"] = s.size;
  data["machine"] = {{"blocks", s.machine.blocks}, {"words", s.machine.words}};
  for (const SceneTable& t : res.tables) {
    json js = json::array();
    for (const Row& r : t.rows) js.push_back(to_json(r));
    data["scenes"][t.name] = js;
  }
  json jl = json::array();
  for (const LeakRow& l : leaks.rows) jl.push_back(to_json(l));
  data["leaks"] = jl;
  json choose = json::object();
  for (const Choice& c : choices) {
    choose[c.scene] = {{"raw", n_of(c.raw)}, {"host", n_of(c.host)}, {"image", n_of(c.image)},
                       {"redone", n_of(c.redone)}, {"all", n_of(c.all)},
                       {"watertight", n_of(c.wt)}};
  }
  data["choose"] = choose;
  return data;
}

}  // namespace fmpp::report::precision
