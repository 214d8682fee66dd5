// A scene of the repository's scenes/ folder, by name, for tests that plan or render one.
#pragma once

#include <string>

#include "sw/rt/scene.h"

#ifndef FMPP_SOURCE_DIR
#define FMPP_SOURCE_DIR "."
#endif

namespace rt {

inline Scene shipped_scene(const std::string& name) {
  return load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/" + name + ".json");
}

}  // namespace rt
