// Output formats: the extension chooses PNG (8-bit), PFM or OpenEXR (linear radiance,
// unclamped); any other is refused by name. The PFM is read back here by a reader
// written from the format's definition, independent of the writer; the OpenEXR file by
// the OpenEXR library, and compared with the PFM of the same render.
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <vector>

#include "common/util/source_tree.h"
#include "sw/render/image.h"
#include "sw/render/render.h"
#include "sw/scene/scene.h"

namespace rt {
namespace {

std::string tmp_path(const std::string& name) {
  std::string d = ::testing::TempDir();
  while (d.size() > 1 && d.back() == '/') d.pop_back();
  return d + "/" + name;
}

// A PFM reader: "PF" (RGB) or "Pf" (grey), width, height, scale (negative: little-endian
// data), each separated by white space, one white-space byte, then rows bottom to top.
struct Pfm {
  int w = 0, h = 0;
  std::vector<float> rgb;  // top row first, as Image stores it
  float at(int x, int y, int c) const { return rgb[(static_cast<size_t>(y) * w + x) * 3 + c]; }
};
Pfm read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::istringstream hs(data);
  std::string magic;
  double scale = 0;
  Pfm p;
  hs >> magic >> p.w >> p.h >> scale;
  EXPECT_EQ(magic, "PF");
  EXPECT_LT(scale, 0) << "little-endian";
  const size_t header = static_cast<size_t>(hs.tellg()) + 1;
  const size_t n = static_cast<size_t>(p.w) * p.h * 3;
  EXPECT_EQ(data.size(), header + n * 4);
  p.rgb.resize(n);
  for (int row = 0; row < p.h; ++row) {  // file row 0 is the image's bottom row
    for (size_t k = 0; k < static_cast<size_t>(p.w) * 3; ++k) {
      const unsigned char* b = reinterpret_cast<const unsigned char*>(data.data()) + header +
                               (static_cast<size_t>(row) * p.w * 3 + k) * 4;
      const uint32_t bits = b[0] | (b[1] << 8) | (b[2] << 16) | (static_cast<uint32_t>(b[3]) << 24);
      float v;
      std::memcpy(&v, &bits, 4);
      p.rgb[static_cast<size_t>(p.h - 1 - row) * p.w * 3 + k] = v;
    }
  }
  return p;
}

// The levels' table gives the formula's level for every double: at and around every
// level's start (where the two could part), and at random values of every scale.
TEST(ImageFormat, LevelTableEqualsTheFormula) {
  for (int k = 1; k < 256; ++k) {
    const double guess = std::pow((k - 0.5) / 255.0, 2.2);
    double v = guess;
    for (int i = 0; i < 300; ++i) v = std::nextafter(v, 0.0);
    for (int i = 0; i < 600; ++i, v = std::nextafter(v, 1.0)) {
      ASSERT_EQ(to_level(v), to_level_by_formula(v)) << "k = " << k << ", v = " << v;
    }
  }
  uint64_t x = 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < 200000; ++i) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    const double v = std::ldexp(static_cast<double>(x >> 11) / 9007199254740992.0, -static_cast<int>(x % 40));
    ASSERT_EQ(to_level(v), to_level_by_formula(v)) << v;
    ASSERT_EQ(to_level(-v), 0);
    ASSERT_EQ(to_level(1 + v), 255);
  }
  for (double v : {0.0, -0.0, 1.0, 5e-324, std::nextafter(1.0, 0.0), std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_EQ(to_level(v), to_level_by_formula(v)) << v;
  }
}

TEST(ImageFormat, ExtensionChoosesTheFormat) {
  EXPECT_EQ(image_format("a.png"), ImageFormat::kPng);
  EXPECT_EQ(image_format("dir.x/A.PNG"), ImageFormat::kPng);
  EXPECT_EQ(image_format("a.pfm"), ImageFormat::kPfm);
  EXPECT_EQ(image_format("a.Pfm"), ImageFormat::kPfm);
  auto error_of = [](const std::string& p) {
    try {
      image_format(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("x.jpg"),
            "--out x.jpg: unknown image format '.jpg': the name must end in .png (8-bit), .pfm or .exr (linear "
            "radiance, 32-bit float)");
  EXPECT_EQ(error_of("render"),
            "--out render: no extension: the name must end in .png (8-bit), .pfm or .exr (linear radiance, 32-bit "
            "float)");
  EXPECT_NE(error_of("x.exr.tif").find("unknown image format '.tif'"), std::string::npos);
  EXPECT_EQ(image_format("a.EXR"), ImageFormat::kExr);
}

TEST(ImageFormat, PfmHoldsTheUnclampedLinearValues) {
  Image img(3, 2);
  img.at(0, 0) = glm::dvec3(0.5, 2.75, 1000.25);  // top left
  img.at(2, 1) = glm::dvec3(1e-3, 0, 7);          // bottom right
  img.at(1, 0) = glm::dvec3(0.1, 0.2, 0.3);
  const std::string path = tmp_path("values.pfm");
  img.write(path);
  const Pfm p = read_pfm(path);
  ASSERT_EQ(p.w, 3);
  ASSERT_EQ(p.h, 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(p.at(x, y, c), static_cast<float>(img.at(x, y)[c])) << x << " " << y;
    }
  }
  EXPECT_EQ(p.at(0, 0, 2), 1000.25f);
}

TEST(ImageFormat, RenderedRadianceAboveOneSurvivesInPfmOnly) {
  // The one-triangle scene under a light four times as bright: its lit pixels exceed 1,
  // which the PNG clamps to 255 and the PFM keeps.
  Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/one_triangle.json");
  for (Light& l : s.lights) l.color *= 4.0;
  ReferenceIntersector ref(s.triangles);
  RenderOptions ro;
  ro.width = 16;
  ro.height = 16;
  const Image img = render(s, ref, ro, nullptr);
  const std::string pfm = tmp_path("bright.pfm"), png = tmp_path("bright.png");
  img.write(pfm);
  img.write(png);
  const Pfm p = read_pfm(pfm);
  ASSERT_EQ(p.w, 16);
  ASSERT_EQ(p.h, 16);
  float brightest = 0;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(p.at(x, y, c), static_cast<float>(img.at(x, y)[c]));
        brightest = std::max(brightest, p.at(x, y, c));
      }
    }
  }
  EXPECT_GT(brightest, 1.5f);
  std::ifstream in(png, std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  EXPECT_EQ(std::memcmp(sig, "\x89PNG\r\n\x1a\n", 8), 0);
}

// An OpenEXR file's R, G, B as floats, row-major from the top (the library's reader).
struct Exr {
  int w = 0, h = 0;
  std::vector<float> v;
  float at(int x, int y, int c) const { return v[3 * (static_cast<size_t>(y) * w + x) + c]; }
};

Exr read_exr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  Exr e;
  e.w = dw.max.x - dw.min.x + 1;
  e.h = dw.max.y - dw.min.y + 1;
  e.v.assign(static_cast<size_t>(e.w) * e.h * 3, -1.0f);
  Imf::FrameBuffer fb;
  const char* names[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    char* base = reinterpret_cast<char*>(e.v.data() + c) -
                 (static_cast<ptrdiff_t>(dw.min.x) + static_cast<ptrdiff_t>(dw.min.y) * e.w) * 3 * sizeof(float);
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, 3 * sizeof(float), 3 * sizeof(float) * e.w));
  }
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return e;
}

TEST(ImageFormat, ExrHoldsThePfmsValues) {
  // The bright one-triangle render to .exr and .pfm: the same floats, pixel for pixel.
  Scene s = load_scene(std::string(FMPP_SOURCE_DIR) + "/scenes/one_triangle.json");
  for (Light& l : s.lights) l.color *= 4.0;
  ReferenceIntersector ref(s.triangles);
  RenderOptions ro;
  ro.width = 24;
  ro.height = 16;
  const Image img = render(s, ref, ro, nullptr);
  const std::string pfm = tmp_path("same.pfm"), exr = tmp_path("same.exr");
  img.write(pfm);
  img.write(exr);
  const Pfm p = read_pfm(pfm);
  const Exr e = read_exr(exr);
  ASSERT_EQ(e.w, 24);
  ASSERT_EQ(e.h, 16);
  float brightest = 0;
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 24; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(e.at(x, y, c), p.at(x, y, c)) << x << " " << y << " " << c;
        brightest = std::max(brightest, e.at(x, y, c));
      }
    }
  }
  EXPECT_GT(brightest, 1.5f);
}

}  // namespace
}  // namespace rt
