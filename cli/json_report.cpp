#include "json_report.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <utility>

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

toml::table event_json(const StepEvent& event)
{
  toml::table e{{"kind", std::string(event_name(event.kind))}, {"step", static_cast<int64_t>(event.step)},
                {"time", event.time}};
  if (event.kind == StepEventKind::rejected)
    e.insert("rejections", event.rejections);
  if (event.kind == StepEventKind::refused)
    e.insert("refusal", std::string(refusal_name(event.refusal)));
  if (const auto& m = event.retriangulation) {
    e.insert("crossing_pairs", static_cast<int64_t>(m->crossing_pairs));
    e.insert("crossing_size", m->crossing_size); // NaN (left out) unless the topology changed at a crossing
    for (const auto& [name, t] : {std::pair{"before", m->before}, std::pair{"after", m->after}}) {
      e.insert(fmt::format("components_{}", name), t.components);
      e.insert(fmt::format("genus_{}", name), t.genus);
      e.insert(fmt::format("boundary_loops_{}", name), t.boundary_loops);
    }
    e.insert("faces_before", static_cast<int64_t>(m->faces_before));
    e.insert("faces_after", static_cast<int64_t>(m->faces_after));
    e.insert("faces_rebuilt", static_cast<int64_t>(m->faces_rebuilt));
    e.insert("volume_restored", m->volume_restored);
    e.insert("debris_volume", m->debris_volume);
  }
  if (!event.detail.empty())
    e.insert("detail", event.detail);
  return e;
}

void print_json(toml::table root)
{
  drop_non_finite(root);
  std::cout << toml::json_formatter{root} << '\n' << std::flush;
}

} // namespace sdflow::cli
