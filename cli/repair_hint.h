#pragma once
//! \file repair_hint.h
//! \brief Reading a verb's input mesh, and when validation refuses it for problems `sdflow repair`
//! fixes, saying so in the error with the command to run.

#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <string_view>

namespace sdflow::cli {

//! `text` as one word of a POSIX shell: unchanged when it holds only safe characters, else in
//! single quotes (a quote inside written as '\'').
inline std::string shell_word(const std::string& text)
{
  const bool safe = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("_./-+:,=@%").find(c) != std::string_view::npos;
  });
  if (safe)
    return text;
  std::string quoted = "'";
  for (const char c : text)
    quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

//! read_mesh(file); when it is refused only for findings repair_soup() fixes (io/repair.h), the
//! same error with the `sdflow repair` command that writes a valid copy (FILE_repaired.EXT).
inline BuiltMesh read_mesh_or_suggest_repair(const std::filesystem::path& file)
{
  try {
    return read_mesh(file);
  } catch (const MeshValidationError& e) {
    const auto& findings = e.findings();
    if (findings.empty() ||
        !std::all_of(findings.begin(), findings.end(), [](const Finding& f) { return is_repairable(f.code); }))
      throw;
    std::filesystem::path repaired = file;
    repaired.replace_filename(file.stem().string() + "_repaired" + file.extension().string());
    throw MeshValidationError(fmt::format("{}\n`sdflow repair` fixes these: sdflow repair {} -o {}", e.what(),
                                          shell_word(file.string()), shell_word(repaired.string())),
                              findings);
  }
}

} // namespace sdflow::cli
