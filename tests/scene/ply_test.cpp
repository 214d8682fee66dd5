// PLY files read by the project (docs/raytracer.md, "Numbers"): binary data that begins
// with a white-space byte, faces of every list and index type, elements and properties
// the reader passes over, polygons, and bad files as errors naming the file and cause.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "sw/scene/mesh.h"
#include "sw/scene/scene.h"
#include "tests/support/test_files.h"

namespace rt {
namespace {

using glm::dvec3;

std::string dir() { return test_files::own_dir("ply_"); }
std::string write(const std::string& name, const std::string& text) { return test_files::write(dir(), name, text); }
using test_files::error_of;

enum class Format { kAscii, kLittle, kBig };
const Format kFormats[] = {Format::kAscii, Format::kLittle, Format::kBig};

const char* format_name(Format f) {
  return f == Format::kAscii ? "ascii" : f == Format::kLittle ? "binary_little_endian" : "binary_big_endian";
}

// The data of a PLY file in one format: values appended as a type of the header names.
class Data {
 public:
  explicit Data(Format f) : f_(f) {}

  // Appends v as the PLY type `type` (char ... double).
  Data& put(const std::string& type, double v) {
    if (type == "char") return bytes(static_cast<int8_t>(v));
    if (type == "uchar") return bytes(static_cast<uint8_t>(v));
    if (type == "short") return bytes(static_cast<int16_t>(v));
    if (type == "ushort") return bytes(static_cast<uint16_t>(v));
    if (type == "int") return bytes(static_cast<int32_t>(v));
    if (type == "uint") return bytes(static_cast<uint32_t>(v));
    if (type == "float") return bytes(static_cast<float>(v));
    return bytes(v);
  }
  // Ends an element instance (a line in ASCII).
  Data& end() {
    if (f_ == Format::kAscii) out_ += "\n";
    return *this;
  }
  const std::string& str() const { return out_; }

 private:
  template <class T>
  Data& bytes(T v) {
    if (f_ == Format::kAscii) {
      char b[40];
      if constexpr (std::is_floating_point_v<T>) {
        std::snprintf(b, sizeof b, "%.17g ", static_cast<double>(v));
      } else {
        std::snprintf(b, sizeof b, "%lld ", static_cast<long long>(v));
      }
      out_ += b;
      return *this;
    }
    char b[sizeof v];
    std::memcpy(b, &v, sizeof v);
    for (size_t k = 0; k < sizeof v; ++k) out_ += b[f_ == Format::kBig ? sizeof v - 1 - k : k];
    return *this;
  }

  Format f_;
  std::string out_;
};

std::string head(Format f, const std::string& elements) {
  return std::string("ply\nformat ") + format_name(f) + " 1.0\ncomment written by ply_test\n" + elements +
         "end_header\n";
}

// The corners of every triangle of the mesh, in order.
std::vector<std::array<dvec3, 3>> corners(const Mesh& m) {
  std::vector<std::array<dvec3, 3>> out;
  for (const MeshGroup& g : m.groups) {
    for (const auto& t : g.triangles) out.push_back({t.p[0], t.p[1], t.p[2]});
  }
  return out;
}

// A value of type T (float or double) near `near` whose first byte in the file, in the
// given byte order, is `first`: little-endian, its lowest mantissa byte; big-endian,
// its sign and exponent byte (a tiny number for the white-space bytes).
template <class T, class Bits>
double with_first_byte(double near, unsigned char first, bool big) {
  T v = static_cast<T>(near);
  Bits bits;
  std::memcpy(&bits, &v, sizeof v);
  const int shift = big ? 8 * (sizeof v - 1) : 0;
  bits = (bits & ~(Bits{0xff} << shift)) | (Bits{first} << shift);
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// The data of a binary file begins at the byte after end_header's line, whatever that
// byte is: a NUL, a tab, a line feed, a vertical tab, a form feed, a carriage return or
// a space is the first byte of the first vertex, read as it is.
TEST(LoaderPly, BinaryDataMayBeginWithWhiteSpaceBytes) {
  for (const Format f : {Format::kLittle, Format::kBig}) {
    for (const std::string type : {"float", "double"}) {
      for (const unsigned char first : {0x00, 0x09, 0x0a, 0x0b, 0x0c, 0x0d, 0x20}) {
        const bool big = f == Format::kBig;
        const double x0 = type == "float" ? with_first_byte<float, uint32_t>(0.3, first, big)
                                          : with_first_byte<double, uint64_t>(-0.6130180635734643, first, big);
        const std::vector<dvec3> v = {{x0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5}};
        const std::vector<std::array<int, 3>> faces = {{0, 1, 2}, {2, 1, 3}};
        Data d(f);
        for (const dvec3& p : v) d.put(type, p.x).put(type, p.y).put(type, p.z);
        for (const auto& t : faces) d.put("uchar", 3).put("int", t[0]).put("int", t[1]).put("int", t[2]);
        // A header ending in CR LF for one of the cases: the data begins after the LF.
        std::string h = head(f, "element vertex 4\nproperty " + type + " x\nproperty " + type + " y\nproperty " + type +
                                    " z\nelement face 2\nproperty list uchar int vertex_indices\n");
        if (first == 0x20 && type == "double") h.insert(h.size() - 1, "\r");
        const std::string what = std::string(format_name(f)) + " " + type + " first byte " + std::to_string(first);
        ASSERT_EQ(static_cast<unsigned char>(d.str()[0]), first) << what;
        Mesh m;
        const std::string e = error_of([&] { m = load_mesh(write("ws.ply", h + d.str())); });
        EXPECT_EQ(e, "no error") << what;
        const auto got = corners(m);
        if (got.size() != 2u) {
          ADD_FAILURE() << what << ": " << got.size() << " triangles";
          continue;
        }
        for (size_t k = 0; k < 2; ++k) {
          for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(got[k][c], v[faces[k][c]]) << what << ": triangle " << k << " corner " << c;
          }
        }
      }
    }
  }
}

// Faces of every list-length type and index type, named vertex_indices or vertex_index,
// in every format.
TEST(LoaderPly, FacesOfEveryListAndIndexType) {
  const char* const kTypes[] = {"uchar", "ushort", "uint", "char", "short", "int"};
  const std::vector<dvec3> v = {{0, 0, -3}, {1, 0, -3}, {0, 1, -3}, {1, 1, -3.5}, {2, 0, -3}};
  const std::vector<std::vector<int>> faces = {{0, 1, 2}, {4, 3, 1}, {2, 1, 3}};
  for (const Format f : kFormats) {
    for (const char* count : kTypes) {
      for (const char* index : kTypes) {
        const std::string name = std::string(count) < index ? "vertex_indices" : "vertex_index";
        Data d(f);
        for (const dvec3& p : v) d.put("float", p.x).put("float", p.y).put("float", p.z).end();
        for (const auto& t : faces) {
          d.put(count, 3);
          for (int i : t) d.put(index, i);
          d.end();
        }
        const std::string h = head(f, "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                                      "element face 3\nproperty list " + std::string(count) + " " + index + " " +
                                          name + "\n");
        const std::string what = std::string(format_name(f)) + " list " + count + " " + index;
        const auto got = corners(load_mesh(write("types.ply", h + d.str())));
        ASSERT_EQ(got.size(), faces.size()) << what;
        for (size_t k = 0; k < faces.size(); ++k) {
          for (int c = 0; c < 3; ++c) EXPECT_EQ(got[k][c], v[faces[k][c]]) << what << ": triangle " << k;
        }
      }
    }
  }
}

// A file with elements before, between and after the vertices and faces, properties
// (scalars and lists) before and after the ones read, an element without properties and
// one of no instances, and the faces declared before the vertices: everything else is
// passed over, and the vertex normals are kept.
TEST(LoaderPly, OtherElementsAndPropertiesArePassedOver) {
  const std::string header =
      "element material 2\nproperty uchar red\nproperty list ushort double weights\nproperty float shine\n"
      "element marker 3\n"
      "element face 2\nproperty uchar flags\nproperty list uchar float texcoord\n"
      "property list int uint vertex_indices\n"
      "property int material_index\nproperty list uchar uchar more\n"
      "element empty 0\nproperty list uchar int nothing\n"
      "element vertex 3\nproperty list uchar short tags\nproperty double nz\nproperty float x\nproperty uchar red\n"
      "property float y\nproperty double ny\nproperty float z\nproperty int id\nproperty double nx\n"
      "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty list uchar char crease\n";
  for (const Format f : kFormats) {
    Data d(f);
    d.put("uchar", 200).put("ushort", 2).put("double", 0.5).put("double", 7).put("float", 3).end();
    d.put("uchar", 10).put("ushort", 0).put("float", 1.5).end();
    // The faces: 6 texture coordinates, the indices, a material, 3 more bytes.
    for (int k = 0; k < 2; ++k) {
      d.put("uchar", 9).put("uchar", 6);
      for (int c = 0; c < 6; ++c) d.put("float", 0.25 * c);
      if (k == 0) d.put("int", 3).put("uint", 0).put("uint", 1).put("uint", 2);
      if (k == 1) d.put("int", 3).put("uint", 2).put("uint", 1).put("uint", 0);
      d.put("int", 1).put("uchar", 3).put("uchar", 32).put("uchar", 10).put("uchar", 13).end();
    }
    const double nz[] = {1, 0.5, 0.25};
    for (int k = 0; k < 3; ++k) {
      d.put("uchar", 2).put("short", -k).put("short", 300).put("double", nz[k]);
      d.put("float", k == 1).put("uchar", 255).put("float", k == 2).put("double", 0.125 * k).put("float", -3);
      d.put("int", -7).put("double", 0.0625).end();
    }
    d.put("int", 0).put("int", 1).put("uchar", 0).end();
    d.put("int", 1).put("int", 2).put("uchar", 2).put("char", -1).put("char", 1).end();
    const std::string what = format_name(f);
    const Mesh m = load_mesh(write("other.ply", head(f, header) + d.str()));
    ASSERT_EQ(m.triangles, 2u) << what;
    EXPECT_EQ(m.skipped_primitives, 0u) << what;
    ASSERT_EQ(m.groups.size(), 1u);
    EXPECT_EQ(m.groups[0].name, "");
    const auto got = corners(m);
    EXPECT_EQ(got[0][0], dvec3(0, 0, -3)) << what;
    EXPECT_EQ(got[0][1], dvec3(1, 0, -3)) << what;
    EXPECT_EQ(got[0][2], dvec3(0, 1, -3)) << what;
    EXPECT_EQ(got[1][0], dvec3(0, 1, -3)) << what;
    EXPECT_EQ(got[1][2], dvec3(0, 0, -3)) << what;
    // The normals (0.0625, 0.125 k, nz[k]) as given, made unit length (divided by their
    // largest component first, as the loader does).
    const auto& n = m.groups[0].normals[0];
    for (int k = 0; k < 3; ++k) {
      const dvec3 want = dvec3(0.0625, 0.125 * k, nz[k]) / nz[k];
      EXPECT_EQ(n[k], want / glm::length(want)) << what << ": normal " << k;
    }
  }
}

// Polygons are triangulated as the project triangulates OFF faces; points and lines are
// counted, not kept.
TEST(LoaderPly, PolygonsAsOffPolygons) {
  const double o = 0x1p29;
  const std::vector<dvec3> v = {{o, o, o},     {o + 4, o, o}, {o + 4, o + 4, o}, {o + 2, o + 1, o},
                                {o, o + 4, o}, {o - 1, o + 2, o}, {o + 5, o + 5, o}};
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3, 4, 5}, {1, 6, 2, 3}, {0}, {1, 2}, {6, 4, 0, 2, 1}};
  std::string off = "OFF\n7 5 0\n";
  char b[120];
  for (const dvec3& p : v) {
    std::snprintf(b, sizeof b, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    off += b;
  }
  for (const auto& face : faces) {
    off += std::to_string(face.size());
    for (int i : face) off += " " + std::to_string(i);
    off += "\n";
  }
  const auto want = corners(load_mesh(write("poly.off", off)));
  ASSERT_EQ(want.size(), 4u + 2u + 3u);
  for (const Format f : kFormats) {
    Data d(f);
    for (const dvec3& p : v) d.put("double", p.x).put("double", p.y).put("double", p.z).end();
    for (const auto& face : faces) {
      d.put("uchar", static_cast<double>(face.size()));
      for (int i : face) d.put("int", i);
      d.end();
    }
    const Mesh m = load_mesh(write("poly.ply", head(f, "element vertex 7\nproperty double x\nproperty double y\n"
                                                       "property double z\nelement face 5\n"
                                                       "property list uchar int vertex_indices\n") +
                                                   d.str()));
    EXPECT_EQ(corners(m), want) << format_name(f);
    EXPECT_EQ(m.skipped_primitives, 2u) << format_name(f);
  }
}

// Bad files: errors naming the file, and the line (ASCII) or the face.
TEST(LoaderPly, BadFilesNameTheFileAndTheCause) {
  const std::string d = dir() + "/";
  auto err = [&](const std::string& name, const std::string& text) {
    return error_of([&] { load_mesh(write(name, text)); });
  };
  const std::string xyz = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 2\nproperty list uchar int vertex_indices\n";
  const std::string asc = head(Format::kAscii, xyz + faces) + "0 0 0\n1 0 0\n0 1 0\n";
  // Indices outside the vertices.
  EXPECT_EQ(err("idx.ply", asc + "3 0 1 2\n3 0 3 1\n"),
            d + "idx.ply:15: face 1: refers to vertex 3 of 3 (indices start at 0)");
  EXPECT_EQ(err("neg.ply", asc + "3 0 1 2\n3 0 -1 1\n"),
            d + "neg.ply:15: face 1: refers to vertex -1 of 3 (indices start at 0)");
  Data bin(Format::kLittle);
  for (int k = 0; k < 9; ++k) bin.put("float", k == 3 || k == 7);
  bin.put("uchar", 3).put("int", 0).put("int", 1).put("int", 2);
  const std::string head_le = head(Format::kLittle, xyz + faces);
  EXPECT_EQ(err("big.ply", head_le + Data(bin).put("uchar", 3).put("int", 2).put("int", 7).put("int", 0).str()),
            d + "big.ply: face 1: refers to vertex 7 of 3 (indices start at 0)");
  EXPECT_EQ(err("frac.ply", asc + "3 0 1 2\n3 0 1.5 2\n"),
            d + "frac.ply:15: face 1: index 2 is not a whole number of its type");
  // Data that ends early: in the vertices, within a face, before the faces, in an element after them.
  EXPECT_EQ(err("cutv.ply", head_le + bin.str().substr(0, 30)), d + "cutv.ply: the file ends before its 3 vertices");
  EXPECT_EQ(err("shortv.ply", head(Format::kAscii, xyz + faces) + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"),
            d + "shortv.ply:12: vertex 1: fewer values than its properties");
  EXPECT_EQ(err("cutf.ply", head_le + Data(bin).put("uchar", 3).put("int", 2).str()),
            d + "cutf.ply: face 1: the file ends within it");
  EXPECT_EQ(err("cutn.ply", head_le + bin.str()), d + "cutn.ply: the file ends after 1 of 2 faces");
  EXPECT_EQ(err("cuta.ply", asc + "3 0 1 2\n"), d + "cuta.ply: the file ends after 1 of 2 faces");
  EXPECT_EQ(err("short.ply", asc + "3 0 1 2\n3 0 1\n"), d + "short.ply:15: face 1: fewer values than its properties");
  Data big(Format::kBig);
  for (int k = 0; k < 9; ++k) big.put("float", k == 3 || k == 7);
  big.put("uchar", 3).put("int", 0).put("int", 1).put("int", 2).put("uchar", 3).put("int", 2);
  EXPECT_EQ(err("cutb.ply", head(Format::kBig, xyz + faces) + big.str()),
            d + "cutb.ply: face 1: the file ends within it");
  // An element after the faces, of lists of doubles with an int length.
  const std::string extra = head(Format::kLittle, xyz + faces + "element extra 2\nproperty list int double w\n");
  const std::string two = Data(bin).put("uchar", 3).put("int", 2).put("int", 1).put("int", 0).str();
  EXPECT_EQ(err("cutw.ply", extra + two + Data(Format::kLittle).put("int", 1).put("double", 1).put("int", 2).str()),
            d + "cutw.ply: instance 1 of the element declared on line 10: the file ends within it");
  EXPECT_EQ(err("negl.ply", extra + two + Data(Format::kLittle).put("int", -1).str()),
            d + "negl.ply: instance 0 of the element declared on line 10: a negative list length");
  EXPECT_EQ(err("cutz.ply", head(Format::kAscii, xyz + faces + "element extra 2\nproperty uchar w\n") +
                                 "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n7\n"),
            d + "cutz.ply: the file ends after 1 of 2 instances of the element declared on line 10");
  EXPECT_EQ(err("few.ply", head_le + "\x01"), d + "few.ply: the file ends before its 3 vertices");
  // Headers the reader refuses.
  EXPECT_EQ(err("noidx.ply", head(Format::kAscii, xyz + "element face 1\nproperty list uchar int corners\n")),
            d + "noidx.ply:8: the face element has no vertex_indices list");
  EXPECT_EQ(err("fidx.ply", head(Format::kAscii, xyz + "element face 1\nproperty list uchar float vertex_indices\n")),
            d + "fidx.ply:8: the face element has vertex indices of a type that is not an integer type");
  EXPECT_EQ(err("fcount.ply", head(Format::kAscii, xyz + "element face 1\nproperty list float int vertex_indices\n")),
            d + "fcount.ply:9: a list whose length type is not an integer type");
  EXPECT_EQ(err("strip.ply", head(Format::kAscii, xyz + "element tristrips 1\nproperty list int int vertex_indices\n")),
            d + "strip.ply:8: triangle strips (a tristrips element) are not read: give the faces as a face element");
  EXPECT_EQ(err("nan.ply", head(Format::kAscii, xyz + faces) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"),
            d + "nan.ply:12: vertex 1: property 1 is not a finite number of its type");
}

}  // namespace
}  // namespace rt
