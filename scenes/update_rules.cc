#include "update_rules.h"

#include "input_error.h"

namespace fibrecheck {

const std::vector<UpdateRuleName>& update_rules() {
  static const std::vector<UpdateRuleName> rules = {
      {UpdateRule::seed, "seed",
       "P' = max(0, P + c*d) with the scene's c (c/n per slice, Eq. 4.28)"},
      {UpdateRule::automatic, "auto", "the seed's update with c = 1/lambda_max(W)"},
      {UpdateRule::accelerated, "accelerated",
       "the same projected step with Nesterov momentum and adaptive restart"},
      {UpdateRule::conjugate_gradient, "cg",
       "projected conjugate gradients per candidate list (frictionless only)"},
  };
  return rules;
}

std::vector<std::string> update_rule_names() {
  std::vector<std::string> names;
  for (const UpdateRuleName& r : update_rules()) names.emplace_back(r.name);
  return names;
}

const char* to_string(UpdateRule rule) {
  for (const UpdateRuleName& r : update_rules())
    if (r.rule == rule) return r.name;
  return "?";
}

UpdateRule parse_update_rule(const std::string& text, const std::string& file,
                             const std::string& field) {
  std::string known;
  for (const UpdateRuleName& r : update_rules()) {
    if (text == r.name) return r.rule;
    known += (known.empty() ? "\"" : ", \"") + std::string(r.name) + "\"";
  }
  throw InputError(file, field, "must be one of " + known + ", got \"" + text + "\"");
}

}  // namespace fibrecheck
