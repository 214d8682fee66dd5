// A PLY file's header and what the mesh reader takes from it (mesh_ply.cpp reads the body).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace rt::ply {

enum class Type { kChar, kUChar, kShort, kUShort, kInt, kUInt, kFloat, kDouble };

// The bytes a value of type t takes in a binary body.
size_t size_of(Type t);
bool integral(Type t);

struct Property {
  std::string name;
  bool list = false;
  Type count = Type::kUChar, type = Type::kFloat;  // count: a list's length type
};
struct Element {
  std::string name;
  unsigned long long count = 0;
  size_t line = 0;  // the header line that declares it
  std::vector<Property> props;
};
struct Header {
  enum Format { kAscii, kLittle, kBig } format = kAscii;
  std::vector<Element> elements;
  size_t body = 0;       // byte offset of the first byte after end_header's line
  size_t body_line = 0;  // its line number
};

// The header, up to and including its end_header line (which ends with '\n': the data
// begins at the byte after it, whatever that byte is). Errors name `path` and the line.
Header header(const std::string& path, const std::string& data);

constexpr size_t kNone = std::numeric_limits<size_t>::max();

// What is read of the file: the first "vertex" element's x, y, z, nx, ny, nz (property
// indices, the last of each name, -1 if absent) and the first "face" element's list of
// vertex indices. Every other element and property is passed over.
struct Plan {
  size_t vertex = kNone, face = kNone;
  std::array<int, 6> role{-1, -1, -1, -1, -1, -1};
  int indices = -1;
  bool normals = false;  // the vertex element has nx, ny or nz
};
Plan plan_of(const std::string& path, const Header& h);

}  // namespace rt::ply
