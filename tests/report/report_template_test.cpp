// The reports' Markdown templates (sw/report/md_template.h): the strict {{name}}
// substitution, its errors naming the template and the placeholder, and the templates
// embedded from sw/report/templates/.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>

#include "sw/report/md_template.h"

namespace fmpp::report {
namespace {

// The message of the std::runtime_error that f throws ("" when it throws none).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ReportTemplate, FillsEveryPlaceholderVerbatim) {
  EXPECT_EQ(fill_text("t.md.in", "a {{x}} b {{y_2}} {{x}}\n", {{"x", "1"}, {"y_2", "{{z}} | $&\\"}}),
            "a 1 b {{z}} | $&\\ 1\n");
  EXPECT_EQ(fill_text("t.md.in", "no placeholder: {a,b} } {", {}), "no placeholder: {a,b} } {");
  EXPECT_EQ(fill_text("t.md.in", "{{empty}}|", {{"empty", ""}}), "|");
}

TEST(ReportTemplate, UnfilledPlaceholderNamesTemplateAndPlaceholder) {
  const std::string e = error_of([] { fill_text("page.md.in", "x {{date}} {{size}}", {{"date", "d"}}); });
  EXPECT_NE(e.find("page.md.in"), std::string::npos) << e;
  EXPECT_NE(e.find("{{size}}"), std::string::npos) << e;
  EXPECT_NE(e.find("no value"), std::string::npos) << e;
}

TEST(ReportTemplate, UnusedValueNamesTemplateAndValue) {
  const std::string e = error_of([] { fill_text("page.md.in", "x {{date}}", {{"date", "d"}, {"seconds", "3"}}); });
  EXPECT_NE(e.find("page.md.in"), std::string::npos) << e;
  EXPECT_NE(e.find("'seconds'"), std::string::npos) << e;
  EXPECT_NE(e.find("no {{seconds}}"), std::string::npos) << e;
}

TEST(ReportTemplate, MalformedPlaceholderNamesTemplateAndLine) {
  for (const char* text : {"a\nb {{ x}}", "a\nb {{X}}", "a\nb {{x}", "a\nb {{x-y}}", "a\nb {{}}", "a\nb {{"}) {
    const std::string e = error_of([&] { fill_text("page.md.in", text, {{"x", "1"}}); });
    EXPECT_NE(e.find("template page.md.in: line 2:"), std::string::npos) << text << ": " << e;
  }
}

// The same errors through an embedded template, as a report meets them.
TEST(ReportTemplate, EmbeddedTemplateErrorsNameTheFile) {
  std::string e = error_of([] { fill_template("paper_no_broadcast.md.in", {{"n", "8"}}); });
  EXPECT_NE(e.find("template paper_no_broadcast.md.in: placeholder {{mantissa_bits}} has no value"),
            std::string::npos)
      << e;
  e = error_of([] { fill_template("precision_reading_quick.md.in", {{"date", "2026-01-01"}}); });
  EXPECT_NE(e.find("template precision_reading_quick.md.in: value 'date'"), std::string::npos) << e;
  EXPECT_EQ(error_of([] { fill_template("paper_no_broadcast.md.in", {{"n", "8"}, {"mantissa_bits", "7"}}); }), "");
}

TEST(ReportTemplate, InlineDropsTheFinalNewline) {
  const std::string quick = fill_inline("precision_reading_quick.md.in", {});
  EXPECT_FALSE(quick.empty());
  EXPECT_NE(quick.back(), '\n');
  EXPECT_EQ(fill_template("precision_reading_quick.md.in", {}), quick + "\n");
}

TEST(ReportTemplate, UnknownTemplateIsAnError) {
  const std::string e = error_of([] { report_template("nonesuch.md.in"); });
  EXPECT_NE(e.find("nonesuch.md.in"), std::string::npos) << e;
}

// Every file of sw/report/templates/ is built in, and each one's placeholders are well
// formed: filling it with a value for each name it holds succeeds and leaves no "{{".
TEST(ReportTemplate, EveryTemplateIsEmbeddedAndWellFormed) {
  const std::set<std::string> want = {"area.md.in",
                                      "area_baseline.md.in",
                                      "area_fpga.md.in",
                                      "area_odd_words.md.in",
                                      "paper-reproduction.md.in",
                                      "paper_fpga_clock.md.in",
                                      "paper_no_broadcast.md.in",
                                      "precision.md.in",
                                      "precision_inconsistent.md.in",
                                      "precision_reading.md.in",
                                      "precision_reading_quick.md.in"};
  const std::vector<std::string> names = report_template_names();
  for (const std::string& w : want) EXPECT_TRUE(std::count(names.begin(), names.end(), w)) << w;
  for (const std::string& name : names) {
    const std::string_view text = report_template(name);
    ASSERT_FALSE(text.empty()) << name;
    EXPECT_EQ(text.back(), '\n') << name;
    TemplateValues values;
    for (size_t p = 0; (p = text.find("{{", p)) != std::string_view::npos; p += 2) {
      const size_t end = text.find("}}", p);
      ASSERT_NE(end, std::string_view::npos) << name;
      values[std::string(text.substr(p + 2, end - p - 2))] = "v";
    }
    std::string filled;
    ASSERT_NO_THROW(filled = fill_text(name, text, values)) << name;
    EXPECT_EQ(filled.find("{{"), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace fmpp::report
