#pragma once
//! \file json_query.h
//! \brief Reading a verb's `--json` output in tests with python3's own JSON parser, so a test checks
//! that the output parses as exactly one JSON document, not only that it contains some text.

#include <optional>
#include <string>

namespace sdflow::test {

//! `expression` (Python, over the parsed object `d`) evaluated on `json` by python3's json module;
//! nullopt when `json` is not exactly one JSON document.
std::optional<std::string> json_query(const std::string& json, const std::string& expression);

} // namespace sdflow::test
