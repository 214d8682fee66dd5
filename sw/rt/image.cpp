// Image tone mapping, PNG output and comparison (see image.h).
#include "sw/rt/image.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "common/util/output_file.h"

namespace rt {

std::vector<uint8_t> Image::to_rgb8() const {
  std::vector<uint8_t> out(px_.size() * 3);
  for (size_t i = 0; i < px_.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double v = std::pow(std::clamp(px_[i][c], 0.0, 1.0), 1.0 / 2.2);
      out[3 * i + c] = static_cast<uint8_t>(std::lround(v * 255.0));
    }
  }
  return out;
}

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
  }
}

ImageFormat image_format(const std::string& path, const std::string& option) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".pfm") return ImageFormat::kPfm;
  throw std::invalid_argument(option + " " + path + ": " +
                              (ext.empty() ? std::string("no extension") : "unknown image format '" + ext + "'") +
                              ": the name must end in .png (8-bit) or .pfm (linear radiance, 32-bit float)");
}

ImageDiff compare(const Image& a, const Image& b, int tolerance) {
  if (a.width() != b.width() || a.height() != b.height()) throw std::invalid_argument("rt::compare: image sizes differ");
  const std::vector<uint8_t> x = a.to_rgb8(), y = b.to_rgb8();
  ImageDiff d;
  for (size_t i = 0; i < x.size(); i += 3) {
    int m = 0;
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(static_cast<int>(x[i + c]) - static_cast<int>(y[i + c])));
    d.pixels += m > 0;
    d.pixels_over += m > tolerance;
    d.max_delta = std::max(d.max_delta, m);
  }
  return d;
}

}  // namespace rt
