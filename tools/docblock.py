"""Generated blocks inside hand-written Markdown, and the facts every measured figure
carries (machine, date). Used by tools/docs.py (make docs, docs-update, docs_check),
tools/gallery.py and tools/bench_embree.py.

A block is the text between the lines `<!-- NAME:begin ... -->` and `<!-- NAME:end -->`;
replace_block rewrites only that text, so the prose around it stays the author's. This
is the one marker syntax of the project's generated text: a whole generated file lives
in docs/generated/ instead.

Generators never write the committed files: they save each block with save_block under
the build directory's docs/ tree (BUILD/docs/blocks/<file>/<NAME>.md, <file> the
committed file's path without .md), and `make docs-update` (tools/docs.py update)
installs the saved blocks with replace_block.
"""
import datetime
import json
import os
import platform
import re
import subprocess
import sys


def replace_block(path, name, text):
    """Replaces the block NAME of the file at path by text; exits naming the file if the
    markers are missing or repeated."""
    with open(path, encoding="utf-8") as f:
        doc = f.read()
    begin = re.compile(r"^<!-- %s:begin[^\n]*-->\n" % re.escape(name), re.M)
    end = re.compile(r"^<!-- %s:end -->$" % re.escape(name), re.M)
    b, e = list(begin.finditer(doc)), list(end.finditer(doc))
    if len(b) != 1 or len(e) != 1 or e[0].start() < b[0].end():
        sys.exit("%s: expected one '<!-- %s:begin -->' ... '<!-- %s:end -->' block" % (path, name, name))
    doc = doc[: b[0].end()] + text.rstrip("\n") + "\n" + doc[e[0].start():]
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(doc)
    os.replace(tmp, path)


def read_block(path, name):
    """The text of the block NAME of the file at path (without its marker lines), or None."""
    with open(path, encoding="utf-8") as f:
        doc = f.read()
    m = re.search(r"^<!-- %s:begin[^\n]*-->\n(.*?)^<!-- %s:end -->$" % (re.escape(name), re.escape(name)), doc, re.M | re.S)
    return m.group(1).rstrip("\n") if m else None


def block_file(out_dir, target, name):
    """Where a generator saves the block NAME of the committed file target (a path
    relative to the repository, e.g. README.md or docs/raytracer.md)."""
    stem = target[:-3] if target.endswith(".md") else target
    return os.path.join(out_dir, "blocks", stem, name + ".md")


def save_block(out_dir, target, name, text):
    path = block_file(out_dir, target, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text.rstrip("\n") + "\n")
    print("wrote %s (block %s of %s)" % (path, name, target))


def saved_blocks(out_dir):
    """(target, name, text) of every block saved under out_dir."""
    found = []
    base = os.path.join(out_dir, "blocks")
    for d, _, files in os.walk(base):
        for f in sorted(files):
            if f.endswith(".md"):
                stem = os.path.relpath(d, base)
                with open(os.path.join(d, f), encoding="utf-8") as h:
                    found.append((stem + ".md", f[:-3], h.read()))
    return sorted(found)


def cpu_model():
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def cpu_mhz():
    """The clock the kernel reports for the first CPU (a VM reports its nominal clock), or 0."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("cpu MHz"):
                    return float(line.split(":", 1)[1])
    except (OSError, ValueError):
        pass
    return 0.0


def load_average():
    """The 1-minute load average when a measurement starts (the machine may be shared), or None."""
    try:
        with open("/proc/loadavg", encoding="utf-8") as f:
            return float(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None


def machine():
    """One line naming the machine: CPU, cores, OS."""
    os_name = "unknown OS"
    try:
        with open("/etc/os-release", encoding="utf-8") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    os_name = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    return "%s, %d cores, %s" % (cpu_model(), os.cpu_count() or 0, os_name)


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")


def git_commit(root):
    try:
        out = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                             check=True)
        dirty = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return out.stdout.strip() + (" + uncommitted changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown commit"


def save_provenance(directory, root):
    """Records in directory/provenance.json when, where and on which commit its
    measurements were made, for tables rewritten later from them."""
    with open(os.path.join(directory, "provenance.json"), "w", encoding="utf-8") as f:
        json.dump({"date": now(), "machine": machine(), "commit": git_commit(root), "load": load_average()}, f)


def provenance(directory):
    """'Measured DATE on MACHINE, commit C' from directory/provenance.json."""
    path = os.path.join(directory, "provenance.json")
    if not os.path.exists(path):
        sys.exit("%s missing: make the measurements first (without --tables-only)" % path)
    with open(path, encoding="utf-8") as f:
        p = json.load(f)
    load = "" if p.get("load") is None else " (load average %.1f at the start)" % p["load"]
    return "Measured %s on %s%s, commit %s" % (p["date"], p["machine"], load, p["commit"])


def run(cmd, log=sys.stderr):
    """Runs cmd (a list), echoing it; exits with its status and name if it fails."""
    print("+ " + " ".join(cmd), file=log, flush=True)
    r = subprocess.run(cmd)
    if r.returncode != 0:
        sys.exit("%s failed with status %d" % (cmd[0], r.returncode))


def fmt_int(n):
    return "{:,}".format(int(n))
