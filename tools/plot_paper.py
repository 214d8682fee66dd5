#!/usr/bin/python3
"""Plots of the paper reproduction (Figs. 5-7) from the data fmpp-report paper writes.

Usage: plot_paper.py paper_data.json OUT_DIR
"""
import sys

from plotting import plt, run, save


def fig_time(data, mapping, title, out):
    fig, axes = plt.subplots(1, 3, figsize=(13, 4), sharey=True)
    for ax, side in zip(axes, (128, 512, 1024)):
        rows = [r for r in data["fig56"] if r["rays"] == side * side]
        m = [r["m"] for r in rows]
        ax.loglog(m, [r["seq"] for r in rows], "k-", label="sequential (33 steps/test)")
        ax.loglog(m, [r["paper_" + mapping[:3]] for r in rows], "k--", label="paper model")
        ax.loglog(m, [r[mapping[:3] + "_generic"] for r in rows], "o-", label="ours, generic multiply")
        ax.loglog(m, [r[mapping[:3] + "_const"] for r in rows], "s-", label="ours, CSD multiply")
        ax.set_title(f"{side} x {side} rays")
        ax.set_xlabel("triangles")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("seconds at 50 MHz")
    axes[0].legend(fontsize=8)
    fig.suptitle(title)
    save(fig, out)


def fig7(data, out):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for blocks, marker in ((64 * 64, "o"), (256 * 256, "s")):
        rows = [r for r in data["fig7"] if r["blocks"] == blocks]
        m = [r["m"] for r in rows]
        side = int(round(blocks ** 0.5))
        ax.semilogx(m, [r["paper"] for r in rows], "k" + marker + "--", label=f"{side}^2 blocks, paper model")
        ax.semilogx(m, [r["ray_generic"] for r in rows], marker + "-", label=f"{side}^2 blocks, ours generic")
        ax.semilogx(m, [r["ray_const"] for r in rows], marker + ":", label=f"{side}^2 blocks, ours CSD")
    ax.set_yscale("log")
    ax.set_xlabel("triangles")
    ax.set_ylabel("speedup over the sequential machine")
    ax.set_title("Fig. 7: 1024 x 1024 rays, limited FMPP (ray-parallel, reloading)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    save(fig, out)


def main():
    return run(__doc__, {
        "fig5_ray_parallel.png": lambda d, o: fig_time(
            d, "ray", "Fig. 5: ideal ray-parallel FMPP against the sequential machine", o),
        "fig6_object_parallel.png": lambda d, o: fig_time(
            d, "object", "Fig. 6: ideal object-parallel FMPP against the sequential machine", o),
        "fig7_limited.png": fig7,
    })


if __name__ == "__main__":
    sys.exit(main())
