#!/usr/bin/env python3
"""make gallery: every shipped scene rendered through the golden model, its clocks
against the culling oracles, the README's gallery and docs/raytracer.md's table.

    tools/gallery.py [--build build] [--out-dir build/docs] [--only scans] [--tables-only]

Renders each frame of FRAMES with fmpp-render (golden model, --oracle) and keeps the
reports in BUILD/gallery/; writes one picture per scene to OUT/img/gallery/ and the
generated blocks `gallery` of README.md and `gallery-oracle` of docs/raytracer.md to
OUT/blocks/ (docblock.save_block). It never writes the committed files: `make
docs-update` installs them. --tables-only makes the blocks from the reports already there.
"""
import argparse
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import docblock  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

SCENES = ["cornell", "spheres_1k", "spheres_10k", "one_triangle", "armadillo", "scans", "armadillo_soft"]
# (scene, side): every shipped scene at 128 x 128 (the frames of the culling tables and
# of the Embree comparison) and at 256 x 256 (the gallery's pictures).
FRAMES = [(s, 128) for s in SCENES] + [(s, 256) for s in SCENES]
# The frames tools/bench_embree.py compares: every scene at 128 x 128, the large one also
# at 256 x 256.
BENCH_FRAMES = [(s, 128) for s in SCENES] + [("scans", 256)]
# The frame each scene shows in the gallery.
PICTURE = {s: 256 for s in SCENES}
# The machine of every frame: the golden model, n = 24, 4096 blocks of 32 words (the
# frame of the culling measurements in docs/perf.md), culled, with the oracles.
FMPP_ARGS = ["--backend", "cmodel", "--bits", "24", "--blocks", "4096", "--words", "32"]
CAPTION = {
    "cornell": "Cornell box: mirror panel, glass sphere",
    "spheres_1k": "16 spheres, two mirrors",
    "spheres_10k": "40 spheres, mirrors and glass",
    "one_triangle": "one triangle",
    "armadillo": "scanned armadillo on the stage (mirror wall, glass sphere)",
    "scans": "armadillo and bunny: 127,940 triangles",
    "armadillo_soft": "the armadillo under area lights (soft shadows), 4 samples per pixel",
}


def report_path(build, scene, side, folder="gallery"):
    return os.path.join(build, folder, "%s_%d.json" % (scene, side))


def png_path(build, scene, side, folder="gallery"):
    return os.path.join(build, folder, "%s_%d.png" % (scene, side))


def command(scene, side, report="r.json", out="out.png"):
    return ["build/fmpp-render", "--scene", "scenes/%s.json" % scene] + FMPP_ARGS + [
        "--width", str(side), "--height", str(side), "--oracle", "--report", report, "--out", out]


def readme_mkdir(folder="gallery"):
    """The README's command that makes the folder its gallery commands write into (fmpp-render makes none)."""
    return "mkdir -p build/%s" % folder


def readme_command(scene, side, folder="gallery"):
    """The README's command for one frame: the command render() runs, with the same files under build/."""
    return command(scene, side, report_path("build", scene, side, folder), png_path("build", scene, side, folder))


def render(build, scene, side, folder="gallery"):
    """Renders one frame into BUILD/folder (tools/docs.py's check renders a few into its own folder)."""
    os.makedirs(os.path.join(build, folder), exist_ok=True)
    cmd = command(scene, side, report_path(build, scene, side, folder), png_path(build, scene, side, folder))
    cmd[0] = os.path.join(build, "fmpp-render")
    cmd[2] = os.path.join(ROOT, cmd[2])
    docblock.run(cmd + ["--quiet"])


def load(build, scene, side, folder="gallery"):
    path = report_path(build, scene, side, folder)
    if not os.path.exists(path):
        sys.exit("%s missing: run tools/gallery.py without --tables-only first" % path)
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def rays(rep):
    return sum(rep["rays"].values())


# The clocks measured for the FMPP, from the committed results: make fpga's largest machine
# placed and routed on the iCE40 HX8K (docs/data/fpga/summary.csv) and make asic's clock
# of the 4,096-block chip with its global networks and wires (docs/asic/chip.csv, from
# tools/asic_chip.py; without it, the largest size of docs/asic/summary.csv, timed before
# placement); the same runs docs/generated/area.md reports.
FPGA_CSV = os.path.join(ROOT, "docs", "data", "fpga", "summary.csv")
ASIC_DIR = os.path.join(ROOT, "docs", "asic")


def _csv_rows(path):
    import csv
    with open(path, encoding="utf-8") as f:
        return [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]


def rtl_of(path):
    """The first 12 digits of the RTL hash a result file's header records (tools/rtl_hash.py;
    the ctest figures_fresh fails when it is not today's)."""
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("# rtl-sha256 "):
                return line.split()[2][:12]
    return "?"


def fpga_mhz(path=FPGA_CSV):
    """The clock of the largest placed HX8K run of tools/fpga.sh's summary.csv."""
    placed = [r for r in _csv_rows(path) if r["device"] == "hx8k" and r["placed"] == "1"]
    if not placed:
        sys.exit("%s: no placed hx8k run" % path)
    return float(max(placed, key=lambda r: int(r["blocks"]) * int(r["words"]))["fmax_mhz"])


def asic_clock(asic_dir=ASIC_DIR):
    """(MHz, label) of make asic's clock for the frames: the largest chip of chip.csv,
    flip-flop to flip-flop, or without chip.csv the largest size of summary.csv. The label
    begins "0.18 um cells" and names what was timed and the RTL hash."""
    chip = os.path.join(asic_dir, "chip.csv")
    if os.path.exists(chip):
        rows = _csv_rows(chip)
        if not rows:
            sys.exit("%s: no timed chip" % chip)
        best = max(rows, key=lambda r: int(r["blocks"]))
        return float(best["fmax_reg_mhz"]), "0.18 um cells, the %s x %s chip with its networks' wires, RTL %s" % (
            format(int(best["blocks"]), ","), best["words"], rtl_of(chip))
    path = os.path.join(asic_dir, "summary.csv")
    timed = [r for r in _csv_rows(path) if r.get("fmax_mhz")]
    if not timed:
        sys.exit("%s: no timed size" % path)
    best = max(timed, key=lambda r: int(r["blocks"]) * int(r["words"]))
    return float(best["fmax_mhz"]), "0.18 um cells, %s x %s, RTL %s, unplaced" % (best["blocks"], best["words"],
                                                                                 rtl_of(path))


def projected_clock(asic_mhz=None):
    """(MHz, label): make asic's clock (or asic_mhz) projected to the CPU's process node (tools/node_scale.py)."""
    import node_scale
    return node_scale.project_mhz(asic_clock()[0] if asic_mhz is None else asic_mhz), node_scale.label()


WALL_COLUMN = 12  # the one column of figures_table that depends on the machine (tools/docs.py check)


def figures_table(build, frames, folder="gallery"):
    fpga, (asic, size) = fpga_mhz(), asic_clock()
    proj, proj_label = projected_clock(asic)
    rows = ["| scene | triangles | frame | rays | FMPP clocks | any-hit oracle | culled / any-hit | nearest-hit oracle "
            "| at 50 MHz (the paper's) | at %.1f MHz (iCE40, measured) | at %.1f MHz (%s) "
            "| at %.0f MHz (%s) | golden-model wall time |" % (fpga, asic, size, proj, proj_label),
            "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for scene, side in frames:
        r = load(build, scene, side, folder)
        o = r["oracle"]
        rows.append("| %s | %s | %d x %d | %s | %s | %s | %.2f | %s | %.1f ms | %.1f ms | %.1f ms | %.2f ms | %.3g s |" % (
            scene, docblock.fmt_int(r["triangles"]), side, side, docblock.fmt_int(rays(r)), docblock.fmt_int(r["cycles"]),
            docblock.fmt_int(o["any_hit_cycles"]), o["cycles_over_any_hit"], docblock.fmt_int(o["nearest_hit_cycles"]),
            1e3 * r["cycles"] / 50e6, 1e3 * r["cycles"] / (fpga * 1e6), 1e3 * r["cycles"] / (asic * 1e6),
            1e3 * r["cycles"] / (proj * 1e6), r["wall_seconds"]))
    return rows


def by_kind_table(build, scene, side):
    r = load(build, scene, side)
    rows = ["| %s %d x %d, batch kind | clocks culled (broadcasts) | any-hit oracle | nearest-hit oracle |" % (
        scene, side, side), "| --- | ---: | ---: | ---: |"]
    for kind, k in r["by_kind"].items():
        o = k["oracle"]
        rows.append("| %s | %s (%s) | %s (%s) | %s (%s) |" % (
            kind, docblock.fmt_int(k["cycles"]), docblock.fmt_int(k["broadcasts"]), docblock.fmt_int(o["any_hit_cycles"]),
            docblock.fmt_int(o["any_hit_broadcasts"]), docblock.fmt_int(o["nearest_hit_cycles"]),
            docblock.fmt_int(o["nearest_hit_broadcasts"])))
    return rows


PROVENANCE = {}  # the build directory's gallery folder, set by main()


def provenance():
    return docblock.provenance(PROVENANCE["dir"]) + "; regenerate with `make gallery`."


def readme_block(build):
    scenes = list(PICTURE)
    ncol = min(3, len(scenes))
    lines = ["| " + " | ".join(scenes[:ncol]) + " |", "| " + " | ".join("---" for _ in range(ncol)) + " |"]
    for i in range(0, len(scenes), ncol):
        row = scenes[i:i + ncol]
        pad = " |" * (ncol - len(row))  # a short last row keeps the table's columns
        if i > 0:
            lines.append("| " + " | ".join("**%s**" % s for s in row) + " |" + pad)
        lines.append("| " + " | ".join('<img src="docs/img/gallery/%s.png" width="%d" alt="%s">' % (s, PICTURE[s], CAPTION[s])
                                       for s in row) + " |" + pad)
        lines.append("| " + " | ".join(CAPTION[s] for s in row) + " |" + pad)
    lines += ["", "Each picture's command (golden model; n = 24 and 4096 blocks of 32 words fixed, as in the culling "
              "tables, not chosen by the precision plan; `make gallery` runs them all and writes the same files, then "
              "copies the pictures to build/docs/img/gallery/):", ""]
    lines += ["    " + readme_mkdir()]
    lines += ["    " + " ".join(readme_command(s, PICTURE[s])) for s in scenes]
    lines += ["", "and its clocks against the oracles of culling ([raytracer.md](docs/raytracer.md#culling-against-the-oracle)):",
              ""]
    lines += figures_table(build, [(s, PICTURE[s]) for s in scenes])
    lines += ["", provenance()]
    return "\n".join(lines)


def raytracer_block(build):
    cmd = command("S", "N", "build/gallery/S_N.json", "build/gallery/S_N.png")
    lines = ["`%s` for each frame S, N x N (golden model; `make gallery` runs them all). %s" % (" ".join(cmd), provenance()), ""]
    lines += figures_table(build, FRAMES)
    if ("scans", 256) in FRAMES:
        lines += [""] + by_kind_table(build, "scans", 256)
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build", help="build directory holding fmpp-render")
    ap.add_argument("--out-dir", help="where the pictures and blocks go (default: BUILD/docs; installed by make docs-update)")
    ap.add_argument("--only", action="append", help="render only this scene (repeatable); tables from all reports")
    ap.add_argument("--tables-only", action="store_true", help="no renders: make the blocks from the reports")
    ap.add_argument("--partial", action="store_true",
                    help="tables of the frames rendered so far only (with --only: a quick look, not for the docs)")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    out = os.path.abspath(a.out_dir or os.path.join(build, "docs"))
    for name in a.only or []:
        if name not in PICTURE:
            sys.exit("--only %s: not a gallery scene (%s)" % (name, ", ".join(PICTURE)))
    os.makedirs(os.path.join(build, "gallery"), exist_ok=True)
    PROVENANCE["dir"] = os.path.join(build, "gallery")
    if not a.tables_only:
        docblock.save_provenance(PROVENANCE["dir"], ROOT)
        for scene, side in FRAMES:
            if a.only and scene not in a.only:
                continue
            render(build, scene, side)
    for scene, side in PICTURE.items():
        if os.path.exists(png_path(build, scene, side)):
            os.makedirs(os.path.join(out, "img", "gallery"), exist_ok=True)
            shutil.copyfile(png_path(build, scene, side), os.path.join(out, "img", "gallery", scene + ".png"))
    if a.partial:
        have = lambda s, n: os.path.exists(report_path(build, s, n))  # noqa: E731
        FRAMES[:] = [f for f in FRAMES if have(*f)]
        for s in [s for s in PICTURE if not have(s, PICTURE[s])]:
            del PICTURE[s]
    docblock.save_block(out, "README.md", "gallery", readme_block(build))
    docblock.save_block(out, "docs/raytracer.md", "gallery-oracle", raytracer_block(build))
    print("make docs-update installs them into README.md, docs/raytracer.md and docs/img/gallery/")


if __name__ == "__main__":
    main()
