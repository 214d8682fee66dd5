#!/usr/bin/python3
"""Checks every relative link and anchor of the documentation (the ctest docs_links).

    tools/check_links.py [ROOT]

Reads README.md and every Markdown file under docs/; for each link `[text](target)`,
image `![alt](target)` and `<img src="target">` that is not a URL: the file or folder
must exist, and an anchor (`file.md#anchor`, `#anchor`) must name a heading of that
file as GitHub spells it (lower case, punctuation dropped, spaces to hyphens, repeated
headings numbered -1, -2 ...). Code blocks and inline code are skipped. Exits 1 naming
every broken link.
"""
import os
import re
import sys

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
IMG = re.compile(r"<img\s[^>]*src=\"([^\"]+)\"")


def strip_code(text):
    """text with fenced code blocks and inline code blanked (line numbers kept)."""
    out, fence = [], None
    for line in text.split("\n"):
        m = re.match(r"^\s*(```|~~~)", line)
        if fence:
            if m and m.group(1) == fence:
                fence = None
            out.append("")
            continue
        if m:
            fence = m.group(1)
            out.append("")
            continue
        out.append(re.sub(r"`[^`]*`", "``", line))
    return out


def slug(heading):
    h = re.sub(r"<[^>]+>", "", heading).strip().lower()
    h = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", h)  # a link in a heading keeps its text
    h = re.sub(r"[^\w\- ]", "", h)
    return h.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, found = {}, set()
        with open(path, encoding="utf-8") as f:
            lines = strip_code(f.read())
        with open(path, encoding="utf-8") as f:
            raw = f.read().split("\n")
        for i, line in enumerate(lines):
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if not m:
                continue
            s = slug(re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", raw[i]).group(1))
            n = seen.get(s, 0)
            found.add(s if n == 0 else "%s-%d" % (s, n))
            seen[s] = n + 1
        for m in re.finditer(r"<a\s+(?:name|id)=\"([^\"]+)\"", "\n".join(raw)):
            found.add(m.group(1))
        cache[path] = found
    return cache[path]


def documents(root):
    docs = [os.path.join(root, "README.md")]
    for d, _, files in os.walk(os.path.join(root, "docs")):
        docs += [os.path.join(d, f) for f in sorted(files) if f.endswith(".md")]
    return docs


def check_file(root, path):
    errors = []
    for no, line in enumerate(strip_code(open(path, encoding="utf-8").read()), 1):
        for target in LINK.findall(line) + IMG.findall(line):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto: ...
                continue
            file_part, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            where = "%s:%d: %s" % (os.path.relpath(path, root), no, target)
            if not os.path.exists(dest):
                errors.append("%s: no such file" % where)
            elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                errors.append("%s: no heading with the anchor #%s in %s" % (where, anchor, os.path.relpath(dest, root)))
    return errors


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    files = documents(root)
    errors = [e for f in files for e in check_file(root, f)]
    if errors:
        print("\n".join(errors))
        sys.exit("%d broken link(s) in %d documents" % (len(errors), len(files)))
    print("links: every relative link and anchor of %d documents resolves" % len(files))


if __name__ == "__main__":
    main()
