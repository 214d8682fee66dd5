// Parts of the mesh reader (mesh.cpp): what assimp may open, the material factors of glTF
// files as the file wrote them, the materials of a file the library reads, and a Mesh as
// bytes, the form in which it comes back from the reader process (isolate.h).
#pragma once

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include <string>
#include <vector>

#include "sw/isect/geometry/io.h"
#include "sw/scene/material.h"
#include "sw/scene/mesh.h"

namespace rt::mesh_library {

namespace fs = std::filesystem;

// A path's extension in lower case (".obj"), and a path made absolute and normal.
std::string lower_extension(const std::string& path);
fs::path normal_path(const std::string& p);

// A file held in memory, as assimp reads it.
class MemoryStream : public Assimp::IOStream {
 public:
  explicit MemoryStream(std::string data) : data_(std::move(data)) {}
  size_t Read(void* buf, size_t size, size_t count) override {
    if (size == 0 || pos_ >= data_.size()) return 0;
    const size_t n = std::min(count, (data_.size() - pos_) / size);
    std::memcpy(buf, data_.data() + pos_, n * size);
    pos_ += n * size;
    return n;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? pos_ : data_.size();
    if (offset > data_.size() - std::min(base, data_.size()) && origin != aiOrigin_END) return aiReturn_FAILURE;
    const size_t to = origin == aiOrigin_END ? (offset > data_.size() ? data_.size() + 1 : data_.size() - offset)
                                             : base + offset;
    if (to > data_.size()) return aiReturn_FAILURE;
    pos_ = to;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return pos_; }
  size_t FileSize() const override { return data_.size(); }
  void Flush() override {}

 private:
  std::string data_;
  size_t pos_ = 0;
};

// The only files assimp may open: the mesh itself (from memory, already read within the
// limits), and for .gltf its buffers in the same directory (regular files, size-limited).
// Anything else - an OBJ's mtllib, a path out of the directory - does not exist for it.
class ConfinedIo : public Assimp::IOSystem {
 public:
  ConfinedIo(const std::string& path, std::string data)
      : self_(normal_path(path)), dir_(self_.parent_path()), data_(std::move(data)),
        siblings_(lower_extension(path) == ".gltf") {}

  bool Exists(const char* file) const override { return allowed(file); }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!file || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a') || !allowed(file)) return nullptr;
    if (normal_path(file) == self_) return new MemoryStream(data_);
    std::string text;
    const std::string err = fmpp::isect::read_input(file, "mesh buffer", fmpp::isect::kMaxMeshBytes, &text);
    if (!err.empty()) {
      opened_error_ = err;
      return nullptr;
    }
    return new MemoryStream(std::move(text));
  }
  void Close(Assimp::IOStream* s) override { delete s; }
  const std::string& opened_error() const { return opened_error_; }

 private:
  bool allowed(const char* file) const {
    if (!file) return false;
    const fs::path p = normal_path(file);
    if (p == self_) return true;
    return siblings_ && p.parent_path() == dir_ && lower_extension(p.string()) != ".gltf";
  }
  fs::path self_, dir_;
  std::string data_;
  bool siblings_;
  std::string opened_error_;
};

// A value the library read in single precision, as the decimal number the file most
// likely wrote (0.8f -> 0.8, not 0.800000011920929), as the scene file's numbers are read.
double file_decimal(float f);

// KHR_materials_transmission's transmissionFactor and KHR_materials_ior's ior, per
// material index (NaN where absent), which the mesh library does not read.
struct GltfExtras {
  double transmission = std::nan(""), ior = std::nan("");
};
std::vector<GltfExtras> gltf_extras(const std::string& data, const std::string& ext);
// A glTF material as the renderer's material, its factors checked and named by `path`.
FileMaterial gltf_material(const aiMaterial& a, const std::string& name, const std::string& path, const GltfExtras& x);

// The file's materials (OBJ: its MTL libraries, each beside the mesh; glTF: its own), as
// Mesh::materials appended to m, and for each of the library's materials its index there
// (-1: the library's default, given to faces without a material); binary STL has none.
// `text` is the file's text (OBJ) or bytes (glTF). mesh_materials.cpp.
std::vector<int> file_materials(const std::string& path, const std::string& ext, const aiScene& sc,
                                const std::string& text, Mesh& m);

std::string serialize(const Mesh& m);
Mesh deserialize(const std::string& s);

}  // namespace rt::mesh_library
