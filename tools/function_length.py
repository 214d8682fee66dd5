#!/usr/bin/env python3
"""Functions longer than a reader can hold: lists every function body in the C++ files of
sw/, backends/, cmodel/ and tb/ over --max lines (from the first line of its signature to
its closing brace), and fails on any that tools/function_length_allow.txt does not name
with a reason, or on an entry of that list that names no function over the limit.

Function bodies are found by matching braces in the text with comments, strings,
character literals and preprocessor lines blanked out: a brace at namespace or class
scope whose declaration has a parenthesis (and no '=' outside one) opens a function;
everything to its matching brace, lambdas and local classes included, is that function.
"""
import argparse
import os
import re
import sys

FOLDERS = ("sw", "backends", "cmodel", "tb")
SUFFIXES = (".cpp", ".cc", ".h", ".hpp")
NON_FUNCTION = re.compile(r"^\s*(template\s*<[^{]*?>\s*)?(class|struct|union|enum|namespace|extern)\b")


def blank(text):
    """The text with comments, string and character literals and preprocessor lines
    replaced by spaces (newlines kept, so line numbers stay)."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    while i < n:
        c = text[i]
        if line_start and c == "#":
            j = i
            while j < n and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 2
                    continue
                if text.startswith("/*", j):  # a block comment inside a directive
                    e = text.find("*/", j + 2)
                    j = n if e < 0 else e + 2
                    continue
                j += 1
            wipe(i, j)
            i = j
            continue
        if c == "\n":
            line_start = True
            i += 1
            continue
        if not c.isspace():
            line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            wipe(i, j)
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i + m.end())
            j = n if end < 0 else end + len(m.group(1)) + 2
            wipe(i, j)
            i = j
        elif c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum())):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            wipe(i, j + 1)
            i = j + 1
        else:
            i += 1
    return "".join(out)


def is_function(header):
    if NON_FUNCTION.match(header):
        return False
    h = re.sub(r"\boperator\s*[^\s(]+", "operator", header)
    depth, paren = 0, False
    for ch in h:
        if ch == "(":
            depth += 1
            paren = True
        elif ch == ")":
            depth -= 1
        elif ch == "=" and depth == 0:
            return False
    return paren


def name_of(header):
    h = re.sub(r"\s+", " ", header.strip())
    m = re.search(r"((?:operator\s*\S+?|~?[A-Za-z_][\w:<>,~ ]*?))\s*\(", h)
    if not m:
        return h[:40]
    return m.group(1).split(" ")[-1]


def functions(path):
    """(name, first line, last line) of every function defined in the file."""
    text = blank(open(path, encoding="utf-8", errors="replace").read())
    found = []
    stack = []  # per open brace: True inside a function
    last = 0  # where the current declaration starts (after ; { })
    for i, ch in enumerate(text):
        if ch == "{":
            inside = bool(stack) and stack[-1] is not False
            if inside:
                stack.append(True)
            else:
                header = text[last:i]
                if is_function(header):
                    start = last + len(header) - len(header.lstrip())
                    stack.append((name_of(header), text.count("\n", 0, start) + 1))
                else:
                    stack.append(False)
            last = i + 1
        elif ch == "}":
            top = stack.pop() if stack else False
            if isinstance(top, tuple):
                found.append((top[0], top[1], text.count("\n", 0, i) + 1))
            last = i + 1
        elif ch == ";" and not (stack and stack[-1] is not False):
            last = i + 1
    return found


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--root", default=root)
    ap.add_argument("--max", type=int, default=80, help="longest function allowed, in lines")
    ap.add_argument("--allow", default=os.path.join(root, "tools", "function_length_allow.txt"))
    ap.add_argument("--all", action="store_true", help="list every function over --max, allowed or not")
    a = ap.parse_args()
    allowed = {}
    for line in open(a.allow, encoding="utf-8"):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        key, _, why = line.partition(" ")
        if not why.strip():
            sys.exit("%s: %s has no reason" % (a.allow, key))
        allowed[key] = why.strip()
    long_ones = []
    for folder in FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(a.root, folder)):
            for f in sorted(files):
                if not f.endswith(SUFFIXES):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, a.root)
                for name, first, last in functions(path):
                    if last - first + 1 > a.max:
                        long_ones.append((last - first + 1, "%s:%s" % (rel, name), first))
    long_ones.sort(reverse=True)
    bad = 0
    seen = set()
    for lines, key, first in long_ones:
        seen.add(key)
        if key in allowed:
            if a.all:
                print("%4d lines  %s (line %d), allowed: %s" % (lines, key, first, allowed[key]))
            continue
        print("%4d lines  %s (line %d): over %d lines; cut it into named stages, or allow it in %s with the "
              "reason" % (lines, key, first, a.max, os.path.relpath(a.allow, a.root)))
        bad += 1
    for key in sorted(set(allowed) - seen):
        print("%s: allowed in %s but no longer over %d lines: take it off the list" %
              (key, os.path.relpath(a.allow, a.root), a.max))
        bad += 1
    if bad:
        return 1
    print("function_length: no function over %d lines but the %d allowed" % (a.max, len(allowed)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
