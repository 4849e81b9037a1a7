#include "sdflow/run/parameters.h"

#include "sdflow/errors.h"
#include "sdflow/run/parameter_schema.h"
#include "sdflow/version.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace sdflow {
namespace {

//! The table of run.toml that records the sdflow which wrote it (version and git commit).
constexpr const char* written_by_table = "written_by";

[[noreturn]] void bad(const std::filesystem::path& file, const toml::node& node, const std::string& what)
{
  throw InvalidParameter(fmt::format("{}:{}: {}", file.string(), node.source().begin.line, what));
}

std::filesystem::path resolve(const std::filesystem::path& file, const std::string& path)
{
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : (file.parent_path() / p).lexically_normal();
}

const char* expected(ParameterType type)
{
  switch (type) {
  case ParameterType::integer: return "an integer";
  case ParameterType::real: return "a number";
  case ParameterType::boolean: return "true or false";
  case ParameterType::choice: return "a name in quotes";
  case ParameterType::path: return "a path in quotes";
  case ParameterType::point: return "[x, y, z]";
  case ParameterType::schedule: return "a file name in quotes or [[first_step, last_step, tau], ...]";
  case ParameterType::reals: return "[a, b, ...] or rows [[a, b, ...], ...]";
  case ParameterType::text: return "a text in quotes";
  }
  return "?";
}

const char* toml_type(const toml::node& node)
{
  switch (node.type()) {
  case toml::node_type::string: return "a string";
  case toml::node_type::integer: return "an integer";
  case toml::node_type::floating_point: return "a number";
  case toml::node_type::boolean: return "a boolean";
  case toml::node_type::array: return "an array";
  case toml::node_type::table: return "a table";
  default: return "a date or time";
  }
}

ScheduleSetting inline_schedule(const std::filesystem::path& file, const toml::array& rows)
{
  ScheduleSetting schedule;
  for (const auto& row : rows) {
    const toml::array* r = row.as_array();
    if (!r || r->size() != 3 || !r->get(0)->is_integer() || !r->get(1)->is_integer() || !r->get(2)->value<double>())
      bad(file, row, "a schedule entry must be [first_step, last_step, tau]");
    schedule.entries.push_back({static_cast<long>(*r->get(0)->value<int64_t>()),
                                static_cast<long>(*r->get(1)->value<int64_t>()), *r->get(2)->value<double>()});
  }
  return schedule;
}

//! The numbers of a `reals` entry: a flat array, or an array of rows of one length read row by row.
std::vector<double> inline_reals(const std::filesystem::path& file, const toml::array& array, const std::string& key)
{
  std::vector<double> numbers;
  std::size_t row_length = 0;
  for (const auto& item : array) {
    if (const auto number = item.value<double>()) {
      if (row_length > 0)
        bad(file, item, fmt::format("{} mixes numbers and rows: give [a, b, ...] or [[a, b, ...], ...]", key));
      numbers.push_back(*number);
      continue;
    }
    const toml::array* row = item.as_array();
    if (!row || row->empty() || (!numbers.empty() && row_length == 0) || (row_length > 0 && row->size() != row_length))
      bad(file, item, fmt::format("{} must be numbers [a, b, ...] or rows of numbers of one length [[a, b, ...], ...]", key));
    row_length = row->size();
    for (const auto& cell : *row) {
      const auto number = cell.value<double>();
      if (!number)
        bad(file, cell, fmt::format("{} holds {} where a number belongs", key, toml_type(cell)));
      numbers.push_back(*number);
    }
  }
  return numbers;
}

//! The value of `entry` a scenario's `node` gives; IoError or InvalidParameter naming the file, line and key.
ParameterValue toml_value(const std::filesystem::path& file, const toml::node& node, const ParameterEntry& entry)
{
  const auto wrong_type = [&]() -> ParameterValue {
    bad(file, node, fmt::format("`{}` has the wrong type: expected {}, got {}", entry.key, expected(entry.type),
                                toml_type(node)));
  };
  switch (entry.type) {
  case ParameterType::integer:
    if (node.is_integer())
      return static_cast<long>(*node.value<int64_t>());
    return wrong_type();
  case ParameterType::real:
    if (auto v = node.value<double>()) // integers are accepted for real values
      return *v;
    return wrong_type();
  case ParameterType::boolean:
    if (node.is_boolean())
      return *node.value<bool>();
    return wrong_type();
  case ParameterType::choice:
    if (node.is_string())
      return *node.value<std::string>();
    if (node.is_boolean() && entry.meshlab.boolean_choices) // as the dialog's boolean, and older keys, give it
      return *node.value<bool>() ? entry.meshlab.boolean_choices->second : entry.meshlab.boolean_choices->first;
    return wrong_type();
  case ParameterType::text:
    if (node.is_string())
      return *node.value<std::string>();
    return wrong_type();
  case ParameterType::path:
    if (node.is_string())
      return resolve(file, *node.value<std::string>());
    return wrong_type();
  case ParameterType::point: {
    const toml::array* a = node.as_array();
    if (!a || a->size() != 3 || !a->get(0)->value<double>() || !a->get(1)->value<double>() ||
        !a->get(2)->value<double>())
      bad(file, node, fmt::format("{} must be [x, y, z]", entry.key));
    return Eigen::Vector3d(*a->get(0)->value<double>(), *a->get(1)->value<double>(), *a->get(2)->value<double>());
  }
  case ParameterType::schedule:
    if (const toml::array* rows = node.as_array())
      return inline_schedule(file, *rows);
    if (node.is_string()) {
      const std::filesystem::path schedule_file = resolve(file, *node.value<std::string>());
      return ScheduleSetting{schedule_file, read_schedule(schedule_file).entries()};
    }
    return wrong_type();
  case ParameterType::reals:
    if (const toml::array* a = node.as_array())
      return inline_reals(file, *a, entry.key);
    return wrong_type();
  }
  return wrong_type();
}

//! The keys of a scenario file with their entries, tables flattened ("retriangulation.edge_length").
struct GivenKey {
  const ParameterEntry* entry;
  const toml::node* node;
};

std::vector<GivenKey> given_keys(const std::filesystem::path& file, const toml::table& table)
{
  std::set<std::string> sections;
  for (const ParameterEntry& e : parameter_schema())
    if (!e.section().empty())
      sections.insert(e.section());
  std::vector<GivenKey> given;
  std::map<const ParameterEntry*, std::string> seen;
  const auto take = [&](const std::string& key, const toml::node& node) {
    const ParameterEntry* entry = find_parameter(key);
    if (!entry) {
      const std::string suggestion = closest_parameter_key(key);
      bad(file, node, fmt::format("unknown key `{}`{}", key,
                                  suggestion.empty() ? "" : fmt::format(" (did you mean `{}`?)", suggestion)));
    }
    if (const auto previous = seen.find(entry); previous != seen.end())
      bad(file, node, fmt::format("`{}` and `{}` are the same parameter, `{}`: give it once", previous->second, key,
                                  entry->key));
    seen[entry] = key;
    given.push_back({entry, &node});
  };
  for (const auto& [key_view, node] : table) {
    const std::string key(key_view.str());
    if (key == written_by_table && node.is_table())
      continue; // what wrote a run.toml: not a parameter
    if (sections.count(key)) {
      const toml::table* t = node.as_table();
      if (!t)
        bad(file, node, fmt::format("`{}` must be a table ([{}] and its keys)", key, key));
      for (const auto& [name, n] : *t)
        take(key + "." + std::string(name.str()), n);
    } else {
      take(key, node);
    }
  }
  return given;
}

} // namespace

void apply_preset(const std::string& name, RunParameters& p)
{
  if (name != "paper" && name != "default")
    throw InvalidParameter(fmt::format("preset must be \"paper\" or \"default\", got \"{}\"", name));
  const RunParameters defaults;
  for (const ParameterEntry& e : parameter_schema())
    if (e.paper)
      e.set(p, name == "paper" ? *e.paper : e.get(defaults));
}

void read_run_parameters(const std::filesystem::path& file, RunParameters& p)
{
  toml::table table;
  try {
    table = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw IoError(fmt::format("{}:{}: {}", file.string(), e.source().begin.line, e.description()));
  }
  const std::vector<GivenKey> given = given_keys(file, table);
  // The preset first, the time-step mode last (a `tau` or `schedule` implies one), the rest in the
  // file's order.
  for (const auto order : {ParameterEntry::Order::first, ParameterEntry::Order::normal, ParameterEntry::Order::last})
    for (const GivenKey& g : given)
      if (g.entry->order == order) {
        const ParameterValue value = toml_value(file, *g.node, *g.entry);
        try {
          g.entry->set(p, value);
          for (const auto& implication : g.entry->implies)
            if (!implication.flag_only)
              find_parameter(implication.key)->set(p, implication.value);
        } catch (const InvalidParameter& e) {
          bad(file, *g.node, e.what());
        }
      }
  // Ranges once everything is read: whether a parameter is in use depends on others (the mode).
  for (const GivenKey& g : given)
    if (!g.entry->in_use || g.entry->in_use(p)) {
      try {
        check_range(*g.entry, g.entry->get(p));
      } catch (const InvalidParameter& e) {
        bad(file, *g.node, e.what());
      }
    }
}

void validate_stop_condition(const RunParameters& p)
{
  if (p.steps == 0 && std::isinf(p.end_time))
    throw InvalidParameter("no stop condition: give a number of steps or an end time");
}

namespace {

//! What the flow does not check of `p`: its stop condition and its own numbers; returns `p`.
const RunParameters& with_run_checks(const RunParameters& p)
{
  validate_stop_condition(p);
  check_in_range(run_ranges.snapshot_every, static_cast<double>(p.snapshot_every), "snapshot_every");
  check_in_range(run_ranges.checkpoint_every, static_cast<double>(p.checkpoint_every), "checkpoint_every");
  return p;
}

} // namespace

CheckedRunParameters::CheckedRunParameters(const RunParameters& parameters)
    : parameters_(with_run_checks(parameters)), flow_(parameters)
{
}

void validate_run_parameters(const RunParameters& parameters)
{
  (void)CheckedRunParameters(parameters);
}

std::string run_parameters_toml(const RunParameters& p)
{
  std::string s = "# sdflow run parameters, fully resolved (read back by `sdflow run --resume`)\n";
  std::string section;
  for (const ParameterEntry& e : parameter_schema()) {
    if (e.written && !e.written(p))
      continue;
    if (e.section() != section) {
      section = e.section();
      s += fmt::format("\n[{}]\n", section);
    }
    const ParameterValue value = e.get(p);
    if (const auto* schedule = std::get_if<ScheduleSetting>(&value); schedule && !schedule->file.empty())
      s += fmt::format("# {} read from {}\n", e.name(), schedule->file.string());
    s += fmt::format("{} = {}\n", e.name(), toml_text(value));
  }
  s += fmt::format("\n[{}]   # the sdflow that wrote this file (not parameters: ignored when read)\n"
                   "sdflow_version = {}\nsdflow_commit = {}\n",
                   written_by_table, toml_text(std::string(version())), toml_text(std::string(git_commit())));
  return s;
}

} // namespace sdflow
