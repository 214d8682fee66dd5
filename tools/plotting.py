"""Shared by the plot scripts fmpp-report runs: matplotlib without a display, the
command line (DATA.json OUT_DIR) and saving a figure."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the scripts)


def save(fig, out, rect=None):
    """Lays out, writes out as a PNG and frees the figure."""
    if rect is None:
        fig.tight_layout()
    else:
        fig.tight_layout(rect=rect)
    fig.savefig(out, dpi=110)
    plt.close(fig)


def run(doc, figures):
    """Command line of a plot script: DATA.json OUT_DIR. figures maps a PNG file name to
    a function (data, path) drawing it. Returns the exit status."""
    if len(sys.argv) != 3:
        print(doc, file=sys.stderr)
        return 2
    with open(sys.argv[1]) as f:
        data = json.load(f)
    out = sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for name, draw in figures.items():
        draw(data, os.path.join(out, name))
    return 0
