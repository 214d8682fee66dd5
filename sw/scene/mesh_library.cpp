// The glTF material factors and a Mesh as bytes (see mesh_library.h).
#include "sw/scene/mesh_library.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cctype>
#include <cstring>
#include <stdexcept>

#include "sw/scene/scene.h"

namespace rt::mesh_library {
namespace {

// A Mesh as bytes, to come back from the reader process.
template <class T>
void put(std::string& s, const T& v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
T get(const std::string& s, size_t& pos) {
  T v{};
  if (pos + sizeof v > s.size()) throw SceneError("mesh reader: short result");
  std::memcpy(&v, s.data() + pos, sizeof v);
  pos += sizeof v;
  return v;
}
void put_string(std::string& s, const std::string& v) {
  put<uint64_t>(s, v.size());
  s += v;
}
std::string get_string(const std::string& s, size_t& pos) {
  const uint64_t len = get<uint64_t>(s, pos);
  if (len > s.size() - pos) throw SceneError("mesh reader: short result");
  std::string v = s.substr(pos, len);
  pos += len;
  return v;
}

}  // namespace

std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

fs::path normal_path(const std::string& p) { return fs::absolute(fs::path(p)).lexically_normal(); }

// A value the library read in single precision, as the decimal number the file most
// likely wrote: the shortest decimal that reads back as the same float, read in double
// (0.8f -> 0.8, not 0.800000011920929), as the scene file's numbers are read.
double file_decimal(float f) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf - 1, f);
  *r.ptr = 0;
  return std::strtod(buf, nullptr);
}

// Two glTF material extensions the mesh library does not read, taken from the file's
// JSON (a .glb's first chunk): KHR_materials_transmission's transmissionFactor and
// KHR_materials_ior's ior, per material index (NaN where absent). The library has
// parsed the same JSON already; anything unexpected here is simply absent.
std::vector<GltfExtras> gltf_extras(const std::string& data, const std::string& ext) {
  std::string text = data;
  if (ext == ".glb") {
    uint32_t len = 0, type = 0;
    if (data.size() < 20) return {};
    std::memcpy(&len, data.data() + 12, 4);
    std::memcpy(&type, data.data() + 16, 4);
    if (type != 0x4E4F534Au || len > data.size() - 20) return {};  // "JSON"
    text = data.substr(20, len);
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  std::vector<GltfExtras> out;
  if (!j.is_object() || !j.contains("materials") || !j["materials"].is_array()) return out;
  for (const auto& m : j["materials"]) {
    GltfExtras e;
    auto number = [&](const char* extension, const char* key, double* v) {
      if (!m.is_object() || !m.contains("extensions") || !m["extensions"].is_object()) return;
      const auto& x = m["extensions"];
      if (x.contains(extension) && x[extension].is_object() && x[extension].contains(key) &&
          x[extension][key].is_number()) {
        *v = x[extension][key].get<double>();
      }
    };
    number("KHR_materials_transmission", "transmissionFactor", &e.transmission);
    number("KHR_materials_ior", "ior", &e.ior);
    out.push_back(e);
  }
  return out;
}

// glTF metallic-roughness onto the Whitted materials (docs/raytracer.md, "Materials from
// the mesh file").
FileMaterial gltf_material(const aiMaterial& a, const std::string& name, const std::string& path, const GltfExtras& x) {
  FileMaterial fm;
  fm.m.name = name;
  fm.where = path;
  aiColor4D base(1, 1, 1, 1);
  if (a.Get(AI_MATKEY_BASE_COLOR, base) != AI_SUCCESS) {
    aiColor3D d(1, 1, 1);
    if (a.Get(AI_MATKEY_COLOR_DIFFUSE, d) == AI_SUCCESS) base = aiColor4D(d.r, d.g, d.b, 1);
  }
  float metallic = 1, roughness = 1, transmission = 0, ior = 1.5f;  // the format's defaults
  a.Get(AI_MATKEY_METALLIC_FACTOR, metallic);
  a.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
  a.Get(AI_MATKEY_TRANSMISSION_FACTOR, transmission);
  a.Get(AI_MATKEY_REFRACTI, ior);
  const float all[] = {base.r, base.g, base.b, metallic, roughness, transmission, ior};
  for (float v : all) {
    if (!std::isfinite(v)) throw SceneError(path + ": material '" + name + "': a factor is not finite");
  }
  fm.m.diffuse = glm::clamp(glm::dvec3(file_decimal(base.r), file_decimal(base.g), file_decimal(base.b)), 0.0, 1.0);
  const double r = std::clamp(file_decimal(roughness), 0.0, 1.0), mt = std::clamp(file_decimal(metallic), 0.0, 1.0);
  fm.m.specular = 1 - r;
  const double r4 = r * r * r * r;  // Blinn-Phong exponent of the GGX width alpha = r^2: 2 / alpha^2 - 2
  fm.m.shininess = r4 > 0 ? std::clamp(2 / r4 - 2, 1.0, 10000.0) : 10000.0;
  fm.m.reflectivity = mt * (1 - r);
  const double tr = std::isnan(x.transmission) ? file_decimal(transmission) : x.transmission;
  const double eta = std::isnan(x.ior) ? file_decimal(ior) : x.ior;
  if (!std::isfinite(tr) || !std::isfinite(eta)) throw SceneError(path + ": material '" + name + "': a factor is not finite");
  fm.m.transparency = std::min(std::clamp(tr, 0.0, 1.0), 1 - fm.m.reflectivity);
  fm.m.ior = std::clamp(eta, 1.0, 4.0);
  return fm;
}

std::string serialize(const Mesh& m) {
  std::string s;
  put<uint64_t>(s, m.materials.size());
  for (const FileMaterial& f : m.materials) {
    put_string(s, f.m.name);
    put_string(s, f.where);
    put<uint8_t>(s, f.defined);
    put(s, f.m.diffuse);
    for (double v : {f.m.specular, f.m.shininess, f.m.reflectivity, f.m.transparency, f.m.ior}) put(s, v);
  }
  put<uint64_t>(s, m.skipped_primitives);
  put<uint64_t>(s, m.groups.size());
  for (const MeshGroup& g : m.groups) {
    put<uint64_t>(s, g.name.size());
    s += g.name;
    put<uint64_t>(s, g.triangles.size());
    for (size_t i = 0; i < g.triangles.size(); ++i) {
      for (int c = 0; c < 3; ++c) put(s, g.triangles[i].p[c]);
      for (int c = 0; c < 3; ++c) put(s, g.normals[i][c]);
      put<int32_t>(s, g.material[i]);
    }
  }
  return s;
}
Mesh deserialize(const std::string& s) {
  Mesh m;
  size_t pos = 0;
  const uint64_t materials = get<uint64_t>(s, pos);
  if (materials > s.size()) throw SceneError("mesh reader: short result");
  for (uint64_t k = 0; k < materials; ++k) {
    FileMaterial f;
    f.m.name = get_string(s, pos);
    f.where = get_string(s, pos);
    f.defined = get<uint8_t>(s, pos) != 0;
    f.m.diffuse = get<glm::dvec3>(s, pos);
    f.m.specular = get<double>(s, pos);
    f.m.shininess = get<double>(s, pos);
    f.m.reflectivity = get<double>(s, pos);
    f.m.transparency = get<double>(s, pos);
    f.m.ior = get<double>(s, pos);
    m.materials.push_back(f);
  }
  m.skipped_primitives = get<uint64_t>(s, pos);
  const uint64_t groups = get<uint64_t>(s, pos);
  for (uint64_t k = 0; k < groups; ++k) {
    MeshGroup g;
    g.name = get_string(s, pos);
    const uint64_t n = get<uint64_t>(s, pos);
    if (n > (s.size() - pos) / (6 * sizeof(glm::dvec3) + sizeof(int32_t))) throw SceneError("mesh reader: short result");
    g.triangles.resize(n);
    g.normals.resize(n);
    g.material.resize(n);
    for (uint64_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) g.triangles[i].p[c] = get<glm::dvec3>(s, pos);
      for (int c = 0; c < 3; ++c) g.normals[i][c] = get<glm::dvec3>(s, pos);
      const int32_t mi = get<int32_t>(s, pos);
      if (mi < -1 || mi >= static_cast<int64_t>(m.materials.size())) throw SceneError("mesh reader: bad material index");
      g.material[i] = mi;
    }
    m.triangles += n;
    m.groups.push_back(std::move(g));
  }
  return m;
}

}  // namespace rt::mesh_library
