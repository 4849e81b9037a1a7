#pragma once
//! \file help_formatter.h
//! \brief The layout of `sdflow --help` and every verb's help: CLI11's, without its internal
//! notation. A choice reads `cotangent|uniform`, a file `FILE`, a default `(default: fair)`; no
//! `{false}` after a flag that has a `--no-` form, no `ENUM:value in {...}`, no validator ranges.
//! The man page and bash completion are read from this text (cli/man/).

#include <CLI/CLI.hpp>

#include <string>

namespace sdflow::cli {

class HelpFormatter : public CLI::Formatter {
public:
  //! Every name of the option, short ones first: `-o, --output, --out`.
  std::string make_option_name(const CLI::Option* option, bool is_positional) const override;
  //! The value's placeholder (its choices, FILE, DIR, INT, FLOAT, TEXT), how many values, the
  //! default, REQUIRED, the options it excludes.
  std::string make_option_opts(const CLI::Option* option) const override;
};

//! The placeholder of an option's value from CLI11's type name and validator descriptions:
//! "TEXT:{a,b}" → "a|b", "TEXT:FILE" → "FILE", "INT:INT in [6 - 1000]" → "INT", "a|b:value in
//! {...}" → "a|b".
std::string value_placeholder(const std::string& cli11_type_name);

} // namespace sdflow::cli
