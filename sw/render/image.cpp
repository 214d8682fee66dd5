// Image tone mapping, PNG output and comparison (see image.h).
#include "sw/render/image.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "common/util/output_file.h"

namespace rt {

namespace {

// The tone curve: the 8-bit level of a linear value.
uint8_t level_by_formula(double v) {
  return static_cast<uint8_t>(std::lround(std::pow(std::clamp(v, 0.0, 1.0), 1.0 / 2.2) * 255.0));
}

// Where each level starts: start[k] is the smallest double in (0, 1) whose level is at
// least k, found from the formula itself (a bisection on the doubles near the curve's
// inverse), so that a search of the table gives the formula's level. Values within 64
// ulps of a start are given by the formula directly: the table cannot differ from it
// there even if pow were not monotone within its last ulp.
struct LevelStarts {
  double start[257];
  LevelStarts() {
    start[0] = 0;
    for (int k = 1; k < 256; ++k) {
      const double guess = std::pow((k - 0.5) / 255.0, 2.2);
      // The guess is within a few ulps of the start (at most 6e-16 of it, measured over
      // the 255 levels): 1e-14 of the value brackets it, else the bisection falls back to
      // the whole of (0, 1) below.
      double lo = guess * (1 - 1e-14), hi = guess * (1 + 1e-14);
      if (level_by_formula(lo) >= k) lo = 0;
      if (level_by_formula(hi) < k) hi = 1;
      // lo has a level below k, hi at least k: bisect on the ordered bit patterns.
      uint64_t a, b;
      std::memcpy(&a, &lo, 8);
      std::memcpy(&b, &hi, 8);
      while (b - a > 1) {
        const uint64_t m = a + (b - a) / 2;
        double v;
        std::memcpy(&v, &m, 8);
        (level_by_formula(v) >= k ? b : a) = m;
      }
      std::memcpy(&start[k], &b, 8);
    }
    start[256] = 1;
  }
};

uint8_t level(double v) {
  if (v <= 0) return 0;     // clamped to 0: pow(0) = 0
  if (v >= 1) return 255;   // clamped to 1
  if (!(v == v)) return level_by_formula(v);  // NaN, as the formula has it
  static const LevelStarts t;
  const double* up = std::upper_bound(t.start + 1, t.start + 256, v);  // first start above v
  const int k = static_cast<int>(up - t.start) - 1;                    // start[k] <= v < start[k + 1]
  const double near = 64 * std::numeric_limits<double>::epsilon() * v;
  if (v - t.start[k] <= near || t.start[k + 1] - v <= near) return level_by_formula(v);
  return static_cast<uint8_t>(k);
}

}  // namespace

std::vector<uint8_t> Image::to_rgb8() const {
  std::vector<uint8_t> out(px_.size() * 3);
  for (size_t i = 0; i < px_.size(); ++i) {
    for (int c = 0; c < 3; ++c) out[3 * i + c] = level(px_[i][c]);
  }
  return out;
}

uint8_t to_level(double v) { return level(v); }
uint8_t to_level_by_formula(double v) { return level_by_formula(v); }

void Image::write_png(const std::string& path) const {
  const std::vector<uint8_t> rgb = to_rgb8();
  // Encoded in memory, then written (checked, atomically) by write_output: stb's own
  // file writer ignores write errors.
  std::string png;
  auto append = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, w_, h_, 3, rgb.data(), w_ * 3)) {
    throw std::runtime_error(path + ": cannot encode PNG");
  }
  fmpp::write_output(path, png);
}

void Image::write_pfm(const std::string& path) const {
  // Header: "PF" (three channels), width and height, and the scale, negative for
  // little-endian data (its magnitude, 1, is not applied to the values).
  std::string pfm = "PF\n" + std::to_string(w_) + " " + std::to_string(h_) + "\n-1.0\n";
  const size_t header = pfm.size();
  pfm.resize(header + px_.size() * 3 * sizeof(float));
  char* out = &pfm[header];
  for (int y = h_ - 1; y >= 0; --y) {  // bottom row first
    for (int x = 0; x < w_; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float v = static_cast<float>(at(x, y)[c]);
        uint32_t bits;
        std::memcpy(&bits, &v, 4);
        for (int b = 0; b < 4; ++b) *out++ = static_cast<char>((bits >> (8 * b)) & 0xff);  // little-endian
      }
    }
  }
  fmpp::write_output(path, pfm);
}

void Image::write(const std::string& path) const {
  switch (image_format(path)) {
    case ImageFormat::kPng: return write_png(path);
    case ImageFormat::kPfm: return write_pfm(path);
    case ImageFormat::kExr: return write_exr(path);
  }
}

ImageFormat image_format(const std::string& path, const std::string& option) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".pfm") return ImageFormat::kPfm;
  if (ext == ".exr") return ImageFormat::kExr;
  throw std::invalid_argument(option + " " + path + ": " +
                              (ext.empty() ? std::string("no extension") : "unknown image format '" + ext + "'") +
                              ": the name must end in .png (8-bit), .pfm or .exr (linear radiance, 32-bit float)");
}

ImageDiff compare(const Image& a, const Image& b, int tolerance) {
  if (a.width() != b.width() || a.height() != b.height()) throw std::invalid_argument("rt::compare: image sizes differ");
  ImageDiff d;
  for (size_t i = 0; i < a.size(); ++i) {
    int m = 0;
    for (int c = 0; c < 3; ++c) {
      // Equal values have equal levels: only differing ones are tone-mapped.
      if (a[i][c] != b[i][c]) m = std::max(m, std::abs(int{level(a[i][c])} - int{level(b[i][c])}));
    }
    d.pixels += m > 0;
    d.pixels_over += m > tolerance;
    d.max_delta = std::max(d.max_delta, m);
  }
  return d;
}

}  // namespace rt
