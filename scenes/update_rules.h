#pragma once

#include <string>
#include <vector>

namespace fibrecheck {

/// The force update rules of the iterative solver (seed §4.3.2, DESIGN §2).
enum class UpdateRule { seed, automatic, accelerated, conjugate_gradient };

/// A rule's name in scene files and on the command line, and what it is.
struct UpdateRuleName {
  UpdateRule rule;
  const char* name;
  const char* summary;
};

/// Every rule, once: the one table that the scene reader, the scene help and the commands use.
const std::vector<UpdateRuleName>& update_rules();

/// The names of every rule, in the table's order.
std::vector<std::string> update_rule_names();

const char* to_string(UpdateRule rule);

/// The rule of that name; throws InputError naming `file` and `field` for any other text.
UpdateRule parse_update_rule(const std::string& text, const std::string& file,
                             const std::string& field);

}  // namespace fibrecheck
