#!/usr/bin/python3
"""Checks scene files against the scene schema (scenes/scene.schema.json,
docs/scene-format.md) without rendering them.

    tools/check_scene.py SCENE.json [SCENE.json ...]

Reads each file as the loader does - UTF-8 with an optional byte-order mark, no key
twice in one object, no NaN, Infinity or number beyond double - and validates it against the schema (JSON
Schema draft 2020-12, Debian's python3-jsonschema). Prints one line per problem, naming
the file and the field in the loader's spelling (`meshes[0].transform.scale`), and exits
1 if any file has one. What a schema cannot check (the mesh files, material and group
names, a singular matrix, parallel rectangle edges) the loader checks when fmpp-render
reads the scene.
"""
import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCHEMA = os.path.join(ROOT, "scenes", "scene.schema.json")
MAX_BYTES = 16 << 20  # kMaxSceneBytes (sw/isect/geometry/io.h)


class SceneJsonError(ValueError):
    pass


def _no_duplicates(pairs):
    out = {}
    for k, v in pairs:
        if k in out:
            raise SceneJsonError("key '%s' given twice in one object" % k)
        out[k] = v
    return out


def _no_constant(name):
    raise SceneJsonError("%s is not a JSON number" % name)


def load_strict(path):
    """The JSON value of `path`, read by the loader's rules; raises SceneJsonError or OSError."""
    if os.path.getsize(path) > MAX_BYTES:
        raise SceneJsonError("larger than the limit of %d bytes" % MAX_BYTES)
    with open(path, "rb") as f:
        data = f.read()
    if b"\0" in data:
        raise SceneJsonError("NUL byte (not a text file)")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise SceneJsonError("not UTF-8: %s" % e)
    return loads_strict(text)


def _float(s):
    v = float(s)
    if math.isinf(v):
        raise SceneJsonError("JSON number out of range: %s is beyond double" % s)
    return v


def _int(s):
    v = int(s)
    if abs(v) > sys.float_info.max:
        raise SceneJsonError("JSON number out of range: %s is beyond double" % s)
    return v


def loads_strict(text):
    try:
        return json.loads(text, object_pairs_hook=_no_duplicates, parse_constant=_no_constant, parse_float=_float,
                          parse_int=_int)
    except json.JSONDecodeError as e:
        raise SceneJsonError("JSON syntax error: %s" % e)


def field(path):
    """A jsonschema error path in the loader's spelling: meshes[0].transform.scale."""
    out = ""
    for p in path:
        out += "[%d]" % p if isinstance(p, int) else ("." if out else "") + str(p)
    return out


def validator():
    from jsonschema import Draft202012Validator  # Debian: python3-jsonschema
    with open(SCHEMA, encoding="utf-8") as f:
        schema = json.load(f)
    Draft202012Validator.check_schema(schema)
    return Draft202012Validator(schema)


def problems(v, scene):
    """Sorted one-line messages, one per schema error of the value `scene`."""
    out = []
    for e in v.iter_errors(scene):
        out.append("field '%s': %s" % (field(e.absolute_path) or "(top level)", e.message))
    return sorted(out)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    v = validator()
    bad = 0
    for path in argv[1:]:
        try:
            scene = load_strict(path)
        except (OSError, SceneJsonError) as e:
            print("%s: %s" % (path, e), file=sys.stderr)
            bad += 1
            continue
        msgs = problems(v, scene)
        for m in msgs:
            print("%s: %s" % (path, m), file=sys.stderr)
        bad += bool(msgs)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
