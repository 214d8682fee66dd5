// The Markdown templates fmpp-report fills: every sentence of a generated page lives in a
// template file of sw/report/templates/, the C++ computes the values and tables that go
// into it. CMake embeds the files into the binary at build time (embed.cmake), so the
// tool needs no source tree at run time.
//
// The substitution is tiny and strict: `{{name}}` (name: a-z, 0-9, _) is replaced by the
// value of that name, verbatim; nothing else is special. Filling throws
// std::runtime_error naming the template and the placeholder when a placeholder has no
// value, when a value is used by no placeholder, or when a `{{` does not open a
// well-formed placeholder.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace fmpp::report {

using TemplateValues = std::map<std::string, std::string>;

// `text` with every placeholder replaced; `name` is the template's name in messages.
std::string fill_text(std::string_view name, std::string_view text, const TemplateValues& values);

// The embedded template sw/report/templates/<file> (throws naming an unknown file).
std::string_view report_template(std::string_view file);

// The names of every embedded template, sorted.
std::vector<std::string> report_template_names();

// The embedded template <file>, filled.
std::string fill_template(std::string_view file, const TemplateValues& values);

// The same without the file's final newline, for text that sits inside a line or a
// paragraph of another template (throws if the file does not end in one).
std::string fill_inline(std::string_view file, const TemplateValues& values);

}  // namespace fmpp::report
