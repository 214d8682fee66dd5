// Images: linear RGB radiance, tone-mapped to 8-bit sRGB-like values for PNG output and
// for comparisons (two renders are compared by their 8-bit pixels).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rt {

class Image {
 public:
  Image(int w, int h) : w_(w), h_(h), px_(static_cast<size_t>(w) * h, glm::dvec3(0)) {}
  int width() const { return w_; }
  int height() const { return h_; }
  glm::dvec3& at(int x, int y) { return px_[static_cast<size_t>(y) * w_ + x]; }
  const glm::dvec3& at(int x, int y) const { return px_[static_cast<size_t>(y) * w_ + x]; }
  glm::dvec3& operator[](size_t i) { return px_[i]; }
  // 8-bit RGB, row-major from the top: clamp to [0, 1], gamma 1/2.2, round.
  std::vector<uint8_t> to_rgb8() const;
  // Writes a PNG (stb_image_write), atomically and checked (fmpp::write_output). Throws
  // std::runtime_error naming the path and the cause on failure.
  void write_png(const std::string& path) const;

 private:
  int w_, h_;
  std::vector<glm::dvec3> px_;
};

struct ImageDiff {
  uint64_t pixels = 0;        // pixels whose 8-bit value differs in any channel
  uint64_t pixels_over = 0;   // ... by more than `tolerance` levels
  int max_delta = 0;          // largest channel difference, 0..255
};
ImageDiff compare(const Image& a, const Image& b, int tolerance = 8);

}  // namespace rt
