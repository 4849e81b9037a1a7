#include "help_formatter.h"

#include <sstream>
#include <vector>

namespace sdflow::cli {

std::string value_placeholder(const std::string& cli11_type_name)
{
  std::vector<std::string> parts;
  std::string::size_type begin = 0;
  // Split at the ':' CLI11 puts before each validator's description (never inside braces).
  int depth = 0;
  for (std::string::size_type i = 0; i < cli11_type_name.size(); ++i) {
    const char c = cli11_type_name[i];
    depth += c == '{' || c == '[';
    depth -= c == '}' || c == ']';
    if (c == ':' && depth == 0) {
      parts.push_back(cli11_type_name.substr(begin, i - begin));
      begin = i + 1;
    }
  }
  parts.push_back(cli11_type_name.substr(begin));
  std::string placeholder = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::string& validator = parts[i];
    if (validator == "FILE" || validator == "DIR" || validator == "PATH(existing)")
      placeholder = validator == "DIR" ? "DIR" : "FILE";
    else if (placeholder == "TEXT" && validator.size() > 2 && validator.front() == '{' && validator.back() == '}') {
      placeholder = validator.substr(1, validator.size() - 2);
      for (char& c : placeholder)
        c = c == ',' ? '|' : c;
    }
  }
  return placeholder;
}

std::string HelpFormatter::make_option_name(const CLI::Option* option, bool is_positional) const
{
  if (is_positional)
    return option->get_name(true, false);
  std::string names;
  for (const std::string& s : option->get_snames())
    names += (names.empty() ? "-" : ", -") + s;
  for (const std::string& l : option->get_lnames())
    names += (names.empty() ? "--" : ", --") + l;
  return names;
}

std::string HelpFormatter::make_option_opts(const CLI::Option* option) const
{
  if (!option->get_option_text().empty())
    return " " + option->get_option_text();
  std::ostringstream out;
  if (option->get_type_size() != 0) {
    const std::string placeholder = value_placeholder(option->get_type_name());
    if (!placeholder.empty())
      out << ' ' << placeholder;
    if (option->get_expected_max() == CLI::detail::expected_max_vector_size)
      out << " ...";
    else if (option->get_expected_min() > 1 && placeholder.find(',') == std::string::npos)
      out << " x " << option->get_expected_min(); // "X,Y,Z" says it already
    if (!option->get_default_str().empty())
      out << " (default: " << option->get_default_str() << ')';
    if (option->get_required())
      out << " REQUIRED";
  }
  if (!option->get_excludes().empty()) {
    out << " (not with";
    for (const CLI::Option* other : option->get_excludes())
      out << ' ' << other->get_name();
    out << ')';
  }
  return out.str();
}

} // namespace sdflow::cli
