// fmpp-intersect: nearest ray-triangle hits computed on an FMPP (or the reference).
//
//   fmpp-intersect --triangles scene.tri --rays rays.txt --backend rtl --mapping ray \
//                  --bits 24 --blocks 64 --out hits.txt --report report.json
//
// Output: one line per ray, in input order: "triangle_index t" (hit point o + t d), or
// "-1 inf" for a miss. The JSON report holds the machine's counts: cycles (load,
// compute, readback), passes, broadcasts, steps per broadcast, overflows, host work.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>

#include "sw/fmpp/backend.h"
#include "sw/fmpp/device.h"
#include "sw/isect/io.h"
#include "sw/isect/kernels.h"
#include "sw/isect/reference.h"
#include "sw/isect/stats_json.h"
#include "sw/tools/cli_options.h"

using namespace fmpp;
using namespace fmpp::isect;

int main(int argc, char** argv) {
  CLI::App app{"Nearest ray-triangle intersections on the FMPP"};
  std::string tri_file, ray_file, out_file = "-", report_file, backend = "cmodel", mapping = "ray", mul = "const";
  unsigned bits = 24, blocks = 64, words = 0;
  std::string config, origins = "auto";
  int cond_bits = -1;
  unsigned qbits = 20;
  app.add_option("--triangles", tri_file, "triangle file: x1 y1 z1 x2 y2 z2 x3 y3 z3 per line")->required();
  app.add_option("--rays", ray_file, "ray file: ox oy oz dx dy dz per line")->required();
  app.add_option("--backend", backend, "reference | cmodel | rtl | lockstep | systemc");
  app.add_option("--mapping", mapping, "ray | object")->check(CLI::IsMember({"ray", "object"}));
  app.add_option("--mul", mul, "multiply: const (CSD, specialised to the broadcast constant) | generic")
      ->check(CLI::IsMember({"const", "generic"}));
  app.add_option("--bits", bits, "multiplier bits n")->check(CLI::Range(2u, 32u));
  app.add_option("--blocks", blocks, "FMPP blocks")->check(CLI::Range(1u, map::kMaxBlocks));
  app.add_option("--words", words, "words per block (default: what the mapping needs)")->check(CLI::Range(2u, 64u));
  app.add_option("--config", config, "a named FMPP configuration instead of --blocks/--words");
  app.add_option("--cond-bits", cond_bits, "triangles with condition number above 2^this go to the host");
  app.add_option("--origins", origins,
                 "ray mapping, rays with different origins: auto (paper's method for large shared-origin groups, "
                 "general formulation for the rest) | group | general")
      ->check(CLI::IsMember({"auto", "group", "general"}));
  bool watertight = false;
  app.add_flag("--watertight", watertight, "exact-integer edge functions for rays sharing an origin (no cracks)");
  app.add_option("--qbits", qbits, "general formulation: bits of the distance quotient")->check(CLI::Range(4u, 28u));
  app.add_option("--out", out_file, "hits file ('-' for stdout)");
  app.add_option("--report", report_file, "JSON summary");
  BackendOptions bo;
  add_trace_options(app, bo);
  CLI11_PARSE(app, argc, argv);

  try {
    check_trace_backend(backend, bo);
    const std::vector<Triangle> tris = read_triangles(tri_file);
    const std::vector<Ray> rays = read_rays(ray_file);
    nlohmann::json rep;
    rep["triangles"] = tris.size();
    rep["rays"] = rays.size();
    rep["backend"] = backend;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Hit> hits;
    if (backend == "reference") {
      hits = nearest_reference(rays, tris);
    } else {
      KernelOptions opt;
      opt.mapping = parse_mapping(mapping);
      opt.mul = parse_mul_mode(mul);
      opt.n = bits;
      opt.cond_bits = cond_bits;
      opt.origins = parse_origins(origins);
      opt.qbits = qbits;
      opt.watertight = watertight;
      Config cfg{blocks, words ? words : ((words_needed(opt) + 1) & ~1u)};
      if (!config.empty()) cfg = named_config(config);
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
    if (!report_file.empty()) {
      std::ofstream f(report_file);
      if (!f) throw std::runtime_error(report_file + ": cannot write");
      f << rep.dump(2) << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fmpp-intersect: %s\n", e.what());
    return 1;
  }
}
