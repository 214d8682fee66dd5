// A scene of the repository's scenes/ folder, by name, for tests that plan or render one.
#pragma once

#include <string>

#include "common/util/source_tree.h"
#include "sw/scene/scene.h"

namespace rt {

inline Scene shipped_scene(const std::string& name) {
  return load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + name + ".json");
}

// The Cornell box with its light made a 0.6 x 0.6 rectangle of samples x pool points:
// shadow rays of many origins, with the box's mirrors' secondary rays.
inline Scene cornell_with_area_light(int samples, int pool) {
  Scene sc = shipped_scene("cornell");
  Light area;
  area.type = LightType::kRect;
  area.position = sc.lights[0].position;
  area.edge1 = glm::dvec3(0.6, 0, 0);
  area.edge2 = glm::dvec3(0, 0, 0.6);
  area.samples = samples;
  area.pool = pool;
  sc.lights = {area};
  return sc;
}

}  // namespace rt
