// The one table of forms (forms/forms.h), and what needs it: a form's name, the form
// for a group of rays, the words per block, the option checks against a device. The
// only file outside the forms' folders that names them (tests/repo/deps_test.py checks it).
#include <stdexcept>
#include <string>

#include "sw/isect/forms/forms.h"
#include "sw/isect/pass/options.h"

namespace fmpp::isect {

const std::vector<FormInfo>& all_forms() {
  // The options each form is chosen by (--form NAME sets them; --mapping, --watertight and
  // --origins are their aliases).
  const auto paper = [](KernelOptions& o) {
    o.mapping = Mapping::kRay;
    o.watertight = false;
  };
  const auto watertight = [](KernelOptions& o) {
    o.mapping = Mapping::kRay;
    o.watertight = true;
  };
  const auto general = [](KernelOptions& o) {
    o.mapping = Mapping::kRay;
    o.watertight = false;
    o.origins = Origins::kGeneral;
  };
  const auto paper_object = [](KernelOptions& o) {
    o.mapping = Mapping::kObject;
    o.watertight = false;
  };
  static const std::vector<FormInfo> forms = {
      {kFormPaper, "paper", Mapping::kRay, true, shared_origin_words, make_paper_form, nullptr, paper},
      {kFormWatertight, "watertight", Mapping::kRay, true, shared_origin_words, make_watertight_form, nullptr,
       watertight},
      {kFormGeneral, "arbitrary-origin", Mapping::kRay, false, general_words, make_general_form, nullptr, general},
      {kFormPaperObject, "paper-object", Mapping::kObject, true, paper_object_words, nullptr, run_object_parallel,
       paper_object},
  };
  return forms;
}

const char* form_name(int id) {
  const auto& forms = all_forms();
  for (size_t i = 0; i < forms.size(); ++i) {
    if (forms[i].id != static_cast<int>(i)) throw std::logic_error("fmpp::isect: the form table is not in FormId order");
  }
  return id >= 0 && static_cast<size_t>(id) < forms.size() ? forms[static_cast<size_t>(id)].name : "?";
}

const FormInfo& form_for(const KernelOptions& opt, bool shared) {
  const FormInfo* of_mapping = nullptr;  // the first form of the options' mapping
  for (const FormInfo& f : all_forms()) {
    if (f.shared_origin != shared) continue;
    if (!shared) return f;  // one form takes rays with their own origins, whatever the options
    KernelOptions chosen = opt;
    f.choose(chosen);
    if (same_form_options(chosen, opt)) return f;
    if (!of_mapping && f.mapping == opt.mapping) of_mapping = &f;
  }
  // Options no form is chosen by (watertight in the object-parallel mapping): the
  // mapping's form, so that validate() names what is wrong with them.
  if (of_mapping) return *of_mapping;
  throw std::invalid_argument(std::string("no form takes rays sharing an origin in the ") + to_string(opt.mapping) +
                              "-parallel mapping" + (opt.watertight ? ", watertight" : ""));
}

const FormInfo& form_named(const std::string& name) {
  std::string names;
  for (const FormInfo& f : all_forms()) {
    if (name == f.name) return f;
    names += std::string(names.empty() ? "" : ", ") + f.name;
  }
  throw std::invalid_argument("no form named '" + name + "' (the forms: " + names + ")");
}

unsigned words_needed(const KernelOptions& opt) { return form_for(opt, true).words(opt); }
unsigned own_origin_words(const KernelOptions& opt) { return form_for(opt, false).words(opt); }

void KernelOptions::validate(const Config& cfg) const {
  if (n < 2 || n > 32) throw std::invalid_argument("multiplier bits n = " + std::to_string(n) + " outside [2, 32]");
  if (vbits < 2 || vbits > 28) throw std::invalid_argument("vbits = " + std::to_string(vbits) + " outside [2, 28]");
  if (mbits < 2 || mbits > 28) throw std::invalid_argument("mbits = " + std::to_string(mbits) + " outside [2, 28]");
  if (cull_packet < 1) throw std::invalid_argument("cull_packet = 0: a culling packet needs at least one ray");
  if (!(t_accuracy >= 0 && t_accuracy < 1)) {
    throw std::invalid_argument("t accuracy " + std::to_string(t_accuracy) + " outside [0, 1)");
  }
  // Options a mapping would ignore are errors, not silently dropped: the object-parallel
  // mapping has the paper's form only, and takes rays grouped by origin.
  if (mapping == Mapping::kObject && watertight) {
    throw std::invalid_argument("the watertight form exists in the ray-parallel mapping only (--mapping ray)");
  }
  if (watertight && mapping == Mapping::kRay && origins == Origins::kGeneral) {
    throw std::invalid_argument("the watertight form takes rays sharing an origin; origins general sends every ray "
                                "to the arbitrary-origin form, so it would never run");
  }
  if (mapping == Mapping::kObject && origins == Origins::kGeneral) {
    throw std::invalid_argument("origins general (the arbitrary-origin form) exists in the ray-parallel mapping only; "
                                "the object-parallel mapping groups rays by origin");
  }
  if (cond_bits > 60) throw std::invalid_argument("cond_bits = " + std::to_string(cond_bits) + " above 60");
  if (cfg.words < words_needed(*this)) {
    throw std::invalid_argument(std::string(to_string(mapping)) + "-parallel " + to_string(mul) + " needs " +
                                std::to_string(words_needed(*this)) + " words per block; the FMPP has " +
                                std::to_string(cfg.words));
  }
}

}  // namespace fmpp::isect
