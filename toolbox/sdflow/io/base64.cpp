#include "sdflow/io/detail/base64.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace sdflow::detail {
namespace {

constexpr std::string_view alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int sextet(char c)
{
  const std::size_t i = alphabet.find(c);
  return i == std::string_view::npos ? -1 : static_cast<int>(i);
}

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }

} // namespace

std::string encode_base64(std::string_view bytes)
{
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t word = 0;
    for (std::size_t k = 0; k < 3; ++k)
      word = (word << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k)
      text.push_back(k <= n ? alphabet[(word >> (18 - 6 * k)) & 0x3F] : '=');
  }
  return text;
}

bool decode_base64(std::string_view text, std::size_t& pos, std::size_t bytes, std::string& out)
{
  while (out.size() < bytes) {
    std::array<std::uint32_t, 4> group{};
    int padding = 0;
    for (int k = 0; k < 4; ++k) {
      while (pos < text.size() && is_space(text[pos]))
        ++pos;
      if (pos >= text.size())
        return false;
      const char c = text[pos++];
      if (c == '=' && k >= 2) {
        ++padding;
        continue;
      }
      const int value = sextet(c);
      if (padding > 0 || value < 0)
        return false;
      group[k] = static_cast<std::uint32_t>(value);
    }
    const std::uint32_t word = (group[0] << 18) | (group[1] << 12) | (group[2] << 6) | group[3];
    out.push_back(static_cast<char>(word >> 16));
    if (padding < 2)
      out.push_back(static_cast<char>((word >> 8) & 0xFF));
    if (padding < 1)
      out.push_back(static_cast<char>(word & 0xFF));
  }
  return true;
}

} // namespace sdflow::detail
