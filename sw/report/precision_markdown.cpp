// fmpp-report precision, the Markdown (precision.h): the tables and values of
// docs/generated/precision.md, filled into sw/report/templates/precision.md.in (md_template.h),
// which holds every sentence; the reading of the full run's numbers is
// precision_reading.md.in, a quick run's note precision_reading_quick.md.in.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sw/report/md_template.h"
#include "sw/report/precision.h"

namespace fmpp::report::precision {
namespace {

// A rate in percent, "0" when exactly zero.
std::string pct(double v) {
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, v >= 0.01 ? "%.2f" : "%.3f", 100 * v);
  return buf;
}

std::string sci(double v) {
  if (v == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

std::string big(uint64_t v) {
  char buf[64];
  if (v >= 1000000) {
    std::snprintf(buf, sizeof buf, "%.3gM", static_cast<double>(v) / 1e6);
  } else if (v >= 10000) {
    std::snprintf(buf, sizeof buf, "%.1fk", static_cast<double>(v) / 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(v));
  }
  return buf;
}

std::string db(double v) { return std::isfinite(v) ? fmt(v, 1) : "identical"; }

// a / b in %, "-" when b = 0 (no ray took a certified form).
std::string share(uint64_t a, uint64_t b) {
  return b ? pct(static_cast<double>(a) / static_cast<double>(b)) : std::string("-");
}

// A scene's section: its heading and table.
std::string scene_table(const SceneTable& t) {
  std::ostringstream md;
  md << "## " << t.name << " (" << t.triangles << " triangles)\n\n";
  md << "| n | form | steps/bcast | raw: frame clocks | wrong % | hit/miss % | depth median | depth max | "
        "fallback: frame clocks | host tris | host tests | wrong % | hit/miss % | flagged % | t host % | render clocks | "
        "render flagged % | render t host % | PSNR dB | px > 8 |\n";
  md << "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Row& r : t.rows) {
    md << "| " << r.n << " | " << r.form << " | " << fmt(r.steps, 1) << " | " << big(r.raw_cycles) << " | "
       << pct(r.raw.wrong) << " | " << pct(r.raw.hitmiss) << " | " << sci(r.raw.depth_median) << " | "
       << sci(r.raw.depth_max) << " | " << big(r.cycles) << " | " << r.host_triangles << " | " << big(r.host_tests)
       << " | " << pct(r.fallback.wrong) << " | " << pct(r.fallback.hitmiss) << " | " << share(r.flagged, r.certified_rays)
       << " | " << share(r.t_redone, r.certified_rays) << " | " << big(r.render_cycles) << " | "
       << (r.render_certified ? share(r.render_flagged, r.render_rays) : std::string("-")) << " | "
       << (r.render_certified ? share(r.render_t_host, r.render_rays) : std::string("-")) << " | " << db(r.psnr)
       << " | " << r.pixels_off << " |\n";
  }
  md << "\n";
  return md.str();
}

std::string leak_table(const Leaks& leaks) {
  std::ostringstream md;
  md << "| n | form | steps/bcast | edge rays leaking | % | uniform rays leaking | % | host tris |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const LeakRow& l : leaks.rows) {
    md << "| " << l.n << " | " << l.form << " | " << fmt(l.steps, 1) << " | " << l.edge_leaks << " of " << l.edge_rays
       << " | " << pct(static_cast<double>(l.edge_leaks) / static_cast<double>(l.edge_rays)) << " | " << l.uniform_leaks
       << " of " << l.uniform_rays << " | "
       << pct(static_cast<double>(l.uniform_leaks) / static_cast<double>(l.uniform_rays)) << " | " << l.host_triangles
       << " |\n";
  }
  return md.str();
}

// Per scene, the smallest n meeting each criterion (const form unless named).
std::string choice_table(const std::vector<Choice>& choices) {
  std::ostringstream md;
  md << "| scene | raw error <= 0.1 % | host triangles <= 1 % | render PSNR >= 40 dB | redone <= 1 % | all four | "
        "steps/bcast there | watertight: all four | its steps/bcast |\n"
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  auto steps_of = [](const Row* r) { return r ? fmt(r->steps, 1) : std::string("-"); };
  for (const Choice& c : choices) {
    md << "| " << c.scene << " | " << n_of(c.raw) << " | " << n_of(c.host) << " | " << n_of(c.image) << " | "
       << n_of(c.redone) << " | " << n_of(c.all) << " | " << steps_of(c.all) << " | " << n_of(c.wt) << " | "
       << steps_of(c.wt) << " |\n";
  }
  return md.str();
}

// The options the intro quotes after `build/fmpp-report precision`.
std::string options_text(const Options& o) {
  if (o.quick) return " --quick";
  return o.size != 32 ? " --size " + std::to_string(o.size) : std::string();
}

}  // namespace

std::string markdown(const Options& o, const Setup& s, const std::string& date, double seconds,
                     const SceneResults& r, const Leaks& l, const std::vector<Choice>& c) {
  std::string tables;
  for (const SceneTable& t : r.tables) tables += scene_table(t);
  // The reading of the numbers is prose written for the full run; a quick run says so.
  const std::string reading = o.quick ? fill_inline("precision_reading_quick.md.in", {})
                                      : fill_template("precision_reading.md.in", {});
  return fill_template(
      "precision.md.in",
      {{"options", options_text(o)},
       {"date", date},
       {"machine", machine_description()},
       {"seconds", fmt(seconds)},
       {"blocks", std::to_string(s.machine.blocks)},
       {"words", std::to_string(s.machine.words)},
       {"config", o.quick ? "small" : "medium"},
       {"size", std::to_string(s.size)},
       {"consistency", r.consistent ? std::string() : fill_template("precision_inconsistent.md.in", {})},
       {"scene_tables", tables},
       {"sphere_triangles", std::to_string(l.sphere_triangles)},
       {"edge_rays", std::to_string(l.edge_rays)},
       {"uniform_rays", std::to_string(l.uniform_rays)},
       {"leak_table", leak_table(l)},
       {"choice_table", choice_table(c)},
       {"reading", reading},
       {"minutes", fmt(std::max(1.0, std::round(seconds / 60)))}});
}

}  // namespace fmpp::report::precision
