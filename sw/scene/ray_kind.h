// The kinds of ray the Whitted tracer casts (render.h): the renderer counts them, and a
// material names the kind of the rays it spawns (material.h).
#pragma once

namespace rt {

enum class RayKind { kPrimary = 0, kShadow = 1, kReflection = 2, kRefraction = 3 };
inline constexpr int kNumRayKinds = 4;

inline const char* to_string(RayKind k) {
  switch (k) {
    case RayKind::kPrimary: return "primary";
    case RayKind::kShadow: return "shadow";
    case RayKind::kReflection: return "reflection";
    case RayKind::kRefraction: return "refraction";
  }
  return "?";
}

}  // namespace rt
