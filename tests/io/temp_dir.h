#pragma once
//! \file temp_dir.h
//! \brief A fresh temporary directory per test, removed afterwards, and small file helpers.

#include <filesystem>
#include <string>
#include <string_view>

namespace sdflow::test {

//! Creates a unique empty directory and removes it (with its contents) on destruction.
class TempDir {
public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

//! Write `bytes` to `file` as they are (no newline translation).
void write_file(const std::filesystem::path& file, std::string_view bytes);

//! The whole file as bytes.
std::string read_file(const std::filesystem::path& file);

} // namespace sdflow::test
