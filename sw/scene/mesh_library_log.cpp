// The mesh library's messages (mesh_library_log.h).
#include "sw/scene/mesh_library_log.h"

#include <assimp/scene.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "sw/scene/scene.h"

namespace rt {
namespace {

// Whether a quoted token of the library's message is repeated as it is: a short name
// (letters, digits, _ . - [ ]), such as a glTF member or type name ("indices", "number").
bool plain_token(const std::string& t) {
  if (t.empty() || t.size() > 32) return false;
  for (char c : t) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '.' && c != '-' && c != '[' && c != ']') {
      return false;
    }
  }
  return true;
}

// The JSON of a glTF file: the text itself, or a .glb's first chunk (12-byte header,
// then the chunk's length and type "JSON"). Discarded (null) when it does not parse.
nlohmann::json gltf_json(const std::string& text) {
  std::string json_text = text;
  if (text.size() >= 20 && text.compare(0, 4, "glTF") == 0) {
    uint32_t length = 0;
    std::memcpy(&length, text.data() + 12, 4);
    if (text.compare(16, 4, "JSON") != 0 || length > text.size() - 20) return nullptr;
    json_text = text.substr(20, length);
  }
  return nlohmann::json::parse(json_text, nullptr, false);
}

// The faces a primitive declares: its index count (or vertex count) read by its mode.
int64_t declared_faces(const nlohmann::json& gltf, const nlohmann::json& prim) {
  if (!prim.is_object() || !gltf.contains("accessors") || !gltf["accessors"].is_array()) return -1;
  const nlohmann::json& accessors = gltf["accessors"];
  const nlohmann::json* acc = nullptr;
  auto at = [&](const nlohmann::json& i) -> const nlohmann::json* {
    return i.is_number_unsigned() && i.get<size_t>() < accessors.size() ? &accessors[i.get<size_t>()] : nullptr;
  };
  if (prim.contains("indices")) {
    acc = at(prim["indices"]);
  } else if (prim.contains("attributes") && prim["attributes"].is_object() && prim["attributes"].contains("POSITION")) {
    acc = at(prim["attributes"]["POSITION"]);
  }
  if (!acc || !acc->contains("count") || !(*acc)["count"].is_number_unsigned()) return -1;
  const auto n = static_cast<int64_t>((*acc)["count"].get<uint64_t>());
  const bool has_mode = prim.contains("mode") && prim["mode"].is_number_integer();
  switch (has_mode ? prim["mode"].get<int>() : 4) {
    case 0: case 2: return n;                   // points, line loop
    case 1: return n / 2;                       // lines
    case 3: return n > 0 ? n - 1 : 0;           // line strip
    case 4: return n / 3;                       // triangles
    case 5: case 6: return n > 2 ? n - 2 : 0;   // strip, fan
    default: return -1;
  }
}

}  // namespace

std::string gltf_short_primitives(const std::string& text, const aiScene& scene) {
  const nlohmann::json gltf = gltf_json(text);
  if (!gltf.is_object() || !gltf.contains("meshes") || !gltf["meshes"].is_array()) return "";
  std::string out;
  unsigned k = 0;  // the library's mesh of the primitive
  for (size_t m = 0; m < gltf["meshes"].size(); ++m) {
    const nlohmann::json& mesh = gltf["meshes"][m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) return "";
    const std::string name = mesh.contains("name") && mesh["name"].is_string() ? mesh["name"].get<std::string>() : "";
    for (size_t p = 0; p < mesh["primitives"].size(); ++p, ++k) {
      if (k >= scene.mNumMeshes) return "";
      const int64_t declared = declared_faces(gltf, mesh["primitives"][p]);
      const int64_t read = scene.mMeshes[k]->mNumFaces;
      if (declared < 0 || read >= declared) continue;
      out += (out.empty() ? "" : "; ") + std::string("meshes[") + std::to_string(m) + "]" +
             (name.empty() ? "" : " (\"" + without_quotes(name.c_str()) + "\")") + " primitive " + std::to_string(p) +
             ": " + std::to_string(read) + " of " + std::to_string(declared) + " faces read";
    }
  }
  return out;
}

std::string without_quotes(const char* msg) {
  std::string out, token;
  char quote = 0;
  for (const char* p = msg ? msg : ""; *p && out.size() < 200; ++p) {
    const char c = *p;
    if (quote) {
      if (c == quote) {
        out += plain_token(token) ? token : "...";
        out += c;
        quote = 0;
        token.clear();
      } else if (token.size() <= 32) {
        token += c;
      }
    } else if (c == '\'' || c == '"' || c == '`') {
      out += c;
      quote = c;
    } else if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) {
      out += c;
    }
  }
  if (quote) out += "...";
  while (!out.empty() && (out.back() == ' ' || out.back() == '.')) out.pop_back();
  return out;
}


void check_library_log(const std::string& path, const std::vector<std::string>& lines,
                       const std::function<std::string()>& where) {
  for (const std::string& l : lines) {
    std::string low = l;
    for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* word : {"dropped", "out-of-range", "out of range", "skipping", "invalid"}) {
      if (low.find(word) != std::string::npos) {
        const std::string element = where ? where() : "";
        throw SceneError(path + ": cannot read mesh: faces lost by the mesh library" +
                         (element.empty() ? "" : " in " + element) + " (" + without_quotes(l.c_str()) + "); fix the file");
      }
    }
  }
}

}  // namespace rt
