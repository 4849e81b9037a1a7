#pragma once
//! \file base64.h
//! \brief Private to the toolbox: base64 (RFC 4648), the text encoding of binary arrays in VTK XML
//! files.

#include <cstddef>
#include <string>
#include <string_view>

namespace sdflow::detail {

//! `bytes` in base64, padded with '=' to a whole number of 4-character groups.
std::string encode_base64(std::string_view bytes);

//! Decode base64 from `text` at `pos`, appending to `out` until it holds at least `bytes` bytes;
//! `pos` ends after the last group read. Whitespace is skipped and each 4-character group decoded
//! on its own, so streams encoded in pieces (VTK may encode a header apart from its data) decode
//! as one. False on a character outside the alphabet or a truncated group.
bool decode_base64(std::string_view text, std::size_t& pos, std::size_t bytes, std::string& out);

} // namespace sdflow::detail
