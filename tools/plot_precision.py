#!/usr/bin/python3
"""Plots of the precision report (docs/generated/precision.md) from the data fmpp-report precision writes.

Usage: plot_precision.py precision_data.json OUT_DIR

precision_scenes.png: per scene and form, the raw machine's primary-ray error rate
against the clocks of a frame of primary rays, and the PSNR of the full render against
its clocks; one curve per scene and form, one point per multiplier width n.
precision_leaks.png: leak rate on the closed sphere and steps per broadcast against n.
precision_pareto.png: per scene, the clocks of the full render against the share of its
rays the host redoes to certify them (flagged, or t from the host): every point gives
the same certified answers (the exact triangle, t within the requested accuracy), so the
trade-off is FMPP clocks against host work; one curve per form, one point per n, and the
Pareto front over all forms.
"""
import math
import sys

from plotting import plt, run, save

FORMS = {
    "generic": dict(linestyle="--", marker="o", mfc="none"),
    "const": dict(linestyle="-", marker="s"),
    "watertight": dict(linestyle=":", marker="^"),
    "object": dict(linestyle="-.", marker="D", mfc="none"),
}
COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]


def fig_scenes(data, out):
    fig, (ax_err, ax_psnr) = plt.subplots(1, 2, figsize=(13, 6.2))
    rays = data["size"] ** 2
    floor = 0.3 * 100.0 / rays  # where a zero error rate is drawn (below one ray)
    top = 0
    for color, (scene, rows) in zip(COLORS, sorted(data["scenes"].items())):
        for form, style in FORMS.items():
            pts = [r for r in rows if r["form"] == form]
            x = [r["raw_cycles"] for r in pts]
            y = [max(100.0 * (r["raw_wrong"] + r["raw_hitmiss"]), floor) for r in pts]
            ax_err.loglog(x, y, color=color, label=f"{scene}, {form}", **style)
            xr = [r["render_cycles"] for r in pts]
            yr = [r["psnr"] if r["psnr"] is not None else math.inf for r in pts]
            top = max([top] + [v for v in yr if math.isfinite(v)])
            ax_psnr.semilogx(xr, yr, color=color, label=f"{scene}, {form}", **style)
            if form == "const":
                # Label n at each point, but only the first of those with no wrong ray.
                at_floor = False
                for r, xx, yy in zip(pts, x, y):
                    if yy <= floor and at_floor:
                        continue
                    at_floor = at_floor or yy <= floor
                    ax_err.annotate(str(r["n"]), (xx, yy), textcoords="offset points", xytext=(3, 3), fontsize=7,
                                    color=color)
    ax_err.axhline(floor, color="gray", linewidth=0.8)
    ax_err.text(ax_err.get_xlim()[0], floor, " no wrong ray", va="bottom", fontsize=8, color="gray")
    ax_err.set_xlabel("FMPP clocks for one frame of primary rays")
    ax_err.set_ylabel("primary rays wrong or hit/miss, raw machine (%)")
    ax_err.set_title("error of the fixed-point format (labels: n, const form)")
    ax_err.grid(True, which="both", alpha=0.3)
    # Identical images (infinite PSNR) are drawn on a line above the finite ones.
    ident = max(top, 40) + 6
    for line in ax_psnr.get_lines():
        ys = [ident if not math.isfinite(v) else v for v in line.get_ydata()]
        line.set_ydata(ys)
    ax_psnr.axhline(ident, color="gray", linewidth=0.8)
    ax_psnr.text(ax_psnr.get_xlim()[0], ident, " identical to the reference", va="bottom", fontsize=8, color="gray")
    ax_psnr.relim()
    ax_psnr.autoscale_view()
    ax_psnr.set_ylim(top=ident + 4)
    ax_psnr.set_xlabel("FMPP clocks for the whole render (with the host fallback)")
    ax_psnr.set_ylabel("PSNR against the reference render (dB)")
    ax_psnr.set_title("image error of the full render")
    ax_psnr.grid(True, which="both", alpha=0.3)
    handles, labels = ax_err.get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=7.5, ncol=4, loc="lower center")
    fig.suptitle(f"Accuracy against cycles, {data['size']} x {data['size']} pixels, golden model, "
                 f"{data['machine']['blocks']} blocks")
    save(fig, out, rect=(0, 0.13, 1, 1))


def fig_leaks(data, out):
    fig, (ax_leak, ax_steps) = plt.subplots(1, 2, figsize=(12, 4.6))
    rows = data["leaks"]
    forms = sorted({r["form"] for r in rows}, key=lambda f: ["paper, raw", "paper, fallback", "watertight"].index(f))
    floor = None
    for r in rows:
        for k in ("edge", "uniform"):
            f = 0.3 * 100.0 / r[k + "_rays"]
            floor = f if floor is None else min(floor, f)
    for form, color in zip(forms, COLORS):
        pts = [r for r in rows if r["form"] == form]
        n = [r["n"] for r in pts]
        for k, style in (("edge", "-o"), ("uniform", "--s")):
            y = [max(100.0 * r[k + "_leaks"] / r[k + "_rays"], floor) for r in pts]
            ax_leak.semilogy(n, y, style, color=color, label=f"{form}, {k} rays")
        ax_steps.plot(n, [r["steps"] for r in pts], "-o", color=color, label=form)
    ax_leak.axhline(floor, color="gray", linewidth=0.8)
    ax_leak.text(min(r["n"] for r in rows), floor, " no leak", va="bottom", fontsize=8, color="gray")
    ax_leak.set_xlabel("multiplier bits n")
    ax_leak.set_ylabel("rays leaking through the closed sphere (%)")
    ax_leak.set_title("leak rate: rays at edges and vertices, and uniform")
    ax_leak.grid(True, which="both", alpha=0.3)
    ax_leak.legend(fontsize=7)
    ax_steps.set_xlabel("multiplier bits n")
    ax_steps.set_ylabel("steps (clocks) per triangle broadcast")
    ax_steps.set_title("cost per broadcast (constant multiply)")
    ax_steps.grid(True, alpha=0.3)
    ax_steps.legend(fontsize=8)
    save(fig, out)


def fig_pareto(data, out):
    scenes = sorted(data["scenes"].items())
    cols = 2
    rows_n = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(rows_n, cols, figsize=(12, 4.8 * rows_n), squeeze=False)
    for ax, (scene, rows) in zip([a for r in axes for a in r], scenes):
        pts_all = []
        floor = None
        for r in rows:
            if r["render_rays"]:
                f = 0.3 * 100.0 / r["render_rays"]
                floor = f if floor is None else min(floor, f)
        for (form, style), color in zip(FORMS.items(), COLORS):
            pts = [r for r in rows if r["form"] == form and r["render_certified"]]
            if not pts:
                continue
            x = [r["render_cycles"] for r in pts]
            y = [max(100.0 * r["render_redone"] / r["render_rays"], floor) for r in pts]
            ax.loglog(x, y, color=color, label=form, **style)
            for r, xx, yy in zip(pts, x, y):
                ax.annotate(str(r["n"]), (xx, yy), textcoords="offset points", xytext=(3, 3), fontsize=7, color=color)
            pts_all += list(zip(x, y))
        # The Pareto front: no other point has both fewer clocks and a smaller host share.
        front = sorted(p for p in pts_all if not any(q[0] <= p[0] and q[1] <= p[1] and q != p for q in pts_all))
        if front:
            ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black", linewidth=2, alpha=0.35,
                    label="Pareto front")
        ax.axhline(floor, color="gray", linewidth=0.8)
        ax.text(ax.get_xlim()[0], floor, " no ray redone", va="bottom", fontsize=8, color="gray")
        ax.axhline(1.0, color="tab:red", linewidth=0.8, linestyle="--")
        ax.set_title(f"{scene}")
        ax.set_xlabel("FMPP clocks for the whole render")
        ax.set_ylabel("rays redone on the host to certify them (%)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7.5)
    for ax in [a for r in axes for a in r][len(scenes):]:
        ax.axis("off")
    fig.suptitle(f"Certified results: FMPP clocks against the host's share, {data['size']} x {data['size']} pixels "
                 f"(labels: n; dashed red: 1 %)")
    save(fig, out)


def main():
    return run(__doc__, {"precision_scenes.png": fig_scenes, "precision_leaks.png": fig_leaks,
                         "precision_pareto.png": fig_pareto})


if __name__ == "__main__":
    sys.exit(main())
