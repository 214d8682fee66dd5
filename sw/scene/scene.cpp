// Scene loading: nlohmann-json for the scene file, assimp for the meshes (mesh.h), with
// every error naming the file and the line or field (see scene.h).
#include "sw/scene/scene.h"

#include "sw/isect/geometry/io.h"
#include "sw/scene/mesh.h"
#include "sw/scene/scene_fields.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

namespace rt {
namespace {

using namespace scene_fields;

// json::parse, keeping the byte offset of an error: nlohmann reports a number overflow
// ("1e999", out_of_range.406) through the same SAX call as a syntax error, but only a
// parse_error carries the position. (json_sax_dom_parser is what json::parse builds with.)
// It also notes a key that appears twice in one object, which json::parse would let the
// last one win silently, with its field path ("camera.fov_y_deg", "lights[1].color").
struct PositionedDomParser : nlohmann::detail::json_sax_dom_parser<json> {
  using Base = nlohmann::detail::json_sax_dom_parser<json>;
  using Base::json_sax_dom_parser;
  size_t error_byte = 0;
  std::string duplicate;  // path of the first repeated key

  template <class Exception>
  bool parse_error(size_t byte, const std::string& token, const Exception& ex) {
    error_byte = byte;
    return Base::parse_error(byte, token, ex);
  }
  bool start_object(size_t len) {
    open_.push_back(Open{false, {}, {}, 0});
    return Base::start_object(len);
  }
  bool key(std::string& k) {
    Open& o = open_.back();
    o.key = k;
    if (!o.keys.insert(k).second && duplicate.empty()) duplicate = path();
    return Base::key(k);
  }
  bool end_object() {
    open_.pop_back();
    done();
    return Base::end_object();
  }
  bool start_array(size_t len) {
    open_.push_back(Open{true, {}, {}, 0});
    return Base::start_array(len);
  }
  bool end_array() {
    open_.pop_back();
    done();
    return Base::end_array();
  }
  bool null() { return done(), Base::null(); }
  bool boolean(bool v) { return done(), Base::boolean(v); }
  bool number_integer(json::number_integer_t v) { return done(), Base::number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return done(), Base::number_unsigned(v); }
  bool number_float(json::number_float_t v, const std::string& s) { return done(), Base::number_float(v, s); }
  bool string(std::string& v) { return done(), Base::string(v); }
  bool binary(json::binary_t& v) { return done(), Base::binary(v); }

 private:
  struct Open {
    bool array;
    std::string key;             // object: the current key
    std::set<std::string> keys;  // object: the keys so far
    size_t index;                // array: the current element
  };
  std::vector<Open> open_;

  // A value ended: in an array, the next one has the next index.
  void done() {
    if (!open_.empty() && open_.back().array) ++open_.back().index;
  }
  std::string path() const {
    std::string p;
    for (const Open& o : open_) {
      p += o.array ? "[" + std::to_string(o.index) + "]" : (p.empty() ? "" : ".") + o.key;
    }
    return p;
  }
};

// The renderer's camera basis: the view direction look_at - eye normalized, and the
// right vector, cross(view, up) normalized: both at least kMinSceneLength long, or the
// basis would not be finite.
void check_camera(const Camera& c, const std::string& f) {
  const glm::dvec3 d = c.look_at - c.eye;
  if (d == glm::dvec3(0)) field_error(f, "camera.look_at", "equals camera.eye");
  if (!(glm::length(d) >= kMinSceneLength)) {
    field_error(f, "camera.look_at", "is within 1e-150 of camera.eye: the view direction cannot be normalized");
  }
  if (!(glm::length(glm::cross(glm::normalize(d), c.up)) >= kMinSceneLength)) {
    field_error(f, "camera.up", "is parallel to the viewing direction (or less than 1e-150 across it)");
  }
}

}  // namespace

const char* to_string(LightType t) {
  switch (t) {
    case LightType::kPoint: return "point";
    case LightType::kDirectional: return "directional";
    case LightType::kSphere: return "sphere";
    case LightType::kRect: return "rect";
  }
  return "?";
}

Scene load_scene(const std::string& json_path) {
  std::string text;
  std::string err = fmpp::isect::read_input(json_path, "scene", fmpp::isect::kMaxSceneBytes, &text);
  if (err.empty()) err = fmpp::isect::check_text(json_path, &text);
  if (!err.empty()) throw SceneError(err);
  json j;
  PositionedDomParser dom(j);
  try {
    json::sax_parse(text, &dom);
  } catch (const json::exception& e) {
    // Any error of the parser: syntax, or a number beyond double (out_of_range.406).
    size_t line = 1;
    for (size_t k = 0; k < dom.error_byte && k < text.size(); ++k) line += text[k] == '\n';
    const char* what = dynamic_cast<const json::parse_error*>(&e)     ? "JSON syntax error"
                       : dynamic_cast<const json::out_of_range*>(&e) ? "JSON number out of range"
                                                                      : "JSON error";
    throw SceneError(json_path + ":" + std::to_string(line) + ": " + what + ": " + e.what());
  }
  if (!dom.duplicate.empty()) field_error(json_path, dom.duplicate, "given twice");
  const std::string& f = json_path;
  if (!j.is_object()) throw SceneError(f + ": the scene must be a JSON object");
  reject_unknown(j, {"description", "camera", "background", "ambient", "max_depth", "samples_per_pixel", "seed", "lights",
                     "materials", "meshes"}, f, "");
  Scene s;
  s.path = json_path;
  s.files.push_back(json_path);
  if (j.contains("description")) {
    if (!j["description"].is_string()) field_error(f, "description", "expected a string");
    s.description = j["description"];
  }

  const json& cam = require(j, "camera", f, "");
  reject_unknown(cam, {"eye", "look_at", "up", "fov_y_deg"}, f, "camera");
  s.camera.eye = position(require(cam, "eye", f, "camera"), f, "camera.eye");
  s.camera.look_at = position(require(cam, "look_at", f, "camera"), f, "camera.look_at");
  s.camera.up = direction(require(cam, "up", f, "camera"), f, "camera.up");
  s.camera.fov_y_deg = number(require(cam, "fov_y_deg", f, "camera"), f, "camera.fov_y_deg", 1, 170);
  check_camera(s.camera, f);
  if (j.contains("background")) s.background = vec3(j["background"], f, "background", 0, 100);
  if (j.contains("ambient")) s.ambient = vec3(j["ambient"], f, "ambient", 0, 100);
  if (j.contains("max_depth")) s.max_depth = static_cast<int>(integer(j["max_depth"], f, "max_depth", 1, 16));

  if (j.contains("samples_per_pixel")) s.spp = integer(j["samples_per_pixel"], f, "samples_per_pixel", 1, kMaxSpp);
  if (j.contains("seed")) s.seed = static_cast<uint64_t>(integer(j["seed"], f, "seed", 0, 9007199254740991.0));

  const json& lights = require(j, "lights", f, "");
  if (!lights.is_array() || lights.empty()) field_error(f, "lights", "expected a non-empty array");
  for (size_t k = 0; k < lights.size(); ++k) s.lights.push_back(light(lights[k], f, "lights[" + std::to_string(k) + "]"));

  std::map<std::string, int> mats;
  // Optional when the mesh files give every face its material.
  static const json kNoMaterials = json::object();
  const json& jm = j.contains("materials") ? j["materials"] : kNoMaterials;
  if (!jm.is_object()) field_error(f, "materials", "expected an object of named materials");
  for (const auto& [name, m] : jm.items()) {
    const std::string w = "materials." + name;
    reject_unknown(m, {"diffuse", "specular", "shininess", "reflectivity", "transparency", "ior"}, f, w);
    Material mat;
    mat.name = name;
    if (m.contains("diffuse")) mat.diffuse = vec3(m["diffuse"], f, w + ".diffuse", 0, 1);
    if (m.contains("specular")) mat.specular = number(m["specular"], f, w + ".specular", 0, 1);
    if (m.contains("shininess")) mat.shininess = number(m["shininess"], f, w + ".shininess", 1, 10000);
    if (m.contains("reflectivity")) mat.reflectivity = number(m["reflectivity"], f, w + ".reflectivity", 0, 1);
    if (m.contains("transparency")) mat.transparency = number(m["transparency"], f, w + ".transparency", 0, 1);
    if (m.contains("ior")) mat.ior = number(m["ior"], f, w + ".ior", 1, 4);
    if (mat.reflectivity + mat.transparency > 1) field_error(f, w, "reflectivity + transparency exceeds 1");
    mats[name] = static_cast<int>(s.materials.size());
    s.materials.push_back(mat);
  }

  const json& meshes = require(j, "meshes", f, "");
  if (!meshes.is_array() || meshes.empty()) field_error(f, "meshes", "expected a non-empty array");
  const std::filesystem::path dir = std::filesystem::path(json_path).parent_path();
  for (size_t k = 0; k < meshes.size(); ++k) add_mesh(s, meshes[k], k, mats, f, dir);
  if (s.triangles.empty()) field_error(f, "meshes", "the meshes hold no triangles");
  return s;
}

}  // namespace rt
