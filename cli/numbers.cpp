#include "numbers.h"

#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>

namespace sdflow::cli {
namespace {

std::string_view without_plus(std::string_view text)
{
  if (text.size() > 1 && text.front() == '+' && text[1] != '-')
    text.remove_prefix(1);
  return text;
}

template <class T>
std::string parse_whole(std::string_view text, T& value)
{
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range)
    return "out of range";
  if (ec != std::errc() || end != text.data() + text.size() || text.empty())
    return "not a plain decimal number";
  return "";
}

} // namespace

std::string integer_problem(const std::string& text, bool non_negative)
{
  const std::string_view t = without_plus(text);
  std::string problem;
  if (non_negative) {
    unsigned long long value = 0;
    problem = t.starts_with('-') ? "negative" : parse_whole(t, value);
  } else {
    long long value = 0;
    problem = parse_whole(t, value);
  }
  return problem.empty() ? "" : "'" + text + "' is " + problem + " (a whole decimal number is expected)";
}

std::string real_problem(const std::string& text, bool infinity)
{
  double value = 0;
  const std::string_view t = without_plus(text);
  if (infinity && t == "inf")
    return "";
  std::string problem = parse_whole(t, value);
  if (problem.empty() && !std::isfinite(value))
    problem = "not finite";
  return problem.empty() ? ""
                         : "'" + text + "' is " + problem +
                               (infinity ? " (a finite decimal number or inf is expected)"
                                         : " (a finite decimal number is expected)");
}

void require_plain_numbers(CLI::App& app)
{
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type.rfind("INT", 0) == 0)
      option->check(CLI::Validator([](std::string& s) { return integer_problem(s, false); }, "", ""));
    else if (type.rfind("UINT", 0) == 0)
      option->check(CLI::Validator([](std::string& s) { return integer_problem(s, true); }, "", ""));
    else if (type.rfind("FLOAT", 0) == 0)
      option->check(CLI::Validator([infinity = type == kRealOrInfinity](std::string& s) { return real_problem(s, infinity); },
                                   "", ""));
  }
  for (CLI::App* verb : app.get_subcommands([](CLI::App*) { return true; }))
    require_plain_numbers(*verb);
}

} // namespace sdflow::cli
