#include "sdflow/run/parameter_schema.h"

#include "sdflow/errors.h"
#include "sdflow/run/detail/schema_sections.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

namespace sdflow {
namespace {

std::vector<ParameterEntry> build_schema()
{
  std::vector<ParameterEntry> s;
  detail::add_run_entries(s);
  detail::add_time_step_entries(s);
  detail::add_scheme_entries(s);
  detail::add_output_entries(s);
  detail::add_flow_option_entries(s);
  detail::add_energy_entries(s);
  detail::add_adaptive_entries(s);
  detail::add_retriangulation_entries(s);
  detail::add_reference_sphere_entries(s);
  return s;
}

std::string quoted(const std::string& s)
{
  std::ostringstream out;
  out << toml::value<std::string>(s);
  return out.str();
}

//! `s` as a TOML basic string: in double quotes, with quotes, backslashes and control characters escaped
//! (toml++ would print a plain name as a literal string, 'name', changing run.toml's bytes).
std::string basic_string(const std::string& s)
{
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
    case '"': out += "\\\""; break;
    case '\\': out += "\\\\"; break;
    case '\n': out += "\\n"; break;
    case '\t': out += "\\t"; break;
    case '\r': out += "\\r"; break;
    default:
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        out += fmt::format("\\u{:04X}", static_cast<unsigned char>(c));
      else
        out += c;
    }
  }
  return out + "\"";
}

//! Levenshtein distance, for suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

} // namespace

std::string type_name(ParameterType type)
{
  switch (type) {
  case ParameterType::integer: return "integer";
  case ParameterType::real: return "real";
  case ParameterType::boolean: return "boolean";
  case ParameterType::choice: return "choice";
  case ParameterType::path: return "path";
  case ParameterType::point: return "point";
  case ParameterType::schedule: return "schedule";
  case ParameterType::reals: return "reals";
  case ParameterType::text: return "text";
  }
  return "?";
}

bool ScheduleSetting::operator==(const ScheduleSetting& other) const
{
  return file == other.file &&
         std::equal(entries.begin(), entries.end(), other.entries.begin(), other.entries.end(),
                    [](const ScheduleEntry& a, const ScheduleEntry& b) {
                      return a.first_step == b.first_step && a.last_step == b.last_step && a.tau == b.tau;
                    });
}

std::string ParameterEntry::section() const
{
  const auto dot = key.find('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string ParameterEntry::name() const
{
  const auto dot = key.find('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

std::string ParameterEntry::default_text() const
{
  // None: no path, no schedule, no preset, no end time, no constant τ (0 is outside its range).
  if (type == ParameterType::path || type == ParameterType::schedule)
    return "none";
  const RunParameters defaults;
  const ParameterValue value = get(defaults);
  if (const auto* text = std::get_if<std::string>(&value); text && text->empty())
    return "none";
  if (const auto* number = std::get_if<double>(&value);
      number && (!range.contains(*number) || (std::isinf(*number) && written && !written(defaults))))
    return "none";
  return toml_text(value);
}

const std::vector<ParameterEntry>& parameter_schema()
{
  static const std::vector<ParameterEntry> schema = build_schema();
  return schema;
}

const ParameterEntry* find_parameter(const std::string& key)
{
  for (const ParameterEntry& e : parameter_schema())
    if (e.key == key || std::find(e.key_aliases.begin(), e.key_aliases.end(), key) != e.key_aliases.end())
      return &e;
  return nullptr;
}

bool MeshlabParameter::offered_by(const MeshlabFilter filter) const
{
  return !name.empty() && std::find(filters.begin(), filters.end(), filter) != filters.end();
}

const ParameterEntry* find_meshlab_parameter(const std::string& name, const MeshlabFilter filter)
{
  for (const ParameterEntry& e : parameter_schema())
    if (e.meshlab.name == name && e.meshlab.offered_by(filter))
      return &e;
  return nullptr;
}

std::string closest_parameter_key(const std::string& key)
{
  std::string best;
  std::size_t best_distance = 0;
  for (const ParameterEntry& e : parameter_schema()) {
    std::vector<std::string> names = {e.key};
    names.insert(names.end(), e.key_aliases.begin(), e.key_aliases.end());
    for (const std::string& name : names) {
      // Within a table, compare the names after the section; a key in the wrong table is close too.
      const std::size_t d = std::min(edit_distance(key, name), edit_distance(key, e.name()));
      if (best.empty() || d < best_distance) {
        best = e.key;
        best_distance = d;
      }
    }
  }
  const std::size_t bound = std::max<std::size_t>(2, key.size() / 3);
  return best_distance <= bound ? best : std::string();
}

std::string toml_text(const ParameterValue& value)
{
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, long>) {
          return fmt::format("{}", v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isnan(v))
            return "nan";
          if (std::isinf(v))
            return v > 0 ? "inf" : "-inf";
          return fmt::format("{}", v);
        } else if constexpr (std::is_same_v<T, bool>) {
          return v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::string>) {
          return basic_string(v); // a choice's name or a text
        } else if constexpr (std::is_same_v<T, std::filesystem::path>) {
          return quoted(std::filesystem::absolute(v).lexically_normal().string());
        } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
          return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z());
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          return fmt::format("[{}]", fmt::join(v, ", "));
        } else {
          std::string s = "[";
          for (const ScheduleEntry& e : v.entries)
            s += fmt::format("[{}, {}, {}], ", e.first_step, e.last_step, e.tau);
          return s + "]";
        }
      },
      value);
}

void check_range(const ParameterEntry& entry, const ParameterValue& value)
{
  double number = 0;
  if (const long* i = std::get_if<long>(&value))
    number = static_cast<double>(*i);
  else if (const double* d = std::get_if<double>(&value))
    number = *d;
  else
    return;
  if (!entry.range.contains(number))
    throw InvalidParameter(fmt::format("{} must be {}{}, got {}", entry.key, std::isinf(number) ? "finite and " : "",
                                       entry.range.text(), toml_text(value)));
}

std::string parameter_table_markdown()
{
  std::string s = "| key | flag | type | default | range | `--resume` | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const ParameterEntry& e : parameter_schema()) {
    std::string key = "`" + e.key + "`";
    for (const std::string& alias : e.key_aliases)
      key += " (or `" + alias + "`)";
    std::string flag = "`" + e.flag + "`";
    if (!e.flag_aliases.empty())
      flag += " (or `" + fmt::format("{}", fmt::join(e.flag_aliases, "`, `")) + "`)";
    for (const auto& shorthand : e.shorthands)
      flag += ", `" + shorthand.flag + "`";
    if (e.type == ParameterType::boolean)
      flag += ", `--no-" + e.flag.substr(2) + "`";
    std::string type = type_name(e.type);
    if (e.type == ParameterType::choice) {
      type.clear();
      for (const std::string& c : e.choices)
        type += (type.empty() ? "" : " \\| ") + ("`" + c + "`");
    }
    const std::string default_text = e.default_text();
    std::string meaning = e.help;
    if (!e.meshlab.name.empty())
      meaning += " (MeshLab: `" + e.meshlab.name + "`)";
    // A '|' inside a cell would end it.
    std::string cell;
    for (char c : meaning)
      cell += c == '|' ? std::string("\\|") : std::string(1, c);
    s += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", key, flag, type,
                     default_text == "none" ? "—" : "`" + default_text + "`", e.range.text(),
                     e.resumable ? "yes" : "", cell);
  }
  return s;
}

std::string meshlab_parameter_table_markdown()
{
  std::string s = "| parameter (.mlx name) | meaning | `sdflow run` |\n|---|---|---|\n";
  for (const ParameterEntry& e : parameter_schema()) {
    if (e.meshlab.name.empty())
      continue;
    std::string cell;
    for (char c : e.meshlab.help.empty() ? e.help : e.meshlab.help)
      cell += c == '|' ? std::string("\\|") : std::string(1, c);
    std::string flag = "`" + e.flag + "`";
    for (const auto& shorthand : e.shorthands)
      flag += ", `" + shorthand.flag + "`";
    if (e.type == ParameterType::boolean)
      flag += ", `--no-" + e.flag.substr(2) + "`";
    if (e.meshlab.filters.size() < meshlab_filters.size()) {
      std::string only;
      for (std::size_t i = 0; i < e.meshlab.filters.size(); ++i)
        only += fmt::format("{}*{}*", i == 0 ? "" : i + 1 == e.meshlab.filters.size() ? " and " : ", ",
                            meshlab_filter_name(e.meshlab.filters[i]));
      cell += " (" + only + " only)";
    }
    s += fmt::format("| {} (`{}`) | {} | {} |\n", e.meshlab.label, e.meshlab.name, cell, flag);
  }
  return s;
}

} // namespace sdflow
