#pragma once
//! \file numbers.h
//! \brief Numbers on the command line are plain decimals: CLI11 alone would take `0x10`, a
//! leading space, and clamp 2⁶³ to the largest long without a word.

#include <CLI/CLI.hpp>

#include <string>

namespace sdflow::cli {

//! "" when `text` is a whole decimal integer that fits a long long (or, `non_negative`, an
//! unsigned long long), else why not.
std::string integer_problem(const std::string& text, bool non_negative);

//! "" when `text` is a whole finite decimal number (no hexadecimal, no blanks, no nan/inf), or, with
//! `infinity`, "inf".
std::string real_problem(const std::string& text, bool infinity = false);

//! The type name of a floating-point option that also takes "inf" (a range that allows ∞).
inline constexpr const char* kRealOrInfinity = "FLOAT|inf";

//! Add the checks above to every integer and floating-point option of `app` and its verbs.
void require_plain_numbers(CLI::App& app);

} // namespace sdflow::cli
