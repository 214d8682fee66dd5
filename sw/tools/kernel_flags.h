// The kernel options' command-line flags, derived from their list (FMPP_KERNEL_OPTIONS,
// sw/isect/pass/options.h): fmpp-intersect declares every option's flag, fmpp-render
// those with a render role. A new option needs nothing here. And --form NAME, a form of
// the form table (sw/isect/form_table.cpp) by its name, which sets the options that
// choose it (FormInfo::choose): --mapping, --watertight and --origins are its aliases.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "common/util/cli_checks.h"
#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/options.h"

namespace fmpp::tools {

enum class FlagTool { kIntersect, kRender };

class KernelFlags {
 public:
  // Declares the flags on `app`, in the list's order, with the defaults of KernelOptions:
  // for fmpp-intersect every option (its default shown), for fmpp-render those with
  // kRenderFlag (default shown) or kRenderPlanned (none: the plan chooses).
  void add(CLI::App& app, FlagTool tool) {
    isect::for_each_kernel_option([&](const isect::OptionInfo& o, auto member, auto kind) {
      using Kind = decltype(kind);
      const bool render = tool == FlagTool::kRender;
      if (render && !o.has(isect::kRenderFlag | isect::kRenderPlanned)) return;
      const std::string help = render && *o.render_help ? o.render_help : o.help;
      CLI::Option* flag = nullptr;
      if constexpr (std::is_same_v<Kind, isect::OptSet>) {
        app.add_flag(o.flag, opt_.*member, help);
      } else if constexpr (std::is_same_v<Kind, isect::OptClear>) {
        app.add_flag(o.flag, cleared_[o.field], help);
      } else if constexpr (std::is_same_v<Kind, isect::OptValue>) {
        using T = std::remove_reference_t<decltype(opt_.*member)>;
        flag = app.add_option(o.flag, opt_.*member, help);
        if constexpr (std::is_floating_point_v<T>) {
          flag->check(finite_range(o.lo, o.hi));
        } else {
          flag->check(int_range(static_cast<long long>(o.lo), static_cast<long long>(o.hi)));
        }
      } else {
        std::vector<std::string> names;
        for (const auto& [name, value] : Kind::Names::kAll) {
          names.push_back(name);
          if (value == opt_.*member) names_[o.field] = name;
        }
        flag = app.add_option(o.flag, names_[o.field], help)->check(CLI::IsMember(names));
      }
      if (flag && !(render && o.has(isect::kRenderPlanned))) flag->capture_default_str();
    });
    add_form(app, tool);
    app.add_flag_callback(
        "--list-kernel-options",
        [tool] {
          std::cout << table(tool).dump(1) << "\n";
          throw CLI::Success();
        },
        "print the kernel options' flags of this tool as JSON (flag, kind, range, default, names) and exit: "
        "the random tests draw every one of them from it");
  }

  // The rows of the tool's kernel-option flags: {"flag", "kind": "value" | "set" | "clear"
  // | "named", and for a value "lo", "hi", "integer", "default"; for a name "names",
  // "default"}; "planned" where fmpp-render's plan chooses the value unless given.
  static nlohmann::json table(FlagTool tool) {
    nlohmann::json rows = nlohmann::json::array();
    const isect::KernelOptions defaults;
    isect::for_each_kernel_option([&](const isect::OptionInfo& o, auto member, auto kind) {
      using Kind = decltype(kind);
      if (tool == FlagTool::kRender && !o.has(isect::kRenderFlag | isect::kRenderPlanned)) return;
      nlohmann::json r = {{"flag", o.flag}, {"planned", tool == FlagTool::kRender && o.has(isect::kRenderPlanned)}};
      if constexpr (std::is_same_v<Kind, isect::OptSet>) {
        r["kind"] = "set";
      } else if constexpr (std::is_same_v<Kind, isect::OptClear>) {
        r["kind"] = "clear";
      } else if constexpr (std::is_same_v<Kind, isect::OptValue>) {
        using T = std::remove_reference_t<decltype(defaults.*member)>;
        r.update({{"kind", "value"}, {"lo", o.lo}, {"hi", o.hi}, {"integer", !std::is_floating_point_v<T>},
                  {"default", defaults.*member}});
      } else {
        r["kind"] = "named";
        r["names"] = nlohmann::json::array();
        for (const auto& [name, value] : Kind::Names::kAll) {
          r["names"].push_back(name);
          if (value == defaults.*member) r["default"] = name;
        }
      }
      rows.push_back(r);
    });
    return rows;
  }

  // Whether --form was given.
  bool form_given() const { return !form_.empty(); }

  // The options the command line gave (once parsed); the others at their defaults.
  isect::KernelOptions options() const {
    isect::KernelOptions out = opt_;
    isect::for_each_kernel_option([&](const isect::OptionInfo& o, auto member, auto kind) {
      using Kind = decltype(kind);
      if constexpr (std::is_same_v<Kind, isect::OptClear>) {
        if (const auto it = cleared_.find(o.field); it != cleared_.end() && it->second) out.*member = false;
      } else if constexpr (!std::is_same_v<Kind, isect::OptSet> && !std::is_same_v<Kind, isect::OptValue>) {
        const auto it = names_.find(o.field);
        if (it == names_.end()) return;
        for (const auto& [name, value] : Kind::Names::kAll) {
          if (it->second == name) out.*member = value;
        }
      }
    });
    if (!form_.empty()) isect::form_named(form_).choose(out);  // its aliases are excluded
    return out;
  }

 private:
  // --form NAME: fmpp-intersect takes every form, fmpp-render those for rays sharing an
  // origin (its other rays always take the arbitrary-origin form). It excludes its aliases.
  void add_form(CLI::App& app, FlagTool tool) {
    std::vector<std::string> names;
    std::string list;
    for (const isect::FormInfo& f : isect::all_forms()) {
      if (tool == FlagTool::kRender && !f.shared_origin) continue;
      names.push_back(f.name);
      list += std::string(list.empty() ? "" : " | ") + f.name;
    }
    std::vector<CLI::Option*> aliases;
    std::string alias_names;
    for (const char* alias : {"--mapping", "--watertight", "--origins"}) {
      if (CLI::Option* a = app.get_option_no_throw(alias)) {
        aliases.push_back(a);
        alias_names += std::string(alias_names.empty() ? "" : ", ") + alias;
      }
    }
    CLI::Option* form = app.add_option("--form", form_,
                                       list + ": the form, by its name in the form table, and with it the mapping (" +
                                           alias_names + " name the same choices)")
                            ->check(CLI::IsMember(names));
    for (CLI::Option* a : aliases) form->excludes(a);
  }

  std::string form_;
  isect::KernelOptions opt_;
  std::map<std::string, std::string> names_;  // by field: the name a choice was given
  std::map<std::string, bool> cleared_;       // by field: whether its --no-... flag was given
};

}  // namespace fmpp::tools
