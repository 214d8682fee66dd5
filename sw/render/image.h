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
  const glm::dvec3& operator[](size_t i) const { return px_[i]; }
  size_t size() const { return px_.size(); }
  // 8-bit RGB, row-major from the top: clamp to [0, 1], gamma 1/2.2, round.
  std::vector<uint8_t> to_rgb8() const;
  // Writes a PNG (stb_image_write), atomically and checked (fmpp::write_output). Throws
  // std::runtime_error naming the path and the cause on failure.
  void write_png(const std::string& path) const;
  // Writes a PFM (Portable Float Map, "PF": RGB, 32-bit little-endian floats, rows from
  // the bottom up, as the format defines): the linear radiance, unclamped, no gamma.
  // Atomic and checked like write_png.
  void write_pfm(const std::string& path) const;
  // Writes an OpenEXR file (Debian's OpenEXR library; sw/render/image_exr.cpp): R, G, B as
  // 32-bit floats, the linear radiance, unclamped, no gamma, rows from the top; atomic and
  // checked like write_png.
  void write_exr(const std::string& path) const;
  // Writes the format that image_format(path) names.
  void write(const std::string& path) const;

 private:
  int w_, h_;
  std::vector<glm::dvec3> px_;
};

// The 8-bit level of one linear value, as to_rgb8 gives it (a search of the levels'
// starts), and the same from the formula itself (clamp, pow, round): equal for every
// double (tests/render/image_format_test.cpp).
uint8_t to_level(double v);
uint8_t to_level_by_formula(double v);

// The output formats, chosen by the file name's extension (case-insensitive): ".png"
// (8-bit, tone-mapped as to_rgb8), ".pfm" and ".exr" (linear radiance, 32-bit float,
// unclamped).
enum class ImageFormat { kPng, kPfm, kExr };
// The format of `path`; throws std::invalid_argument("<option> <path>: ...") naming the
// extension and the accepted ones for any other (".jpg", none).
ImageFormat image_format(const std::string& path, const std::string& option = "--out");

struct ImageDiff {
  uint64_t pixels = 0;        // pixels whose 8-bit value differs in any channel
  uint64_t pixels_over = 0;   // ... by more than `tolerance` levels
  int max_delta = 0;          // largest channel difference, 0..255
};
ImageDiff compare(const Image& a, const Image& b, int tolerance = 8);

}  // namespace rt
