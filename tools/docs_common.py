"""What the documentation generators share (docs.py, docs_plan.py): the repository, the
build's tools and output folder, and running a tool that must succeed.
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gallery  # noqa: E402

ROOT = gallery.ROOT
PY = sys.executable or "/usr/bin/python3"


def out_dir(build):
    return os.path.join(build, "docs")


def tool(build, name):
    path = os.path.join(build, name)
    if not os.path.exists(path):
        sys.exit("%s missing: build it first (make build)" % path)
    return path


def run(cmd, **kw):
    print("+ " + " ".join(cmd), file=sys.stderr, flush=True)
    r = subprocess.run(cmd, **kw)
    if r.returncode != 0:
        sys.exit("%s failed with status %d" % (os.path.basename(cmd[0]), r.returncode))
    return r
