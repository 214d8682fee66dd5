// Scenes for the ray tracer: a small JSON file (camera, point lights, materials,
// background) naming mesh files (OBJ, PLY, OFF, STL, glTF: mesh.h), whose groups get
// materials. Loading checks every field
// and reports errors with the file and the line (JSON syntax, OBJ) or the field.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "sw/isect/geometry.h"

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

struct Light {
  glm::dvec3 position;
  glm::dvec3 color{1, 1, 1};
};

struct Scene {
  std::string path;
  std::vector<std::string> files;  // the JSON file and every mesh file read
  std::string description;
  Camera camera;
  glm::dvec3 background{0, 0, 0};
  glm::dvec3 ambient{0.1, 0.1, 0.1};
  int max_depth = 3;
  std::vector<Light> lights;
  std::vector<Material> materials;
  // Triangles, with per-triangle material and per-vertex normals (face normal if the
  // mesh has none).
  std::vector<fmpp::isect::Triangle> triangles;
  std::vector<int> material_of;
  std::vector<std::array<glm::dvec3, 3>> normals;
};

// Loads a JSON scene and its meshes (paths relative to the JSON file). Throws
// SceneError("<file>:<line>: ..." or "<file>: field 'a.b': ...").
Scene load_scene(const std::string& json_path);

}  // namespace rt
