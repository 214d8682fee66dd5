// The mesh library's messages (mesh.cpp): its log captured while it reads one file, a
// face it dropped turned into an error, and its messages made safe to repeat.
#pragma once

#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

#include <functional>
#include <string>
#include <vector>

struct aiScene;

namespace rt {

// The library's warnings and errors while it reads one file, their text as it gives it
// ("Warn,  T0: " and the line's end taken off). Assimp's logger is global: one capture at
// a time (the reader runs in a child process of its own, load_mesh).
class LibraryLog {
 public:
  LibraryLog() {
    Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
    Assimp::DefaultLogger::get()->attachStream(new Stream(&lines_), Assimp::Logger::Warn | Assimp::Logger::Err);
  }
  ~LibraryLog() { Assimp::DefaultLogger::kill(); }  // deletes the stream
  LibraryLog(const LibraryLog&) = delete;
  LibraryLog& operator=(const LibraryLog&) = delete;
  const std::vector<std::string>& lines() const { return lines_; }

 private:
  struct Stream : Assimp::LogStream {
    explicit Stream(std::vector<std::string>* to) : to_(to) {}
    void write(const char* message) override {
      std::string s = message ? message : "";
      if (const size_t colon = s.find(": "); colon != std::string::npos && colon < 16) s.erase(0, colon + 2);
      while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
      to_->push_back(s);
    }
    std::vector<std::string>* to_;
  };
  std::vector<std::string> lines_;
};

// The library's error message with any quoted token but a short name replaced by "...":
// a longer token may be text of the file, which need not be a mesh at all (a password file
// named as one), and is not repeated. Control characters go too, and the length is bounded.
std::string without_quotes(const char* msg);

// A face the library could not read is an error naming the file, the element that lost
// faces when `where` can tell (empty when not) and the library's own words (its glTF
// reader drops a face with an out-of-range index and only logs it, naming no element).
void check_library_log(const std::string& path, const std::vector<std::string>& lines,
                       const std::function<std::string()>& where);

// The glTF primitives whose faces the library read fewer of than the file declares, as
// "meshes[0] (\"name\") primitive 1: 1 of 2 faces read; ...": `text` is the file's bytes
// (.gltf JSON or .glb), `scene` what the library made of it (one mesh per primitive, in
// the file's order). Empty when the file's JSON cannot say (then the message names the
// file alone).
std::string gltf_short_primitives(const std::string& text, const aiScene& scene);

}  // namespace rt
