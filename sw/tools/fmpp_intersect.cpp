// fmpp-intersect: nearest ray-triangle hits computed on an FMPP (or the reference).
//
//   fmpp-intersect --triangles scene.tri --rays rays.txt --backend rtl --mapping ray
//                  --bits 24 --blocks 64 --out hits.txt --report report.json
//
// Output: one line per ray, in input order: "triangle_index t" (hit point o + t d), or
// "-1 inf" for a miss. The JSON report holds the machine's counts: cycles (load,
// compute, readback), passes, broadcasts, steps per broadcast, overflows, host work.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "backends/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/geometry/io.h"
#include "sw/isect/kernels.h"
#include "sw/isect/exact/reference.h"
#include "sw/isect/stats_json.h"
#include "sw/tools/cli_options.h"
#include "backends/rtl/rtl_bus.h"

using namespace fmpp;
using namespace fmpp::isect;

int main(int argc, char** argv) {
  CLI::App app{"Nearest ray-triangle intersections on the FMPP"};
  std::string tri_file, ray_file, out_file = "-", report_file, backend = "cmodel", mapping = "ray", mul = "const";
  unsigned bits = 24, blocks = 64, words = 0;
  std::string config, origins = "auto";
  int cond_bits = -1;
  double t_accuracy = 0;
  unsigned qbits = 20;
  app.add_option("--triangles", tri_file, "triangle file: x1 y1 z1 x2 y2 z2 x3 y3 z3 per line, |x| <= 1e100")
      ->required();
  app.add_option("--rays", ray_file,
                 "ray file: ox oy oz dx dy dz per line, |o| <= 1e100, largest |d| in [1e-100, 1e100]")
      ->required();
  app.add_option("--backend", backend, "reference (double precision on the host) or the machine: " +
                                           join(backend_names(), " | "))
      ->capture_default_str()
      ->check(CLI::IsMember(tool_backends()));
  app.add_option("--mapping", mapping, "ray | object")->capture_default_str()->check(CLI::IsMember({"ray", "object"}));
  app.add_option("--mul", mul, "multiply: const (CSD, specialised to the broadcast constant) | generic")
      ->capture_default_str()
      ->check(CLI::IsMember({"const", "generic"}));
  app.add_option("--bits", bits, "multiplier bits n")->capture_default_str()->check(bits_range());
  CLI::Option* blocks_opt =
      app.add_option("--blocks", blocks, "FMPP blocks")->capture_default_str()->check(int_range(1, map::kMaxBlocks));
  CLI::Option* words_opt = app.add_option("--words", words,
                 "words per block, even (default: what the mapping and multiply need, 26 when rays take the "
                 "arbitrary-origin kernel: --origins general, or rays of origins too few to share one with auto)")
      ->check(even_words());
  exclude_config_sizes(app.add_option("--config", config, "a named FMPP configuration instead of --blocks/--words"),
                       blocks_opt, words_opt);
  app.add_option("--cond-bits", cond_bits,
                 "triangles with condition number above 2^this go to the host (-1: chosen from the bits)")
      ->capture_default_str()
      ->check(int_range(-1, 60));
  app.add_option("--t-accuracy", t_accuracy,
                 "relative accuracy of a certified t; a hit whose bound is looser gets its t on the host "
                 "(0: the default, docs/intersection.md)")
      ->capture_default_str()
      ->check(finite_range(0.0, 0.5));
  app.add_option("--origins", origins,
                 "ray mapping, rays with different origins: auto (paper's method for large shared-origin groups, "
                 "general formulation for the rest) | group | general")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "group", "general"}));
  bool watertight = false;
  app.add_flag("--watertight", watertight, "certified edge functions for rays sharing an origin (no cracks, no vertex moved)");
  bool no_gates = false;
  add_no_gates_flag(app, no_gates);
  app.add_option("--qbits", qbits, "general formulation: bits of the distance quotient")
      ->capture_default_str()
      ->check(int_range(4, 28));
  app.add_option("--out", out_file, "hits file ('-' for stdout)")->capture_default_str();
  app.add_option("--report", report_file, "JSON summary file ('-' for stdout, if --out is a file)");
  BackendOptions bo;
  add_trace_options(app, bo);
  CLI11_PARSE(app, argc, argv);

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
    std::vector<Hit> hits;
    if (backend == "reference") {
      hits = nearest_reference(rays, tris);
    } else {
      KernelOptions opt;
      opt.mapping = parse_mapping(mapping);
      opt.mul = parse_mul_mode(mul);
      opt.n = bits;
      opt.cond_bits = cond_bits;
      opt.t_accuracy = t_accuracy;
      opt.origins = parse_origins(origins);
      opt.qbits = qbits;
      opt.watertight = watertight;
      opt.gates = !no_gates;
      const size_t general = route_rays(rays, opt, config.empty() ? blocks : named_config(config).blocks).general.size();
      const unsigned need = std::max((words_needed(opt) + 1) & ~1u, general ? own_origin_words(opt) : 0u);
      Config cfg{blocks, words ? words : need};
      if (!config.empty()) cfg = named_config(config);
      if (config.empty() && !words && backend != "cmodel") {
        // The RTL exists in its built sizes only: the default words are the fewest of a
        // built configuration with these blocks that holds what the kernel needs.
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
                                          " rays have origins shared by too few rays and take the arbitrary-origin "
                                          "kernel (--origins auto)";
        const std::string k = std::to_string(own_origin_words(opt));
        const std::string fix = config.empty() ? "give --words " + k + " or more (or leave --words out)"
                                               : "use a --config with " + k + " words or more, or --blocks and --words";
        throw std::invalid_argument(given + " is too few: " + why + ", which needs " + k + " words per block; " + fix +
                                    ", or --origins group");
      }
      opt.validate(cfg);  // every option and combination, before any work
      auto be = make_backend(backend, cfg, bo);
      Device dev(be->bus());
      KernelStats st;
      hits = intersect_fmpp(dev, rays, tris, opt, &st);
      be->finish();
      rep["fmpp"] = {{"blocks", cfg.blocks}, {"words", cfg.words}};
      rep["mapping"] = mapping;
      rep["multiply"] = mul;
      rep["bits"] = bits;
      rep["watertight"] = watertight;
      rep.update(stats_json(st));
    }
    rep["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    size_t nhit = 0;
    for (const Hit& h : hits) nhit += h.hit();
    rep["hits"] = nhit;
    write_hits(out_file, hits);
    if (!report_file.empty()) write_text(report_file, rep.dump(2) + "\n");
    return 0;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "fmpp-intersect: out of memory while %s (limits: docs/reliability.md)\n", stage.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-intersect: %s\n", e.what());
    return 1;
  }
}
