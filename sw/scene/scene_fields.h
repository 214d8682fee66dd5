// What the scene loader's parts share (scene.cpp, scene_fields.cpp): the checked JSON
// fields; the lights and the meshes (with their placement), read from their fields.
#pragma once

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <initializer_list>
#include <string>
#include <vector>

#include "sw/scene/mesh.h"
#include "sw/scene/scene.h"

namespace rt::scene_fields {

using json = nlohmann::json;

[[noreturn]] inline void field_error(const std::string& file, const std::string& field, const std::string& what) {
  throw SceneError(file + ": field '" + field + "': " + what);
}

inline const json& require(const json& j, const char* key, const std::string& file, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) field_error(file, where.empty() ? key : where + "." + key, "missing");
  return j.at(key);
}

// The shortest decimal that reads back as `v` ("1000000002.75", "1e-06", "0.1"): a value
// in a message, exactly as the loader holds it.
inline std::string exact_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// A JSON number as the double nearest its decimal (the JSON reader's strtod), which must
// lie in [lo, hi].
inline double number(const json& j, const std::string& file, const std::string& field, double lo, double hi) {
  if (!j.is_number()) field_error(file, field, "expected a number");
  const double v = j.get<double>();
  if (!std::isfinite(v) || v < lo || v > hi) {
    field_error(file, field, "value " + exact_text(v) + " outside [" + exact_text(lo) + ", " + exact_text(hi) + "]");
  }
  return v;
}

inline glm::dvec3 vec3(const json& j, const std::string& file, const std::string& field, double lo = -1e9, double hi = 1e9) {
  if (!j.is_array() || j.size() != 3) field_error(file, field, "expected an array of 3 numbers");
  glm::dvec3 v;
  for (int k = 0; k < 3; ++k) v[k] = number(j[k], file, field + "[" + std::to_string(k) + "]", lo, hi);
  return v;
}

// A direction (a camera's up, a light's direction, a rotation's axis): each component
// within kMaxScenePosition (its length is checked where it is used).
inline glm::dvec3 direction(const json& j, const std::string& file, const std::string& field) {
  return vec3(j, file, field, -kMaxScenePosition, kMaxScenePosition);
}

// A JSON number in (0, hi].
inline double positive(const json& j, const std::string& file, const std::string& field, double hi) {
  if (!j.is_number()) field_error(file, field, "expected a number");
  const double v = j.get<double>();
  if (!(v > 0 && v <= hi)) field_error(file, field, "value " + exact_text(v) + " outside (0, " + exact_text(hi) + "]");
  return v;
}

// A point of the scene (camera eye and look_at, a light's position, centre or corner, a
// translation): each coordinate within kMaxScenePosition.
inline glm::dvec3 position(const json& j, const std::string& file, const std::string& field) {
  return vec3(j, file, field, -kMaxScenePosition, kMaxScenePosition);
}

// A number that must be a whole number in [lo, hi].
inline double integer(const json& j, const std::string& file, const std::string& field, double lo, double hi) {
  const double d = number(j, file, field, lo, hi);
  if (d != std::floor(d)) field_error(file, field, "value " + exact_text(d) + " must be an integer");
  return d;
}

// Also the check that `j` is an object at all: a JSON array or scalar has no fields.
inline void reject_unknown(const json& j, std::initializer_list<const char*> known, const std::string& file,
                    const std::string& where) {
  if (!j.is_object()) field_error(file, where, "expected an object");
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || key == k;
    if (!ok) field_error(file, where.empty() ? key : where + "." + key, "unknown field");
  }
}

// One light of "lights" at field w.
Light light(const json& j, const std::string& f, const std::string& w);
// meshes[index]: reads its file (relative to dir), places it, gives its groups their
// materials (mats: the scene's materials by name) and appends its triangles to s.
void add_mesh(Scene& s, const json& m, size_t index, const std::map<std::string, int>& mats, const std::string& file,
              const std::filesystem::path& dir);

}  // namespace rt::scene_fields
