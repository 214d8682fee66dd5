// The strict {{name}} substitution of md_template.h.
#include "sw/report/md_template.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace fmpp::report {

// Defined in the file CMake generates from sw/report/templates/ (embed.cmake): the
// templates by file name, and {nullptr, 0} past the last.
struct EmbeddedTemplate {
  const char* name;
  const char* text;
  std::size_t size;
};
extern const EmbeddedTemplate kEmbeddedTemplates[];

namespace {

bool name_char(char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; }

[[noreturn]] void fail(std::string_view name, const std::string& what) {
  throw std::runtime_error("template " + std::string(name) + ": " + what);
}

}  // namespace

std::string fill_text(std::string_view name, std::string_view text, const TemplateValues& values) {
  std::string out;
  std::set<std::string> used;
  size_t pos = 0;
  for (size_t open; (open = text.find("{{", pos)) != std::string_view::npos;) {
    out.append(text, pos, open - pos);
    size_t end = open + 2;
    while (end < text.size() && name_char(text[end])) ++end;
    const std::string key(text.substr(open + 2, end - open - 2));
    if (key.empty() || text.compare(end, 2, "}}") != 0) {
      const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + open, '\n'));
      fail(name, "line " + std::to_string(line) + ": '{{' does not open a placeholder {{name}} (name: a-z, 0-9, _)");
    }
    const auto it = values.find(key);
    if (it == values.end()) fail(name, "placeholder {{" + key + "}} has no value");
    out += it->second;
    used.insert(key);
    pos = end + 2;
  }
  out.append(text, pos);
  for (const auto& [key, value] : values) {
    if (!used.count(key)) fail(name, "value '" + key + "' is given but the template has no {{" + key + "}}");
  }
  return out;
}

std::string_view report_template(std::string_view file) {
  for (const EmbeddedTemplate* t = kEmbeddedTemplates; t->name; ++t) {
    if (file == t->name) return {t->text, t->size};
  }
  fail(file, "not among the templates built in (sw/report/templates/)");
}

std::vector<std::string> report_template_names() {
  std::vector<std::string> names;
  for (const EmbeddedTemplate* t = kEmbeddedTemplates; t->name; ++t) names.emplace_back(t->name);
  std::sort(names.begin(), names.end());
  return names;
}

std::string fill_template(std::string_view file, const TemplateValues& values) {
  return fill_text(file, report_template(file), values);
}

std::string fill_inline(std::string_view file, const TemplateValues& values) {
  std::string s = fill_template(file, values);
  if (s.empty() || s.back() != '\n') fail(file, "does not end in a newline");
  s.pop_back();
  return s;
}

}  // namespace fmpp::report
