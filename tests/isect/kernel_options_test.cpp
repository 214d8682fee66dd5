// The kernel options' list (FMPP_KERNEL_OPTIONS, sw/isect/pass/options.h) against every
// use derived from it: each option, moved off its default, changes exactly the uses its
// roles name (forms' identity, the plan's cache key, the ranks' agreement, the reports)
// and is read back from its flag in fmpp-intersect, and in fmpp-render where it has a
// render role. An option a use leaves out fails here, by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <type_traits>
#include <vector>

#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/options.h"
#include "sw/isect/stats_json.h"
#include "sw/plan/plan_cache.h"
#include "sw/tools/kernel_flags.h"

namespace {

using namespace fmpp::isect;
using fmpp::tools::FlagTool;
using fmpp::tools::KernelFlags;

// KernelOptions holds the list and the three hooks, nothing else: a field declared beside
// the hooks instead of in the list changes the size.
struct ListAndHooks {
#define FIELD(type, field, init, ...) type field = init;
  FMPP_KERNEL_OPTIONS(FIELD)
#undef FIELD
  std::function<void(uint64_t, uint64_t)> progress;
  PassShare* share = nullptr;
  FormCache* forms = nullptr;
};
static_assert(sizeof(ListAndHooks) == sizeof(KernelOptions),
              "a field of KernelOptions outside FMPP_KERNEL_OPTIONS: declare it in the list");

// The options with `member` moved off its default, and the command-line words that do so.
template <class T, class Kind>
KernelOptions moved(const OptionInfo& o, T KernelOptions::*member, Kind, std::vector<std::string>* words) {
  KernelOptions b;
  words->push_back(o.flag);
  if constexpr (std::is_same_v<Kind, OptSet> || std::is_same_v<Kind, OptClear>) {
    b.*member = !(b.*member);
  } else if constexpr (std::is_same_v<Kind, OptValue>) {
    const T hi = static_cast<T>(o.hi), lo = static_cast<T>(o.lo);
    b.*member = b.*member != hi ? hi : lo;
    if constexpr (std::is_floating_point_v<T>) {
      words->push_back(std::to_string(b.*member));
    } else {
      words->push_back(std::to_string(static_cast<long long>(b.*member)));
    }
  } else {
    for (const auto& [name, value] : Kind::Names::kAll) {
      if (value != b.*member) {
        b.*member = value;
        words->push_back(name);
        break;
      }
    }
  }
  return b;
}

// Every option's value, by field name.
nlohmann::json all(const KernelOptions& opt) {
  nlohmann::json j;
  for_each_kernel_option([&](const OptionInfo& o, auto member, auto) {
    if constexpr (std::is_enum_v<std::remove_reference_t<decltype(opt.*member)>>) {
      j[o.field] = static_cast<int>(opt.*member);
    } else {
      j[o.field] = opt.*member;
    }
  });
  return j;
}

KernelOptions parsed(FlagTool tool, std::vector<std::string> words) {
  CLI::App app;
  KernelFlags flags;
  flags.add(app, tool);
  std::reverse(words.begin(), words.end());  // CLI11 takes the words last first
  app.parse(words);
  return flags.options();
}

TEST(KernelOptions, EveryOptionInEveryUseItsRolesName) {
  int rows = 0;
  for_each_kernel_option([&](const OptionInfo& o, auto member, auto kind) {
    ++rows;
    SCOPED_TRACE(o.field);
    const KernelOptions a;
    std::vector<std::string> words;
    const KernelOptions b = moved(o, member, kind, &words);
    ASSERT_NE(a.*member, b.*member);
    EXPECT_EQ(!same_form_options(a, b), o.has(kFormIdentity)) << "same_form_options (form_cache.cpp)";
    rt::PlanRequest ra, rb;
    ra.base = a;
    rb.base = b;
    EXPECT_EQ(rt::request_json(ra) != rt::request_json(rb), o.has(kPlanKey)) << "the plan's cache key";
    EXPECT_EQ(options_json(a, kAgreed) != options_json(b, kAgreed), o.has(kAgreed)) << "RenderChips::agree";
    EXPECT_EQ(options_json(a, kReported) != options_json(b, kReported), o.has(kReported)) << "the reports";
    if (o.has(kReported)) {
      EXPECT_TRUE(options_json(a, kReported).contains(o.report));
    }
    const unsigned data_roles = kFormIdentity | kPlanKey | kAgreed | kReported;
    if ((o.roles & data_roles) != data_roles) {
      EXPECT_STRNE(o.why, "") << "a role left out needs its reason";
    }
    // The flags: fmpp-intersect has every one; fmpp-render those with a render role.
    EXPECT_EQ(all(parsed(FlagTool::kIntersect, words)), all(b));
    if (o.has(kRenderFlag | kRenderPlanned)) {
      EXPECT_EQ(all(parsed(FlagTool::kRender, words)), all(b));
    } else {
      EXPECT_THROW(parsed(FlagTool::kRender, words), CLI::ParseError);
    }
  });
  EXPECT_GT(rows, 0);
}

// The defaults of the flags are those of KernelOptions, in both tools.
TEST(KernelOptions, FlagsDefaultToTheOptions) {
  EXPECT_EQ(all(parsed(FlagTool::kIntersect, {})), all(KernelOptions{}));
  EXPECT_EQ(all(parsed(FlagTool::kRender, {})), all(KernelOptions{}));
}

// --form NAME picks the form of that name, gives the options its aliases give, and is
// refused beside them.
TEST(KernelOptions, FormByNameOrAlias) {
  for (const FormInfo& f : all_forms()) {
    SCOPED_TRACE(f.name);
    KernelOptions o;
    f.choose(o);
    EXPECT_STREQ(form_for(o, f.shared_origin).name, f.name);
    EXPECT_EQ(all(parsed(FlagTool::kIntersect, {"--form", f.name})), all(o));
  }
  const auto same = [](std::vector<std::string> form, std::vector<std::string> alias) {
    EXPECT_EQ(all(parsed(FlagTool::kIntersect, form)), all(parsed(FlagTool::kIntersect, alias)));
  };
  same({"--form", "paper"}, {"--mapping", "ray"});
  same({"--form", "watertight"}, {"--watertight"});
  same({"--form", "paper-object"}, {"--mapping", "object"});
  same({"--form", "arbitrary-origin"}, {"--origins", "general"});
  EXPECT_EQ(all(parsed(FlagTool::kRender, {"--form", "watertight"})), all(parsed(FlagTool::kRender, {"--watertight"})));
  EXPECT_THROW(parsed(FlagTool::kIntersect, {"--form", "paper", "--watertight"}), CLI::ParseError);
  EXPECT_THROW(parsed(FlagTool::kIntersect, {"--form", "paper", "--mapping", "ray"}), CLI::ParseError);
  EXPECT_THROW(parsed(FlagTool::kIntersect, {"--form", "nonesuch"}), CLI::ParseError);
  EXPECT_THROW(parsed(FlagTool::kRender, {"--form", "arbitrary-origin"}), CLI::ParseError);
  EXPECT_THROW(form_named("nonesuch"), std::invalid_argument);
}

// The reports' names and values, pinned: their readers (tools/gallery.py, the docs) know these.
TEST(KernelOptions, ReportNames) {
  EXPECT_EQ(options_json(KernelOptions{}, kReported).dump(),
            R"({"bits":24,"box_diagonals":true,"box_edges":true,"box_reads":true,"changed_reads":true,"cull":true,"cull_packet":1,"cull_probe":true,)"
            R"("fmpp_boxes":true,"gates":true,"host_gates":true,)"
            R"("mapping":"ray","max_probe_rounds":8,"merge_below":0,"multiply":"const","pass_order":"coherent","t_accuracy":0.0,)"
            R"("watertight":false})");
}

}  // namespace
