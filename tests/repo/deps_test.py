#!/usr/bin/env python3
"""Dependencies run one way: the folders of the repository form no cycle.

Reads two graphs from the source tree:
  includes  a file's folder -> the folder of each "path/x.h" it includes (a path from the
            repository root; "fmpp/x.h" is the golden model's cmodel/include/fmpp/),
  links     the folder of a target (that of its first source file, or of the headers it
            publishes) -> the folder of each first-party target it links,
and checks, at three levels (top-level folders; sub-folders of sw/ and backends/; the
concerns of sw/isect and its forms), that neither graph nor their union has a cycle, so
no pair of folders depends on each other both ways. A form is known to the rest of the
host software through the form table only: no file of sw/ outside sw/isect/forms/
includes a header of one form's folder or names a form's own identifiers. It also checks that no CMake target puts the repository root on its include
path, and that the programs that do not offer the systemc backend do not link SystemC.
The fuzz targets (tests/fuzz/) are a separate clang build and are read for includes only.
Exit status 0 when all hold; otherwise each violation is printed with an example.
"""
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
UNITS = ["common", "cmodel", "rtl", "backends", "tb", "sw", "tests"]
SUBDIVIDED = ["sw", "backends"]  # their sub-folders are units of the second level
SKIP = {"build", ".git"}


def unit(path, level):
    """The unit a repository path belongs to at `level` (1: top-level, 2: sub-folders,
    3: sw/isect's concerns and its forms' folders)."""
    parts = path.split("/")
    if parts[0] not in UNITS:
        return None
    if level == 3 and parts[:2] == ["sw", "isect"]:
        if len(parts) == 3:
            return "sw/isect"
        if parts[2] == "forms" and len(parts) > 4:
            return "/".join(parts[:4])
        return "/".join(parts[:3])
    if level >= 2 and parts[0] in SUBDIVIDED and len(parts) > 2:
        return parts[0] + "/" + parts[1]
    return parts[0]


# A form's own identifiers (its factory, class, layout and certification), which only its
# folder, the forms' shared base (sw/isect/forms/) and the form table
# (sw/isect/form_table.cpp) may name.
FORM_NAMES = re.compile(r"\b(kForm(Paper|Watertight|General|PaperObject)|make_(paper|watertight|general)_form|"
                        r"run_object_parallel|(Paper|Watertight|General)Form|layout::(general|object)|"
                        r"paper_inverse|paper_object_program|paper_bounds|certified_inverse)\b")


def form_violations():
    out = []
    for rel in source_files():
        if not rel.startswith("sw/") or rel.startswith("sw/isect/forms/") or rel == "sw/isect/form_table.cpp":
            continue
        with open(os.path.join(ROOT, rel), errors="replace") as fh:
            for no, line in enumerate(fh, 1):
                code = line.split("//")[0]
                m = re.match(r'\s*#\s*include\s+"(sw/isect/forms/[^/"]+/[^"]+)"', code)
                if m:
                    out.append(f"{rel}:{no}: includes {m.group(1)}, a form's own header")
                m = FORM_NAMES.search(code)
                if m:
                    out.append(f"{rel}:{no}: names {m.group(0)}, a form's own identifier")
    return out


def source_files():
    for top in UNITS:
        for dp, dns, fns in os.walk(os.path.join(ROOT, top)):
            dns[:] = [d for d in dns if d not in SKIP]
            for f in fns:
                if f.endswith((".h", ".cpp", ".in")):
                    yield os.path.relpath(os.path.join(dp, f), ROOT)


def include_edges():
    edges = []  # (from_path, to_path)
    for rel in source_files():
        with open(os.path.join(ROOT, rel), errors="replace") as fh:
            for line in fh:
                m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
                if not m:
                    continue
                inc = m.group(1)
                if inc.startswith("fmpp/"):
                    target = "cmodel/include/" + inc
                elif os.path.exists(os.path.join(ROOT, inc)):
                    target = inc
                else:
                    continue  # generated (Vfmpp_*.h) or beside the file
                edges.append((rel, target))
    return edges


def cmake_files():
    for top in UNITS:
        for dp, dns, fns in os.walk(os.path.join(ROOT, top)):
            dns[:] = [d for d in dns if d not in SKIP]
            if "CMakeLists.txt" in fns:
                yield os.path.relpath(os.path.join(dp, "CMakeLists.txt"), ROOT)


def commands(text, name):
    """The argument lists of every call of `name` in a CMake file (comments removed)."""
    text = re.sub(r"#[^\n]*", "", text)
    for m in re.finditer(r"\b" + name + r"\s*\(([^()]*(?:\([^()]*\)[^()]*)*)\)", text):
        yield m.group(1).split()


def link_graph():
    defined = {}  # target pattern -> CMakeLists path
    links = []  # (CMakeLists path, target, dependency)
    include_dirs = []  # (CMakeLists path, args)
    for cm in cmake_files():
        if cm.startswith("tests/fuzz/"):
            continue
        text = open(os.path.join(ROOT, cm)).read()
        here = os.path.dirname(cm)
        published = {}
        for args in commands(text, "fmpp_public_folders"):
            folders = [a for a in args[1:] if a != "PRIVATE"]
            if folders:
                published[args[0]] = folders[0]
        for kind in ("add_library", "add_executable", "fmpp_test_binary", "fmpp_rtl_factory"):
            for args in commands(text, kind):
                if not args or args[0].startswith("${lib}") or args[0].startswith("${name}"):
                    continue
                srcs = [a for a in args[1:] if a not in ("STATIC", "OBJECT", "INTERFACE", "SHARED")
                        and not a.startswith("$")]
                if srcs and kind != "fmpp_rtl_factory":
                    folder = os.path.normpath(os.path.join(here, os.path.dirname(srcs[0])))
                else:
                    folder = published.get(args[0], here)
                defined[args[0]] = folder + "/CMakeLists.txt"
        for args in commands(text, "target_link_libraries"):
            for dep in args[1:]:
                if dep not in ("PUBLIC", "PRIVATE", "INTERFACE"):
                    links.append((cm, args[0], dep))
        for args in commands(text, "target_include_directories"):
            include_dirs.append((cm, args))
    patterns = [(re.compile("^" + re.sub(r"\\\$\\\{[^}]*\\\}", ".+", re.escape(t)) + "$"), cm)
                for t, cm in defined.items()]

    def where(target):
        for rx, cm in patterns:
            if rx.match(target):
                return cm
        return None

    return defined, links, include_dirs, where


def cycles(edges):
    """The strongly connected components with more than one node (Tarjan)."""
    graph = {}
    for a, b in edges:
        graph.setdefault(a, set()).add(b)
        graph.setdefault(b, set())
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def main():
    failures = []
    inc = include_edges()
    defined, links, include_dirs, where = link_graph()
    link_paths = []
    for cm, target, dep in links:
        a, b = where(target), where(dep)
        if a and b:
            link_paths.append((a, b))
    for level in (1, 2, 3):
        graphs = {"include": [], "link": []}
        examples = {}
        for kind, pairs in (("include", inc), ("link", link_paths)):
            for src, dst in pairs:
                a, b = unit(src, level), unit(dst, level)
                if a and b and a != b:
                    graphs[kind].append((a, b))
                    examples.setdefault((kind, a, b), f"{src} -> {dst}")
        for kind, edges in list(graphs.items()) + [("include+link", graphs["include"] + graphs["link"])]:
            for comp in cycles(edges):
                detail = [examples[k] for k in sorted(examples) if k[1] in comp and k[2] in comp]
                failures.append(f"level {level} {kind} cycle among {', '.join(comp)}: " + "; ".join(detail[:6]))
    failures += form_violations()
    for cm, args in include_dirs:
        for a in args:
            if re.fullmatch(r"\$\{(PROJECT_SOURCE_DIR|CMAKE_SOURCE_DIR)\}/?", a):
                failures.append(f"{cm}: target {args[0]} puts the repository root on its include path")

    # Programs and what they may link: closure over first-party targets and the SystemC package.
    deps = {}
    for cm, target, dep in links:
        deps.setdefault(target, set()).add(dep)

    def closure(t):
        seen, todo = set(), [t]
        while todo:
            x = todo.pop()
            for d in deps.get(x, ()):
                if d not in seen:
                    seen.add(d)
                    todo.append(d)
        return seen

    for prog in ("fmpp-report", "fmpp-embree-bench", "fmpp_model_tests", "fmpp_report_tests", "fmpp_scene_tests", "fmpp_plan_tests"):
        if prog not in defined:
            failures.append(f"{prog}: not defined by any CMakeLists.txt (the check is stale)")
        elif "PkgConfig::SYSTEMC" in closure(prog):
            failures.append(f"{prog} does not offer the systemc backend but links SystemC")
    for prog in ("fmpp-render", "fmpp-intersect", "fmpp-sim"):
        if "PkgConfig::SYSTEMC" not in closure(prog):
            failures.append(f"{prog} offers the systemc backend but does not link it")

    for f in failures:
        print("FAIL:", f)
    print(f"{len(inc)} includes, {len(links)} link entries, {len(defined)} targets read; "
          f"{len(failures)} violation(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
