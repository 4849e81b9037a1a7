#pragma once
//! \file common_options.h
//! \brief The options every verb spells the same way: the output (`-o`, `--output`, `--out`), the
//! encoding of PLY and STL files (`--binary`, the default, or `--ascii`), `--json`, `-q`/`-v`, and
//! choices listed by name in the help.

#include "sdflow/io/io.h"

#include <CLI/CLI.hpp>

#include <map>
#include <string>

namespace sdflow::cli {

//! The names of an output option, on every verb that writes one.
inline constexpr const char* output_names = "-o,--output,--out";

//! The mesh formats every verb reads and writes (io/io.h, MeshFormat), as help texts list them.
inline constexpr const char* mesh_formats = "OFF, OBJ, PLY, STL, VTP";

//! `-o, --output, --out`: where the verb writes its result.
CLI::Option* add_output_option(CLI::App& verb, std::string& output, const std::string& help);

//! `--binary` (the default) and `--ascii`: how PLY and STL files are written (OFF and OBJ are text).
void add_encoding_flags(CLI::App& verb, Encoding& encoding);

//! `--json`: the result as one JSON object on stdout (and on failure the error and its findings,
//! written by main: cli/failure.h). `keys` names where README documents the keys.
CLI::Option* add_json_flag(CLI::App& verb, bool& json, const std::string& keys = "keys documented in README.md");

//! `-q, --quiet` and `-v, --verbose` after the verb too, bound to the flags the top level has.
void add_verbosity_flags(CLI::App& verb, bool& verbose, bool& quiet);

//! An option taking one of `choices` by name (case-insensitive), its help listing them.
template <typename Value>
CLI::Option* add_choice_option(CLI::App& verb, const std::string& names, Value& value,
                               const std::map<std::string, Value>& choices, const std::string& help)
{
  std::string placeholder;
  for (const auto& [name, _] : choices)
    placeholder += (placeholder.empty() ? "" : "|") + name;
  return verb.add_option(names, value, help)
      ->transform(CLI::CheckedTransformer(choices, CLI::ignore_case).description(""))
      ->type_name(placeholder);
}

} // namespace sdflow::cli
