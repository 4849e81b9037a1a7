#include "sdflow/errors.h"
#include "sdflow/io/detail/formats.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <system_error>

namespace sdflow::detail {

void fail(const std::filesystem::path& file, std::size_t line, std::string_view what)
{
  if (line == 0)
    throw IoError(fmt::format("{}: {}", file.string(), what));
  throw IoError(fmt::format("{}:{}: {}", file.string(), line, what));
}

bool LineReader::next(std::string_view& line)
{
  if (pos_ >= text_.size())
    return false;
  const std::size_t end = text_.find('\n', pos_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r')
    line.remove_suffix(1);
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++line_;
  return true;
}

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

} // namespace

std::string_view without_byte_order_mark(std::string_view bytes, MeshFormat format)
{
  constexpr std::string_view mark = "\xEF\xBB\xBF";
  if (bytes.substr(0, mark.size()) != mark)
    return bytes;
  const std::string_view rest = bytes.substr(mark.size());
  if (format == MeshFormat::stl && !(rest.size() >= 5 && iequals(rest.substr(0, 5), "solid")))
    return bytes;
  return rest;
}

std::vector<std::string_view> split_tokens(std::string_view line)
{
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i]))
      ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i]))
      ++i;
    if (i > start)
      tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::string_view strip_comment(std::string_view line)
{
  if (const auto hash = line.find('#'); hash != std::string_view::npos)
    line = line.substr(0, hash);
  while (!line.empty() && is_space(line.front()))
    line.remove_prefix(1);
  while (!line.empty() && is_space(line.back()))
    line.remove_suffix(1);
  return line;
}

bool parse_double(std::string_view token, double& value)
{
  // from_chars rejects a leading '+', which C's strtod and most mesh writers accept.
  if (token.size() > 1 && token.front() == '+' && token[1] != '-')
    token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value, std::chars_format::general);
  return ec == std::errc() && ptr == end && !token.empty();
}

bool parse_integer(std::string_view token, long long& value)
{
  if (token.size() > 1 && token.front() == '+' && token[1] != '-')
    token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end && !token.empty();
}

bool iequals(std::string_view a, std::string_view b)
{
  if (a.size() != b.size())
    return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

Numbering number_elements(const Mesh& mesh)
{
  Numbering n;
  n.vertex.assign(mesh.n_vertices(), -1);
  for (auto v : mesh.vertices())
    n.vertex[v.idx()] = static_cast<int>(n.vertices++);
  for ([[maybe_unused]] auto f : mesh.faces())
    ++n.faces;
  return n;
}

std::string format_point(const Mesh::Point& p) { return fmt::format("{:.17g} {:.17g} {:.17g}", p[0], p[1], p[2]); }

} // namespace sdflow::detail
