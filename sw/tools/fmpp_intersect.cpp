// fmpp-intersect: nearest ray-triangle hits computed on an FMPP (or the reference).
//
//   fmpp-intersect --triangles scene.tri --rays rays.txt --backend rtl --mapping ray
//                  --bits 24 --blocks 64 --out hits.txt --report report.json
//
// Output: one line per ray, in input order: "triangle_index t" (hit point o + t d), or
// "-1 inf" for a miss. The JSON report holds the machine's counts: cycles (load,
// compute, readback), passes, broadcasts, steps per broadcast, overflows, host work.
// Every option of the kernels (KernelOptions) is one of the command line's (declared from
// their list: sw/tools/kernel_flags.h), so that the differential tests
// (tests/diff/optrun.py) can draw any of them; the report names those with kReported.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "backends/backend.h"
#include "common/util/cli_usage.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/io.h"
#include "sw/isect/kernels.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/stats_json.h"
#include "sw/tools/cli_options.h"
#include "sw/tools/kernel_flags.h"
#include "backends/rtl/rtl_bus.h"

using namespace fmpp;
using namespace fmpp::isect;

namespace {

// The machine for `opt`: --config, or --blocks with --words (default: what the forms
// need). The RTL exists in its built sizes only: there the default words are the fewest
// of a built configuration with these blocks that holds what the kernels need.
// The machine as the command line names it.
struct MachineFlags {
  std::string backend, config;
  unsigned blocks = 0, words = 0;
};

Config machine(const std::vector<Ray>& rays, const KernelOptions& opt, const MachineFlags& m) {
  const std::string& backend = m.backend;
  const std::string& config = m.config;
  const unsigned blocks = m.blocks, words = m.words;
  const size_t general = route_rays(rays, opt, config.empty() ? blocks : named_config(config).blocks).general.size();
  const unsigned need = std::max((words_needed(opt) + 1) & ~1u, general ? own_origin_words(opt) : 0u);
  Config cfg{blocks, words ? words : need};
  if (!config.empty()) cfg = named_config(config);
  if (config.empty() && !words && backend != "cmodel") {
    for (const std::string& name : backends::rtl_configs()) {
      const Config c = named_config(name);
      if (c.blocks == cfg.blocks && c.words >= need && (cfg.words == need || c.words < cfg.words)) cfg = c;
    }
  }
  if (general && cfg.words < own_origin_words(opt)) {
    const std::string given = config.empty() ? "--words " + std::to_string(cfg.words)
                                             : "--config " + config + " (" + std::to_string(cfg.words) + " words)";
    const std::string why = opt.origins == Origins::kGeneral
                                ? "with --origins general every ray takes the arbitrary-origin kernel"
                                : std::to_string(general) + " of the " + std::to_string(rays.size()) +
                                      " rays take the arbitrary-origin kernel (their origins are shared by too few "
                                      "rays with --origins auto, or they have a tmin or an excluded triangle)";
    const std::string k = std::to_string(own_origin_words(opt));
    const std::string fix = config.empty() ? "give --words " + k + " or more (or leave --words out)"
                                           : "use a --config with " + k + " words or more, or --blocks and --words";
    throw std::invalid_argument(given + " is too few: " + why + ", which needs " + k + " words per block; " + fix +
                                ", or --origins group");
  }
  opt.validate(cfg);  // every option and combination, before any work
  return cfg;
}

// The FMPP's answers, with its counters in *rep.
std::vector<Hit> run_fmpp(const std::vector<Ray>& rays, const std::vector<Triangle>& tris, const KernelOptions& opt,
                          const MachineFlags& m, const BackendOptions& bo, nlohmann::json* rep) {
  const Config cfg = machine(rays, opt, m);
  auto be = make_backend(m.backend, cfg, bo);
  Device dev(be->bus());
  KernelStats st;
  std::vector<Hit> hits = intersect_fmpp(dev, rays, tris, opt, &st);
  be->finish();
  (*rep)["fmpp"] = {{"blocks", cfg.blocks}, {"words", cfg.words}};
  rep->update(options_json(opt, kReported));
  rep->update(stats_json(st));
  if (opt.oracle) (*rep)["oracle"] = oracle_json(st);
  return hits;
}

// The command line, as given.
struct Args {
  std::string tri_file, ray_file, out_file = "-", report_file, backend = "cmodel", config;
  unsigned blocks = 64, words = 0;
  bool hex_t = false;
  tools::KernelFlags flags;  // the kernel options' flags (sw/tools/kernel_flags.h)
  BackendOptions bo;
};

// Parses the command line into *a: -1 to go on, else the exit status (help, a usage error).
int parse(int argc, char** argv, Args* a) {
  CLI::App app{"Nearest ray-triangle intersections on the FMPP"};
  app.add_option("--triangles", a->tri_file, "triangle file: x1 y1 z1 x2 y2 z2 x3 y3 z3 per line, |x| <= 1e100")
      ->required();
  app.add_option("--rays", a->ray_file,
                 "ray file: ox oy oz dx dy dz [tmin tmax [exclude [hint]]] per line, |o| <= 1e100, largest |d| in "
                 "[1e-100, 1e100], tmin >= 0, tmax a number or inf, exclude and hint a triangle index or -1")
      ->required();
  app.add_option("--backend", a->backend,
                 "reference (double precision on the host) or the machine: " + join(backend_names(), " | "))
      ->capture_default_str()
      ->check(CLI::IsMember(tool_backends()));
  CLI::Option* blocks =
      app.add_option("--blocks", a->blocks, "FMPP blocks")->capture_default_str()->check(int_range(1, map::kMaxBlocks));
  CLI::Option* words = app.add_option("--words", a->words,
                                      "words per block, even (default: what the mapping and multiply need, 26 when "
                                      "rays take the arbitrary-origin kernel: --origins general, or rays of origins "
                                      "too few to share one with auto)")
                           ->check(even_words());
  exclude_config_sizes(app.add_option("--config", a->config, "a named FMPP configuration instead of --blocks/--words"),
                       blocks, words);
  a->flags.add(app, tools::FlagTool::kIntersect);
  app.add_option("--out", a->out_file, "hits file ('-' for stdout)")->capture_default_str();
  app.add_flag("--hex-t", a->hex_t, "write each t exactly, as a hexadecimal float (default: 9 significant digits)");
  app.add_option("--report", a->report_file, "JSON summary file ('-' for stdout, if --out is a file)");
  add_trace_options(app, a->bo);
  app.footer(exit_status_footer(
      "an error (a triangle, ray or output file the tool cannot use, options this machine does not take; the "
      "message says which)"));
  return parse_command_line(app, argc, argv);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (const int status = parse(argc, argv, &a); status >= 0) return status;
  const std::string &tri_file = a.tri_file, &ray_file = a.ray_file, &out_file = a.out_file,
                    &report_file = a.report_file, &backend = a.backend, &config = a.config;
  const BackendOptions& bo = a.bo;

  std::string stage = "checking the options";  // for an out-of-memory message
  try {
    check_trace_options(backend, bo);
    check_config_name(backend, config);
    if (out_file == "-" && report_file == "-") {
      throw std::invalid_argument("--out and --report both write to stdout ('-'): give one of them a file");
    }
    // Every output is checked before the work, not after it.
    check_writable("--out", out_file);
    if (!report_file.empty()) check_writable("--report", report_file);
    check_no_alias({{"--out", out_file}, {"--report", report_file}, {"--trace", bo.trace_file}},
                   {{"--triangles", tri_file}, {"--rays", ray_file}});
    stage = "reading " + tri_file;
    const std::vector<Triangle> tris = read_triangles(tri_file);
    stage = "reading " + ray_file;
    const std::vector<Ray> rays = read_rays(ray_file);
    // A file without records is a mistake (a wrong path, a truncated export), not a
    // question with an empty answer: refused by name, before any work.
    if (tris.empty()) throw std::invalid_argument(tri_file + ": holds no triangle (every line is empty or a comment)");
    if (rays.empty()) throw std::invalid_argument(ray_file + ": holds no ray (every line is empty or a comment)");
    nlohmann::json rep;
    rep["triangles"] = tris.size();
    rep["rays"] = rays.size();
    rep["backend"] = backend;
    const auto t0 = std::chrono::steady_clock::now();
    stage = "intersecting " + std::to_string(rays.size()) + " rays with " + std::to_string(tris.size()) + " triangles";
    const std::vector<Hit> hits = backend == "reference"
                                      ? nearest_reference(rays, tris)
                                      : run_fmpp(rays, tris, a.flags.options(), MachineFlags{backend, config, a.blocks, a.words}, bo, &rep);
    rep["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    size_t nhit = 0;
    for (const Hit& h : hits) nhit += h.hit();
    rep["hits"] = nhit;
    write_hits(out_file, hits, a.hex_t);
    if (!report_file.empty()) write_text(report_file, rep.dump(2) + "\n");
    return 0;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "fmpp-intersect: out of memory while %s (limits: docs/reliability.md)\n", stage.c_str());
    return 1;
  } catch (const std::exception& e) {
    return print_error("fmpp-intersect", e.what(), error_status(e, stage == "checking the options"));
  }
}
