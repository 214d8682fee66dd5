#!/usr/bin/python3
"""The scene schema (scenes/scene.schema.json) against the scenes and the loader (the
ctest scene_schema).

    tests/scene/scene_schema_test.py SOURCE_DIR FMPP_RENDER

1. Every scene file of the repository - every .json under scenes/, tests/ and
   docs/examples/ but the schema itself - validates, read by the loader's JSON rules
   (tools/check_scene.py); so do 40 scenes of the render fuzzer's generator
   (tests/render_fuzz/scenegen.py) and every scene and fragment in the JSON blocks of
   docs/scene-format.md and docs/your-own-scene.md.
2. Malformed scenes - the guide's minimal scene with one thing wrong - are refused by the
   schema AND by the loader (fmpp-render on the reference backend, at 1 x 1), the
   loader's message naming the field given, and the schema's errors on the same
   path: the schema is not vacuous, and refuses for the loader's reason.
3. Scenes at the edges of the format (every light type, every transform form, the
   limits themselves, integers written as 4.0) pass both.
4. What a schema cannot say (look_at at the eye, a singular matrix, an undefined
   material name, ...) passes the schema and is refused by the loader, as
   docs/scene-format.md says.
Prints each failure and exits 1 if any.
"""
import copy
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

SRC = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RENDER = sys.argv[2] if len(sys.argv) > 2 else None
sys.path.insert(0, os.path.join(SRC, "tools"))
sys.path.insert(0, os.path.join(SRC, "tests", "render_fuzz"))
import check_scene  # noqa: E402
import scenegen  # noqa: E402

MINIMAL = os.path.join(SRC, "docs", "examples", "minimal.json")
failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg, file=sys.stderr)


def scene_files():
    out = []
    for d in ("scenes", "tests", os.path.join("docs", "examples")):
        for root, _, files in os.walk(os.path.join(SRC, d)):
            out += [os.path.join(root, f) for f in files if f.endswith(".json") and f != "scene.schema.json"]
    return sorted(out)


# ------------------------------------------------------------------ the scene files
V = check_scene.validator()
files = scene_files()
if len(files) < 10:
    fail("only %d scene files found under scenes/, tests/, docs/examples/" % len(files))
for path in files:
    try:
        msgs = check_scene.problems(V, check_scene.load_strict(path))
    except check_scene.SceneJsonError as e:
        msgs = [str(e)]
    for m in msgs:
        fail("%s: %s" % (os.path.relpath(path, SRC), m))
print("%d scene files checked" % len(files))

tmp = tempfile.mkdtemp(prefix="scene_schema_")
try:
    rng = random.Random(45)
    for k in range(40):
        path, _ = scenegen.make_scene(rng, os.path.join(tmp, "gen%02d" % k))
        for m in check_scene.problems(V, check_scene.load_strict(path)):
            fail("scenegen scene %d: %s" % (k, m))

    with open(MINIMAL, encoding="utf-8") as f:
        BASE = json.load(f)

    # The JSON blocks of the docs: a whole scene, or a fragment ("key": value) put into
    # the minimal scene (a transform into its mesh).
    blocks = 0
    for doc in ("scene-format.md", "your-own-scene.md"):
        with open(os.path.join(SRC, "docs", doc), encoding="utf-8") as f:
            text = f.read()
        for body in re.findall(r"```json\n(.*?)```", text, re.S):
            blocks += 1
            try:
                value = check_scene.loads_strict(body if body.lstrip().startswith("{") else "{" + body + "}")
            except check_scene.SceneJsonError as e:
                fail("%s: a JSON block does not parse: %s" % (doc, e))
                continue
            if "camera" not in value:
                scene = copy.deepcopy(BASE)
                for key, v in value.items():
                    if key == "transform":
                        scene["meshes"][0]["transform"] = v
                    else:
                        scene[key] = v
                value = scene
            for m in check_scene.problems(V, value):
                fail("%s: a JSON block: %s" % (doc, m))
    if blocks < 3:
        fail("only %d JSON blocks in the docs" % blocks)

    # ------------------------------------------------------------- against the loader
    shutil.copy(os.path.join(SRC, "docs", "examples", "minimal.obj"), tmp)
    runs = [0]

    def loader(scene_text):
        """(exit status, stderr) of fmpp-render reading the scene (reference, 1 x 1)."""
        path = os.path.join(tmp, "case%03d.json" % runs[0])
        runs[0] += 1
        with open(path, "w", encoding="utf-8") as f:
            f.write(scene_text)
        p = subprocess.run([RENDER, "--scene", path, "--backend", "reference", "--width", "1", "--height", "1",
                            "--quiet", "--out", os.path.join(tmp, "out.png")], capture_output=True, text=True)
        return p.returncode, p.stderr

    def at(scene, path):
        for p in path[:-1]:
            scene = scene[p]
        return scene, path[-1]

    def mutated(path, value=None, delete=False):
        s = copy.deepcopy(BASE)
        if not path:
            return value
        obj, key = at(s, path)
        if delete:
            del obj[key]
        else:
            obj[key] = value
        return s

    IDENTITY = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    SPHERE = {"type": "sphere", "center": [0, 2, 0], "radius": 0.2, "samples": 2}
    RECT = {"type": "rect", "corner": [-0.5, 3, -1], "edge1": [1, 0, 0], "edge2": [0, 0, 1], "samples": 2}
    L0, M0, T0 = ["lights", 0], ["meshes", 0], ["meshes", 0, "transform"]

    def light(**kw):
        d = dict(kw.pop("base", {"position": [2, 3, 1]}))
        d.update(kw)
        return d

    # (scene, the loader's field in its message)
    BAD = [
        (mutated(["colour"], 1), "field 'colour': unknown field"),
        (mutated(["camera"], delete=True), "field 'camera': missing"),
        (mutated(["lights"], delete=True), "field 'lights': missing"),
        (mutated(["meshes"], delete=True), "field 'meshes': missing"),
        (mutated([], [BASE]), "the scene must be a JSON object"),
        (mutated(["description"], 5), "field 'description': expected a string"),
        (mutated(["camera"], [0, 0, 0]), "field 'camera': expected an object"),
        (mutated(["camera", "fov"], 45), "field 'camera.fov': unknown field"),
        (mutated(["camera", "up"], delete=True), "field 'camera.up': missing"),
        (mutated(["camera", "fov_y_deg"], 200), "field 'camera.fov_y_deg': value 200 outside [1, 170]"),
        (mutated(["camera", "fov_y_deg"], 0.5), "field 'camera.fov_y_deg': value 0.5 outside"),
        (mutated(["camera", "fov_y_deg"], "45"), "field 'camera.fov_y_deg': expected a number"),
        (mutated(["camera", "fov_y_deg"], True), "field 'camera.fov_y_deg': expected a number"),
        (mutated(["camera", "eye"], [0, 1]), "field 'camera.eye': expected an array of 3 numbers"),
        (mutated(["camera", "eye"], [0, 1, 2, 3]), "field 'camera.eye': expected an array of 3 numbers"),
        (mutated(["camera", "eye"], [0, 1, 1.0000000000000002e99]), "field 'camera.eye[2]': value"),
        (mutated(["camera", "look_at"], [0, -2e99, 0]), "field 'camera.look_at[1]': value"),
        (mutated(["camera", "up"], [0, "1", 0]), "field 'camera.up[1]': expected a number"),
        (mutated(["background"], [-0.1, 0, 0]), "field 'background[0]': value -0.1 outside [0, 100]"),
        (mutated(["ambient"], "grey"), "field 'ambient': expected an array of 3 numbers"),
        (mutated(["ambient"], [0, 0, 100.00000000000001]), "field 'ambient[2]': value"),
        (mutated(["max_depth"], 2.7), "field 'max_depth': value 2.7 must be an integer"),
        (mutated(["max_depth"], 0), "field 'max_depth': value 0 outside [1, 16]"),
        (mutated(["max_depth"], 17), "field 'max_depth': value 17 outside [1, 16]"),
        (mutated(["samples_per_pixel"], 1025), "field 'samples_per_pixel': value 1025 outside"),
        (mutated(["samples_per_pixel"], 0), "field 'samples_per_pixel': value 0 outside"),
        (mutated(["seed"], -1), "field 'seed': value -1 outside"),
        (mutated(["seed"], 9007199254740992), "field 'seed': value 9007199254740992 outside"),
        (mutated(["seed"], 1.5), "field 'seed': value 1.5 must be an integer"),
        (mutated(["lights"], []), "field 'lights': expected a non-empty array"),
        (mutated(["lights"], {"position": [0, 1, 0]}), "field 'lights': expected a non-empty array"),
        (mutated(L0, 5), "field 'lights[0]': expected an object"),
        (mutated(L0, [1, 2, 3]), "field 'lights[0]': expected an object"),
        (mutated(L0, light(type="spot")), "field 'lights[0].type': 'spot' is not one of point, directional"),
        (mutated(L0, light(type=1)), "field 'lights[0].type': expected a string"),
        (mutated(L0, {"color": [1, 1, 1]}), "field 'lights[0].position': missing"),
        (mutated(L0, light(color=[0, 0, 101])), "field 'lights[0].color[2]': value 101 outside [0, 100]"),
        (mutated(L0, light(color=[1, 1])), "field 'lights[0].color': expected an array of 3 numbers"),
        (mutated(L0, light(radius=1)), "field 'lights[0].radius': unknown field"),
        (mutated(L0, {"direction": [0, -1, 0]}), "field 'lights[0].direction': unknown field"),
        (mutated(L0, {"type": "directional"}), "field 'lights[0].direction': missing"),
        (mutated(L0, {"type": "directional", "direction": [0, -1, 0], "samples": 2}),
         "field 'lights[0].samples': unknown field"),
        (mutated(L0, {"type": "directional", "direction": [0, -1e100, 0]}), "field 'lights[0].direction[1]': value"),
        (mutated(L0, {"type": "sphere", "center": [0, 2, 0], "samples": 2}), "field 'lights[0].radius': missing"),
        (mutated(L0, light(base=SPHERE, samples=None)), "field 'lights[0].samples': expected a number"),
        (mutated(L0, {"type": "sphere", "center": [0, 2, 0], "radius": 0.2}), "field 'lights[0].samples': missing"),
        (mutated(L0, light(base=SPHERE, radius=0)), "field 'lights[0].radius': value 0 outside (0, 1e+99]"),
        (mutated(L0, light(base=SPHERE, radius=-1)), "field 'lights[0].radius': value -1 outside"),
        (mutated(L0, light(base=SPHERE, samples=2.5)), "field 'lights[0].samples': value 2.5 must be an integer"),
        (mutated(L0, light(base=SPHERE, samples=0)), "field 'lights[0].samples': value 0 outside [1, 1024]"),
        (mutated(L0, light(base=SPHERE, samples=1025)), "field 'lights[0].samples': value 1025 outside"),
        (mutated(L0, light(base=SPHERE, pool=4097)), "field 'lights[0].pool': value 4097 outside [0, 4096]"),
        (mutated(L0, light(base=SPHERE, pool=-1)), "field 'lights[0].pool': value -1 outside"),
        (mutated(L0, light(base=SPHERE, position=[0, 2, 0])), "field 'lights[0].position': unknown field"),
        (mutated(L0, light(base=RECT, edge2=None)), "field 'lights[0].edge2': expected an array of 3 numbers"),
        (mutated(L0, {k: v for k, v in RECT.items() if k != "edge1"}), "field 'lights[0].edge1': missing"),
        (mutated(L0, {k: v for k, v in RECT.items() if k != "corner"}), "field 'lights[0].corner': missing"),
        (mutated(L0, light(base=RECT, edge1=[2e75, 0, 0])), "field 'lights[0].edge1[0]': value"),
        (mutated(L0, light(base=RECT, center=[0, 0, 0])), "field 'lights[0].center': unknown field"),
        (mutated(["materials"], []), "field 'materials': expected an object of named materials"),
        (mutated(["materials", "grey"], 5), "field 'materials.grey': expected an object"),
        (mutated(["materials", "grey", "gloss"], 1), "field 'materials.grey.gloss': unknown field"),
        (mutated(["materials", "grey", "diffuse"], [1.5, 0, 0]), "field 'materials.grey.diffuse[0]': value 1.5 outside [0, 1]"),
        (mutated(["materials", "grey", "specular"], 1.01), "field 'materials.grey.specular': value 1.01 outside [0, 1]"),
        (mutated(["materials", "grey", "shininess"], 0.5), "field 'materials.grey.shininess': value 0.5 outside [1, 10000]"),
        (mutated(["materials", "grey", "shininess"], 10001), "field 'materials.grey.shininess': value 10001 outside"),
        (mutated(["materials", "grey", "reflectivity"], -0.1), "field 'materials.grey.reflectivity': value -0.1 outside"),
        (mutated(["materials", "grey", "transparency"], 2), "field 'materials.grey.transparency': value 2 outside"),
        (mutated(["materials", "grey", "ior"], 0.5), "field 'materials.grey.ior': value 0.5 outside [1, 4]"),
        (mutated(["materials", "grey", "ior"], 4.5), "field 'materials.grey.ior': value 4.5 outside [1, 4]"),
        (mutated(["meshes"], []), "field 'meshes': expected a non-empty array"),
        (mutated(M0, "minimal.obj"), "field 'meshes[0]': expected an object"),
        (mutated(M0 + ["file"], delete=True), "field 'meshes[0].file': missing"),
        (mutated(M0 + ["file"], ""), "field 'meshes[0].file': empty path"),
        (mutated(M0 + ["file"], 3), "field 'meshes[0].file': expected a string"),
        (mutated(M0 + ["file"], "minimal.obj\u0000x"), "field 'meshes[0].file': the path holds a NUL byte"),
        (mutated(M0 + ["colour"], 3), "field 'meshes[0].colour': unknown field"),
        (mutated(M0 + ["material"], 5), "field 'meshes[0].material': expected a material name"),
        (mutated(M0 + ["groups"], []), "field 'meshes[0].groups': expected an object of group: material"),
        (mutated(M0 + ["groups"], {"floor": 3}), "field 'meshes[0].groups.floor': expected a material name"),
        (mutated(T0, [1, 2, 3]), "field 'meshes[0].transform': expected an object"),
        (mutated(T0, {"shear": 1}), "field 'meshes[0].transform.shear': unknown field"),
        (mutated(T0, {"scale": 0}), "field 'meshes[0].transform.scale': value 0 outside [1e-100, 1e+100]"),
        (mutated(T0, {"scale": 1e101}), "field 'meshes[0].transform.scale': value 1e+101 outside"),
        (mutated(T0, {"scale": [1, 1]}), "field 'meshes[0].transform.scale': expected an array of 3 numbers"),
        (mutated(T0, {"scale": [1, -1, 1]}), "field 'meshes[0].transform.scale[1]': value -1 outside"),
        (mutated(T0, {"scale": "2"}), "field 'meshes[0].transform.scale': expected a number"),
        (mutated(T0, {"translate": [1, 2]}), "field 'meshes[0].transform.translate': expected an array of 3 numbers"),
        (mutated(T0, {"translate": [1, 2, 2e99]}), "field 'meshes[0].transform.translate[2]': value"),
        (mutated(T0, {"rotate_y_deg": 361}), "field 'meshes[0].transform.rotate_y_deg': value 361 outside [-360, 360]"),
        (mutated(T0, {"rotate_y_deg": 10, "rotate": {"axis": [0, 1, 0], "deg": 5}}),
         "field 'meshes[0].transform.rotate_y_deg': cannot be given with 'rotate'"),
        (mutated(T0, {"rotate": []}), "field 'meshes[0].transform.rotate': expected {\"axis\""),
        (mutated(T0, {"rotate": 30}), "field 'meshes[0].transform.rotate': expected {\"axis\""),
        (mutated(T0, {"rotate": {"axis": [0, 1, 0]}}), "field 'meshes[0].transform.rotate.deg': missing"),
        (mutated(T0, {"rotate": {"deg": 30}}), "field 'meshes[0].transform.rotate.axis': missing"),
        (mutated(T0, {"rotate": {"axis": [0, 1, 0], "deg": -400}}), "field 'meshes[0].transform.rotate.deg': value -400"),
        (mutated(T0, {"rotate": {"axis": [0, 1, 0], "deg": 30, "about": [0, 0, 0]}}),
         "field 'meshes[0].transform.rotate.about': unknown field"),
        (mutated(T0, {"rotate": [{"axis": [0, 1, 0], "deg": 30}, {"axis": [1, 0], "deg": 30}]}),
         "field 'meshes[0].transform.rotate[1].axis': expected an array of 3 numbers"),
        (mutated(T0, {"matrix": IDENTITY, "scale": 2}), "field 'meshes[0].transform.scale': cannot be given with 'matrix'"),
        (mutated(T0, {"matrix": IDENTITY, "translate": [0, 0, 0]}),
         "field 'meshes[0].transform.translate': cannot be given with 'matrix'"),
        (mutated(T0, {"matrix": IDENTITY[:3]}), "field 'meshes[0].transform.matrix': expected 4 rows of 4 numbers"),
        (mutated(T0, {"matrix": IDENTITY[:3] + [[0, 0, 1]]}),
         "field 'meshes[0].transform.matrix[3]': expected a row of 4 numbers"),
        (mutated(T0, {"matrix": IDENTITY[:3] + [[0, 0, 1, 1]]}),
         "field 'meshes[0].transform.matrix[3]': must be [0, 0, 0, 1]"),
        (mutated(T0, {"matrix": IDENTITY[:3] + [[0, 0, 0, 2]]}),
         "field 'meshes[0].transform.matrix[3]': must be [0, 0, 0, 1]"),
        (mutated(T0, {"matrix": [[2e6, 0, 0, 0]] + IDENTITY[1:]}), "field 'meshes[0].transform.matrix[0][0]': value"),
        (mutated(T0, {"matrix": [[1, 0, 0, 2e99]] + IDENTITY[1:]}), "field 'meshes[0].transform.matrix[0][3]': value"),
        (mutated(T0, {"matrix": [[1, 0, 0, "0"]] + IDENTITY[1:]}),
         "field 'meshes[0].transform.matrix[0][3]': expected a number"),
    ]
    # The JSON rules the schema leaves to the reader (tools/check_scene.py reads them as the loader does).
    text = json.dumps(BASE)
    RAW_BAD = [
        (text.replace('"fov_y_deg": 45', '"fov_y_deg": 45, "fov_y_deg": 50'), "field 'camera.fov_y_deg': given twice"),
        (text.replace('"fov_y_deg": 45', '"fov_y_deg": NaN'), "JSON syntax error"),
        (text.replace('"fov_y_deg": 45', '"fov_y_deg": 1e999'), "JSON number out of range"),
        (text.replace('"fov_y_deg": 45', '"fov_y_deg": 1' + "0" * 400), "JSON number out of range"),
        (text[:-1], "JSON syntax error"),
    ]
    # Scenes at the edges of the format: both accept them.
    GOOD = [
        mutated(["max_depth"], 4.0), mutated(["max_depth"], 16), mutated(["seed"], 9007199254740991),
        mutated(["seed"], 0), mutated(["samples_per_pixel"], 2), mutated(["description"], "edges"),
        mutated(["camera", "fov_y_deg"], 170), mutated(["camera", "fov_y_deg"], 1),
        mutated(["camera", "up"], [0, 5, 1]), mutated(["background"], [100, 0, 0.5]), mutated(["ambient"], [0, 0, 0]),
        mutated(L0, light(type="point", color=[100, 100, 100])),
        mutated(L0, {"type": "directional", "direction": [-0.3, -1, -0.4], "color": [0.5, 0.5, 0.5]}),
        mutated(L0, light(base=SPHERE, pool=0)), mutated(L0, light(base=SPHERE, pool=4096, samples=1)),
        mutated(L0, light(base=RECT, pool=1, color=[2, 2, 2])),
        mutated(["materials", "grey"], {}),
        mutated(["materials", "grey"], {"diffuse": [1, 0, 0], "specular": 1, "shininess": 10000, "reflectivity": 0.5,
                                         "transparency": 0.5, "ior": 4}),
        mutated(["materials", "spare"], {"ior": 1}),
        mutated(M0 + ["groups"], {"triangle": "grey"}),
        mutated(T0, {}), mutated(T0, {"scale": 2}), mutated(T0, {"scale": [1e-100, 1, 1e98]}),
        mutated(T0, {"rotate_y_deg": -360, "translate": [0, 0, -1]}),
        mutated(T0, {"rotate": {"axis": [1, 1, 1], "deg": 30}}),
        mutated(T0, {"rotate": [{"axis": [0, 1, 0], "deg": 30}, {"axis": [1, 0, 0], "deg": -90}], "scale": 0.5}),
        mutated(T0, {"matrix": [[0, 0, 1, 0.5], [0, 1, 0, 0], [-1, 0, 0, -1], [0, 0, 0, 1.0]]}),
        mutated(T0, {"matrix": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0.0, -0.0, 0, 1]]}),
    ]
    # What the schema cannot say: it accepts, the loader refuses.
    SEMANTIC = [
        (mutated(["camera", "look_at"], [0, 1.5, 3]), "field 'camera.look_at': equals camera.eye"),
        (mutated(["camera", "up"], [0, -1, -5]), "field 'camera.up': is parallel to the viewing direction"),
        (mutated(L0, {"type": "directional", "direction": [0, 0, 0]}), "field 'lights[0].direction': is the zero vector"),
        (mutated(L0, light(base=RECT, edge2=[2, 0, 0])), "field 'lights[0].edge2': is parallel to edge1"),
        (mutated(["materials", "grey"], {"reflectivity": 0.6, "transparency": 0.6}),
         "field 'materials.grey': reflectivity + transparency exceeds 1"),
        (mutated(M0 + ["material"], "gold"), "field 'meshes[0].material': no material 'gold'"),
        (mutated(M0 + ["groups"], {"lid": "grey"}), "field 'meshes[0].groups.lid': no group 'lid'"),
        (mutated(T0, {"rotate": {"axis": [0, 0, 0], "deg": 30}}), "field 'meshes[0].transform.rotate.axis': is the zero vector"),
        (mutated(T0, {"matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 0], [0, 0, 0, 1]]}),
         "field 'meshes[0].transform.matrix': is singular"),
        (mutated(M0 + ["file"], "absent.obj"), "absent.obj: cannot open"),
        (mutated(T0, {"scale": 1e99}), "field 'meshes[0].transform': moves a vertex of"),
    ]

    def schema_errors(value):
        return check_scene.problems(V, value)

    def same_place(schema_msgs, want):
        """Some schema error lies on the path of the loader's field: at it, within it, or
        at an object that holds it (a missing or unknown key is the object's error)."""
        m = re.match(r"field '([^']*)'", want)
        if not m:
            return True
        for msg in schema_msgs:
            at = re.match(r"field '([^']*)'", msg).group(1)
            at = "" if at == "(top level)" else at
            if m.group(1).startswith(at) or at.startswith(m.group(1)):
                return True
        return False

    for scene, want in BAD:
        errs = schema_errors(scene)
        if not errs:
            fail("the schema accepts a scene the loader refuses (%s): %s" % (want, json.dumps(scene)))
        elif not same_place(errs, want):
            fail("the schema refuses elsewhere than the loader (%s): %s" % (want, "; ".join(errs)))
        rc, err = loader(json.dumps(scene))
        if rc == 0 or want not in err:
            fail("the loader: want exit 1 and \"%s\", got %d: %s" % (want, rc, err.strip()))
    for raw, want in RAW_BAD:
        try:
            check_scene.loads_strict(raw)
            fail("check_scene reads a scene the loader refuses (%s)" % want)
        except check_scene.SceneJsonError:
            pass
        rc, err = loader(raw)
        if rc == 0 or want not in err:
            fail("the loader: want exit 1 and \"%s\", got %d: %s" % (want, rc, err.strip()))
    for scene in GOOD:
        for m in schema_errors(scene):
            fail("the schema refuses a scene the loader reads: %s: %s" % (m, json.dumps(scene)))
        rc, err = loader(json.dumps(scene))
        if rc != 0:
            fail("the loader refuses %s: %s" % (json.dumps(scene), err.strip()))
    for scene, want in SEMANTIC:
        for m in schema_errors(scene):
            fail("the schema refuses what it cannot check (%s): %s" % (want, m))
        rc, err = loader(json.dumps(scene))
        if rc == 0 or want not in err:
            fail("the loader: want exit 1 and \"%s\", got %d: %s" % (want, rc, err.strip()))
    print("%d malformed, %d malformed JSON, %d edge and %d semantic scenes against schema and loader" %
          (len(BAD), len(RAW_BAD), len(GOOD), len(SEMANTIC)))
finally:
    shutil.rmtree(tmp, ignore_errors=True)

if failures:
    print("%d failures" % len(failures), file=sys.stderr)
    sys.exit(1)
print("scene schema: OK")
