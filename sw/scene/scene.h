// Scenes for the ray tracer: a small JSON file (camera, point lights, materials,
// background) naming mesh files (OBJ, PLY, OFF, STL, glTF: mesh.h), whose groups get
// materials. Loading checks every field
// and reports errors with the file and the line (JSON syntax, OBJ) or the field.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/isect/geometry/geometry.h"
#include "sw/scene/sampling.h"

namespace rt {

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Camera {
  glm::dvec3 eye{0, 0, 0};
  glm::dvec3 look_at{0, 0, -1};
  glm::dvec3 up{0, 1, 0};
  double fov_y_deg = 45;
};

struct Material {
  std::string name;
  glm::dvec3 diffuse{0.7, 0.7, 0.7};
  double specular = 0;     // Blinn-Phong highlight weight
  double shininess = 32;
  double reflectivity = 0;  // share of light from the mirror direction
  double transparency = 0;  // share of light from the refracted direction
  double ior = 1.5;
};

// A light (docs/raytracer.md, "Lights"). Every kind but the point light is given its
// own fields; none of them is geometry (rays do not hit lights).
enum class LightType { kPoint, kDirectional, kSphere, kRect };
const char* to_string(LightType t);

struct Light {
  glm::dvec3 position;  // point: the position; sphere: the centre; rect: a corner
  glm::dvec3 color{1, 1, 1};
  LightType type = LightType::kPoint;
  glm::dvec3 direction{0, -1, 0};  // directional: unit, the way its light travels
  double radius = 0;               // sphere
  glm::dvec3 edge1{0}, edge2{0};   // rect: the corners are position + {0, edge1} + {0, edge2}
  // Area lights: shadow rays per shading point (one per stratum of the light's surface),
  // and the pool: that many points per stratum, fixed per render, each shading point
  // taking one of them per stratum (0: a fresh point for every shadow ray).
  int samples = 1;
  int pool = 16;
  bool area() const { return type == LightType::kSphere || type == LightType::kRect; }
};

struct Scene {
  std::string path;
  std::vector<std::string> files;  // the JSON file and every mesh file read
  std::string description;
  Camera camera;
  glm::dvec3 background{0, 0, 0};
  glm::dvec3 ambient{0.1, 0.1, 0.1};
  int max_depth = 3;
  // Samples per pixel (stratified, jittered; 1: the pixel's centre) and the seed of every
  // random choice of a render (sampling.h).
  int spp = 1;
  uint64_t seed = kDefaultSeed;
  std::vector<Light> lights;
  std::vector<Material> materials;
  // Triangles, with per-triangle material and per-vertex normals (face normal if the
  // mesh has none).
  std::vector<fmpp::isect::Triangle> triangles;
  std::vector<int> material_of;
  std::vector<std::array<glm::dvec3, 3>> normals;
};

// The largest |coordinate| of any point of a scene: the camera's eye and look_at, a
// light's position, centre or corner, a mesh translation and every mesh vertex as placed
// (docs/raytracer.md, "Numbers"). The renderer casts rays between such points: a shadow
// ray runs from a light to a shaded point, its direction their difference (up to twice
// this) plus the shaded point's own error (the hit's t within its certified bound,
// under 100 %, so under twice this again), and the intersector takes ray origins and
// directions up to fmpp::isect::kMaxCoordinate (1e100) only. 1e99 keeps every such ray
// inside with room to spare.
inline constexpr double kMaxScenePosition = 1e99;
// The shortest vector the renderer normalizes: the view direction, `up` across it, a
// light's direction, a rotation's axis, a rectangle light's normal (edge1 x edge2). Its
// squared length is then a normal double, so its unit vector is finite.
inline constexpr double kMinSceneLength = 1e-150;
// The largest |component| of a rectangle light's edges: the renderer normalizes
// edge1 x edge2, whose squared length (up to about (3 x 1e75^2)^2) stays finite.
inline constexpr double kMaxRectEdge = 1e75;

// Limits of the sampling fields (scene JSON and fmpp-render's options).
inline constexpr int kMaxSpp = 1024;
inline constexpr int kMaxLightSamples = 1024;
inline constexpr int kMaxLightPool = 4096;

// Loads a JSON scene and its meshes (paths relative to the JSON file). Throws
// SceneError("<file>:<line>: ..." or "<file>: field 'a.b': ...").
Scene load_scene(const std::string& json_path);

}  // namespace rt
