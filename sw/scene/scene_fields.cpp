// A mesh's placement and the lights of a scene file (see scene_fields.h).
#include "sw/scene/scene_fields.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace rt::scene_fields {
namespace {

// A mesh's placement in the scene (docs/raytracer.md, "Scenes"): either a 4x4 affine
// matrix, or p -> T R_k ... R_1 S p (scale per axis first, then the rotations in the
// order given, then the translation). Each step is applied in turn, so the identity
// leaves every coordinate bit for bit as read, and a uniform scale with a rotation about
// y computes what the earlier scale/rotate_y_deg/translate placement computed.
// Normals go through the inverse transpose of each linear step; they are normalized
// again only when a step changes lengths unevenly (a non-uniform scale, a matrix).
struct Step {
  enum Kind { kScale, kRotate, kTranslate, kLinear } kind;
  glm::dvec3 v{0};                  // kScale: per-axis factors; kTranslate: the offset
  double m[3][3] = {};              // kRotate, kLinear: row-major
  int axis = -1;                    // kRotate about a coordinate axis (0, 1, 2), else -1
  double c = 1, sn = 0;             // kRotate about a coordinate axis: cos, sin
  double n[3][3] = {};              // kLinear: the inverse transpose, for normals
};

struct Placement {
  std::vector<Step> steps;
  bool mirrors = false;  // the linear part's determinant is negative: the winding flips
  bool identity() const { return steps.empty(); }
};

// cos and sin of `deg` degrees, exact (0, 1, -1) at multiples of 90 degrees.
void sincos_deg(double deg, double* c, double* sn) {
  const double q = deg / 90;
  if (q == std::floor(q)) {
    static const double kc[4] = {1, 0, -1, 0}, ks[4] = {0, 1, 0, -1};
    const int k = static_cast<int>(((static_cast<long long>(q) % 4) + 4) % 4);
    *c = kc[k];
    *sn = ks[k];
    return;
  }
  const double a = glm::radians(deg);
  *c = std::cos(a);
  *sn = std::sin(a);
}

// A rotation by `deg` degrees about `axis` (right-handed: counter-clockwise looking
// down the axis towards the origin).
Step rotation(glm::dvec3 axis, double deg, const std::string& file, const std::string& where) {
  const double len = glm::length(axis);
  if (!(len >= kMinSceneLength) || !std::isfinite(len)) {
    field_error(file, where + ".axis", "is the zero vector (or shorter than 1e-150)");
  }
  Step st;
  st.kind = Step::kRotate;
  double c, sn;
  sincos_deg(deg, &c, &sn);
  st.c = c;
  st.sn = sn;
  // About a coordinate axis (two components zero): its own formula, exact at multiples
  // of 90 degrees; about the negative axis, the opposite angle.
  for (int k = 0; k < 3; ++k) {
    if (axis[(k + 1) % 3] == 0 && axis[(k + 2) % 3] == 0) {
      st.axis = k;
      if (axis[k] < 0) st.sn = -sn;
    }
  }
  axis /= len;
  const double t = 1 - c, x = axis.x, y = axis.y, z = axis.z;
  const double r[3][3] = {{c + t * x * x, t * x * y - sn * z, t * x * z + sn * y},
                          {t * x * y + sn * z, c + t * y * y, t * y * z - sn * x},
                          {t * x * z - sn * y, t * y * z + sn * x, c + t * z * z}};
  std::memcpy(st.m, r, sizeof r);
  return st;
}

glm::dvec3 apply(const double (&m)[3][3], const glm::dvec3& p) {
  return glm::dvec3(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z, m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
                    m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z);
}

glm::dvec3 rotate(const Step& st, const glm::dvec3& p) {
  const double c = st.c, sn = st.sn;
  switch (st.axis) {
    case 0: return glm::dvec3(p.x, c * p.y - sn * p.z, sn * p.y + c * p.z);
    case 1: return glm::dvec3(c * p.x + sn * p.z, p.y, -sn * p.x + c * p.z);
    case 2: return glm::dvec3(c * p.x - sn * p.y, sn * p.x + c * p.y, p.z);
    default: return apply(st.m, p);
  }
}


// A placement by its 'matrix' (an affine 4 x 4, alone): its linear part with the
// inverse transpose for the normals, and its translation.
Placement matrix_placement(const json& t, const std::string& file, const std::string& where) {
  Placement pl;
  for (const char* other : {"scale", "rotate", "rotate_y_deg", "translate"}) {
    if (t.contains(other)) field_error(file, where + "." + other, "cannot be given with 'matrix'");
  }
  const json& m = t["matrix"];
  const std::string w = where + ".matrix";
  if (!m.is_array() || m.size() != 4) field_error(file, w, "expected 4 rows of 4 numbers");
  Step lin;
  lin.kind = Step::kLinear;
  Step tr;
  tr.kind = Step::kTranslate;
  for (int r = 0; r < 4; ++r) {
    const std::string wr = w + "[" + std::to_string(r) + "]";
    if (!m[r].is_array() || m[r].size() != 4) field_error(file, wr, "expected a row of 4 numbers");
    for (int c = 0; c < 4; ++c) {
      const std::string wc = wr + "[" + std::to_string(c) + "]";
      if (r == 3) {
        if (number(m[r][c], file, wc, -1e9, 1e9) != (c == 3 ? 1 : 0)) {
          field_error(file, wr, "must be [0, 0, 0, 1] (an affine transform)");
        }
      } else if (c == 3) {
        tr.v[r] = number(m[r][c], file, wc, -kMaxScenePosition, kMaxScenePosition);
      } else {
        lin.m[r][c] = number(m[r][c], file, wc, -1e6, 1e6);
      }
    }
  }
  const auto& a = lin.m;
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (!(std::abs(det) >= 1e-18) || !std::isfinite(det)) {
    field_error(file, w, "is singular (determinant " + exact_text(det) + "): it would flatten the mesh");
  }
  // Inverse transpose = cofactor matrix / det.
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      lin.n[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
    }
  }
  pl.mirrors = det < 0;
  bool is_identity = true;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) is_identity = is_identity && a[r][c] == (r == c ? 1 : 0);
  }
  if (!is_identity) pl.steps.push_back(lin);
  if (tr.v != glm::dvec3(0)) pl.steps.push_back(tr);
  return pl;
}

// The steps of 'rotate' (one {"axis", "deg"} or a list of them), in order, into *pl.
void add_rotations(const json& t, const std::string& file, const std::string& where, Placement* pl) {
  const json& r = t["rotate"];
  const std::string w = where + ".rotate";
  if (!r.is_object() && !(r.is_array() && !r.empty())) {
    field_error(file, w, "expected {\"axis\": [x, y, z], \"deg\": a} or a non-empty array of them");
  }
  const size_t n = r.is_array() ? r.size() : 1;
  for (size_t k = 0; k < n; ++k) {
    const json& one = r.is_array() ? r[k] : r;
    const std::string wk = r.is_array() ? w + "[" + std::to_string(k) + "]" : w;
    reject_unknown(one, {"axis", "deg"}, file, wk);
    const glm::dvec3 axis = direction(require(one, "axis", file, wk), file, wk + ".axis");
    const double deg = number(require(one, "deg", file, wk), file, wk + ".deg", -360, 360);
    const Step st = rotation(axis, deg, file, wk);
    if (deg != 0) pl->steps.push_back(st);
  }
}

Placement placement(const json& t, const std::string& file, const std::string& where) {
  reject_unknown(t, {"matrix", "scale", "rotate", "rotate_y_deg", "translate"}, file, where);
  if (t.contains("matrix")) return matrix_placement(t, file, where);
  Placement pl;
  if (t.contains("scale")) {
    const std::string w = where + ".scale";
    Step st;
    st.kind = Step::kScale;
    if (t["scale"].is_array()) {
      st.v = vec3(t["scale"], file, w, 1e-100, 1e100);
    } else {
      st.v = glm::dvec3(number(t["scale"], file, w, 1e-100, 1e100));
    }
    if (st.v != glm::dvec3(1)) pl.steps.push_back(st);
  }
  if (t.contains("rotate_y_deg") && t.contains("rotate")) {
    field_error(file, where + ".rotate_y_deg", "cannot be given with 'rotate' (add it to 'rotate')");
  }
  if (t.contains("rotate_y_deg")) {
    const double deg = number(t["rotate_y_deg"], file, where + ".rotate_y_deg", -360, 360);
    if (deg != 0) pl.steps.push_back(rotation(glm::dvec3(0, 1, 0), deg, file, where + ".rotate_y_deg"));
  }
  if (t.contains("rotate")) add_rotations(t, file, where, &pl);
  if (t.contains("translate")) {
    Step st;
    st.kind = Step::kTranslate;
    st.v = position(t["translate"], file, where + ".translate");
    if (st.v != glm::dvec3(0)) pl.steps.push_back(st);
  }
  return pl;
}

void place(const Placement& pl, MeshGroup& g) {
  if (pl.identity()) return;
  bool renormalize = false;
  for (const Step& st : pl.steps) {
    renormalize = renormalize || st.kind == Step::kLinear || (st.kind == Step::kScale && (st.v.x != st.v.y || st.v.y != st.v.z));
  }
  for (auto& t : g.triangles) {
    for (auto& p : t.p) {
      for (const Step& st : pl.steps) {
        switch (st.kind) {
          case Step::kScale: p = glm::dvec3(st.v.x * p.x, st.v.y * p.y, st.v.z * p.z); break;
          case Step::kRotate: p = rotate(st, p); break;
          case Step::kTranslate: p = p + st.v; break;
          case Step::kLinear: p = apply(st.m, p); break;
        }
      }
    }
    if (pl.mirrors) std::swap(t.p[1], t.p[2]);  // keep the front face where it was
  }
  for (auto& n : g.normals) {
    for (auto& v : n) {
      for (const Step& st : pl.steps) {
        switch (st.kind) {
          case Step::kScale:
            // A uniform scale leaves directions alone.
            if (st.v.x != st.v.y || st.v.y != st.v.z) v = glm::dvec3(v.x / st.v.x, v.y / st.v.y, v.z / st.v.z);
            break;
          case Step::kRotate: v = rotate(st, v); break;
          case Step::kTranslate: break;
          case Step::kLinear: v = apply(st.n, v); break;
        }
      }
      if (renormalize) v /= glm::length(v);
    }
    if (pl.mirrors) std::swap(n[1], n[2]);
  }
}

// Every vertex of g, as placed, within kMaxScenePosition (scene.h says why).
void check_placed(const MeshGroup& g, bool identity, const std::string& file, const std::string& where,
                  const std::string& path) {
  for (const auto& t : g.triangles) {
    for (const auto& p : t.p) {
      const double m = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
      if (!(m <= kMaxScenePosition)) {
        const std::string v = "(" + exact_text(p.x) + ", " + exact_text(p.y) + ", " + exact_text(p.z) + ")";
        if (!identity) field_error(file, where + ".transform", "moves a vertex of " + path + " to " + v +
                                                                    ", beyond the scene's position limit 1e99");
        field_error(file, where, path + " has a vertex at " + v + ", beyond the scene's position limit 1e99");
      }
    }
  }
}

}  // namespace

// One light of "lights" (docs/raytracer.md, "Lights"): by its "type", point (the default),
// directional, sphere or rect, each with its own fields only.
Light light(const json& j, const std::string& f, const std::string& w) {
  if (!j.is_object()) field_error(f, w, "expected an object");
  Light l;
  std::string type = "point";
  if (j.contains("type")) {
    if (!j["type"].is_string()) field_error(f, w + ".type", "expected a string");
    type = j["type"].get<std::string>();
  }
  auto area_fields = [&] {
    l.samples = static_cast<int>(integer(require(j, "samples", f, w), f, w + ".samples", 1, kMaxLightSamples));
    if (j.contains("pool")) l.pool = static_cast<int>(integer(j["pool"], f, w + ".pool", 0, kMaxLightPool));
  };
  if (type == "point") {
    reject_unknown(j, {"type", "position", "color"}, f, w);
    l.position = position(require(j, "position", f, w), f, w + ".position");
  } else if (type == "directional") {
    reject_unknown(j, {"type", "direction", "color"}, f, w);
    l.type = LightType::kDirectional;
    const glm::dvec3 d = direction(require(j, "direction", f, w), f, w + ".direction");
    const double len = glm::length(d);
    if (!(len >= kMinSceneLength)) field_error(f, w + ".direction", "is the zero vector (or shorter than 1e-150)");
    l.direction = d / len;
  } else if (type == "sphere") {
    reject_unknown(j, {"type", "center", "radius", "color", "samples", "pool"}, f, w);
    l.type = LightType::kSphere;
    l.position = position(require(j, "center", f, w), f, w + ".center");
    l.radius = positive(require(j, "radius", f, w), f, w + ".radius", kMaxScenePosition);
    area_fields();
  } else if (type == "rect") {
    reject_unknown(j, {"type", "corner", "edge1", "edge2", "color", "samples", "pool"}, f, w);
    l.type = LightType::kRect;
    l.position = position(require(j, "corner", f, w), f, w + ".corner");
    l.edge1 = vec3(require(j, "edge1", f, w), f, w + ".edge1", -kMaxRectEdge, kMaxRectEdge);
    l.edge2 = vec3(require(j, "edge2", f, w), f, w + ".edge2", -kMaxRectEdge, kMaxRectEdge);
    const double e1 = glm::length(l.edge1), e2 = glm::length(l.edge2), a = glm::length(glm::cross(l.edge1, l.edge2));
    if (l.edge1 == glm::dvec3(0)) field_error(f, w + ".edge1", "is the zero vector");
    if (l.edge2 == glm::dvec3(0)) field_error(f, w + ".edge2", "is the zero vector");
    if (!(a > 1e-6 * e1 * e2)) field_error(f, w + ".edge2", "is parallel to edge1: the rectangle has no area");
    if (!(a >= kMinSceneLength)) {
      field_error(f, w + ".edge2",
                  "makes with edge1 an area under 1e-150: the rectangle's normal cannot be normalized");
    }
    area_fields();
  } else {
    field_error(f, w + ".type", "'" + type + "' is not one of point, directional, sphere, rect");
  }
  if (j.contains("color")) l.color = vec3(j["color"], f, w + ".color", 0, 100);
  return l;
}

void add_mesh(Scene& s, const json& m, size_t index, const std::map<std::string, int>& mats, const std::string& file,
               const std::filesystem::path& dir) {
  const std::string where = "meshes[" + std::to_string(index) + "]";
  reject_unknown(m, {"file", "material", "groups", "transform"}, file, where);
  const json& f = require(m, "file", file, where);
  if (!f.is_string()) field_error(file, where + ".file", "expected a string");
  if (f.get<std::string>().empty()) field_error(file, where + ".file", "empty path");
  if (f.get<std::string>().find('\0') != std::string::npos) field_error(file, where + ".file", "the path holds a NUL byte");
  const std::string path = (dir / f.get<std::string>()).string();
  auto material = [&](const json& name, const std::string& field) {
    if (!name.is_string()) field_error(file, field, "expected a material name");
    const auto it = mats.find(name.get<std::string>());
    if (it == mats.end()) field_error(file, field, "no material '" + name.get<std::string>() + "'");
    return it->second;
  };
  // The mesh's default material: for faces without one of their own in the file.
  const int def = m.contains("material") ? material(m["material"], where + ".material") : -1;
  std::map<std::string, int> group_mat;
  if (m.contains("groups")) {
    if (!m["groups"].is_object()) field_error(file, where + ".groups", "expected an object of group: material");
    for (const auto& [g, name] : m["groups"].items()) group_mat[g] = material(name, where + ".groups." + g);
  }
  const Placement pl = m.contains("transform") ? placement(m["transform"], file, where + ".transform") : Placement{};
  Mesh mesh = load_mesh(path);
  s.files.push_back(path);
  // The file's materials, added to the scene as faces use them; one the scene file
  // defines by the same name takes its place (docs/raytracer.md, "Materials from the
  // mesh file").
  std::vector<int> file_to_scene(mesh.materials.size(), -1);
  auto from_file = [&](int fi) {
    if (file_to_scene[fi] >= 0) return file_to_scene[fi];
    const FileMaterial& fm = mesh.materials[fi];
    const auto it = mats.find(fm.m.name);
    if (it != mats.end()) return file_to_scene[fi] = it->second;
    if (!fm.defined) {
      throw SceneError(fm.where + ": usemtl '" + fm.m.name +
                       "': no material of that name in the file's material libraries, nor in the materials of " + file);
    }
    s.materials.push_back(fm.m);
    return file_to_scene[fi] = static_cast<int>(s.materials.size() - 1);
  };
  std::map<std::string, bool> used;
  for (MeshGroup& g : mesh.groups) {
    place(pl, g);
    check_placed(g, pl.identity(), file, where, path);
    const auto it = group_mat.find(g.name);
    if (it != group_mat.end()) used[g.name] = true;
    for (size_t i = 0; i < g.triangles.size(); ++i) {
      int mat = def;
      if (it != group_mat.end()) {
        mat = it->second;
      } else if (i < g.material.size() && g.material[i] >= 0) {
        mat = from_file(g.material[i]);
      }
      if (mat < 0) {
        field_error(file, where + ".material",
                    "missing: faces of " + path + " (part '" + g.name + "') have no material of their own");
      }
      s.material_of.push_back(mat);
    }
    s.triangles.insert(s.triangles.end(), g.triangles.begin(), g.triangles.end());
    s.normals.insert(s.normals.end(), g.normals.begin(), g.normals.end());
  }
  for (const auto& [g, m2] : group_mat) {
    if (!used.count(g)) field_error(file, where + ".groups." + g, "no group '" + g + "' in " + path);
  }
}

}  // namespace rt::scene_fields
