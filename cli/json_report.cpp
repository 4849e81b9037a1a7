#include "json_report.h"

#include <cmath>
#include <iostream>

namespace sdflow::cli {
namespace {

void drop_non_finite(toml::node& node);

//! Whether `node` is an infinite or NaN floating-point value, which JSON cannot hold.
bool non_finite(const toml::node& node)
{
  const auto* number = node.as_floating_point();
  return number && !std::isfinite(number->get());
}

//! Remove the non-finite numbers from the tables and arrays under `node`.
void drop_non_finite(toml::node& node)
{
  if (auto* table = node.as_table()) {
    for (auto it = table->begin(); it != table->end();) {
      if (non_finite(it->second)) {
        it = table->erase(it);
      } else {
        drop_non_finite(it->second);
        ++it;
      }
    }
  } else if (auto* array = node.as_array()) {
    for (auto it = array->begin(); it != array->end();) {
      if (non_finite(*it)) {
        it = array->erase(it);
      } else {
        drop_non_finite(*it);
        ++it;
      }
    }
  }
}

} // namespace

toml::array findings_json(const std::vector<Finding>& findings)
{
  toml::array out;
  for (const Finding& f : findings)
    out.push_back(toml::table{{"severity", severity_name(f.severity)}, {"code", f.code}, {"message", f.message}});
  return out;
}

void print_json(toml::table root)
{
  drop_non_finite(root);
  std::cout << toml::json_formatter{root} << '\n' << std::flush;
}

} // namespace sdflow::cli
