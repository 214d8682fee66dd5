// The mesh library's messages (mesh_library_log.h).
#include "sw/rt/mesh_library_log.h"

#include <cctype>

#include "sw/rt/scene.h"

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

}  // namespace

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


void check_library_log(const std::string& path, const std::vector<std::string>& lines) {
  for (const std::string& l : lines) {
    std::string low = l;
    for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* word : {"dropped", "out-of-range", "out of range", "skipping", "invalid"}) {
      if (low.find(word) != std::string::npos) {
        throw SceneError(path + ": cannot read mesh: faces lost by the mesh library (" + without_quotes(l.c_str()) +
                         "); fix the file");
      }
    }
  }
}


}  // namespace rt
