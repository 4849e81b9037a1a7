#include "sdflow/io/io.h"

#include "sdflow/errors.h"
#include "sdflow/io/detail/formats.h"

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <system_error>

namespace sdflow {
namespace {

//! The whole file as bytes; IoError when it is missing, a directory, or unreadable.
std::string read_bytes(const std::filesystem::path& file)
{
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status))
    throw IoError(fmt::format("{}: no such file", file.string()));
  if (std::filesystem::is_directory(status))
    throw IoError(fmt::format("{}: is a directory, not a mesh file", file.string()));
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw IoError(fmt::format("{}: cannot be opened for reading ({})", file.string(), std::strerror(errno)));
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
    throw IoError(fmt::format("{}: reading failed ({})", file.string(), std::strerror(errno)));
  return bytes;
}

//! A name for the temporary file beside `file` that no other writer picks.
std::filesystem::path temporary_beside(const std::filesystem::path& file)
{
  static thread_local std::mt19937_64 random{std::random_device{}()};
  return file.parent_path() / fmt::format(".{}.{:016x}.tmp", file.filename().string(), random());
}

//! Errors of the machine rather than of the request: a full disk or quota, a file past the
//! process's size limit, a read-only file system, a failing device.
bool is_environment_error(int error)
{
  return error == ENOSPC || error == EDQUOT || error == EFBIG || error == EROFS || error == EIO;
}

[[noreturn]] void throw_write_error(int error, const std::string& message)
{
  if (is_environment_error(error))
    throw EnvironmentFailure(message + " (an environment failure: free space or raise the limit, then retry)");
  throw IoError(message);
}

} // namespace

MeshFormat format_from_extension(const std::filesystem::path& file)
{
  std::string extension = file.extension().string();
  for (char& c : extension)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".off")
    return MeshFormat::off;
  if (extension == ".obj")
    return MeshFormat::obj;
  if (extension == ".ply")
    return MeshFormat::ply;
  if (extension == ".stl")
    return MeshFormat::stl;
  if (extension == ".vtp")
    return MeshFormat::vtp;
  throw IoError(fmt::format("{}: unknown mesh format '{}' (expected .off, .obj, .ply, .stl or .vtp)", file.string(),
                            file.extension().string()));
}

PolygonSoup read_polygon_soup(const std::filesystem::path& file)
{
  const MeshFormat format = format_from_extension(file);
  const std::string bytes = read_bytes(file);
  const std::string_view text = detail::without_byte_order_mark(bytes, format);
  switch (format) {
  case MeshFormat::off: return detail::read_off(text, file);
  case MeshFormat::obj: return detail::read_obj(text, file);
  case MeshFormat::ply: return detail::read_ply(text, file);
  case MeshFormat::stl: return detail::read_stl(text, file);
  case MeshFormat::vtp: return detail::read_vtp(text, file);
  }
  throw IoError(fmt::format("{}: unhandled mesh format", file.string()));
}

BuiltMesh read_mesh(const std::filesystem::path& file, const BuildOptions& options)
{
  const PolygonSoup soup = read_polygon_soup(file);
  BuildOptions build = options;
  // STL repeats every shared vertex in each triangle; merging them is the only way to connect it.
  if (format_from_extension(file) == MeshFormat::stl)
    build.merge_duplicate_vertices = true;
  return build_mesh(soup, file.string(), build);
}

void write_mesh(const Mesh& mesh, const std::filesystem::path& file, const WriteOptions& options)
{
  const MeshFormat format = format_from_extension(file);
  const bool binary = options.encoding == Encoding::binary;
  check_vertex_fields(options.vertex_fields, mesh.n_vertices(), file);
  write_atomically(file, [&](std::ostream& out) {
    switch (format) {
    case MeshFormat::off: detail::write_off(mesh, out); break;
    case MeshFormat::obj: detail::write_obj(mesh, out); break;
    case MeshFormat::ply: detail::write_ply(mesh, out, binary, options.vertex_fields); break;
    case MeshFormat::stl: detail::write_stl(mesh, out, binary); break;
    case MeshFormat::vtp: detail::write_vtp(mesh, options.vertex_fields, out); break;
    }
  });
}

void write_atomically(const std::filesystem::path& file, const std::function<void(std::ostream&)>& write)
{
  const std::filesystem::path temporary = temporary_beside(file);
  auto discard = [&] {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
  };
  errno = 0;
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) {
    const int error = errno;
    throw_write_error(error, fmt::format("{}: cannot create the temporary file {} ({})", file.string(),
                                         temporary.string(), std::strerror(error)));
  }
  errno = 0;
  try {
    write(out);
  } catch (...) {
    out.close();
    discard();
    throw;
  }
  out.flush();
  const bool written = static_cast<bool>(out);
  out.close();
  if (!written || out.fail()) {
    const int error = errno;
    const std::string reason = error != 0 ? std::strerror(error) : "the stream reported an error";
    discard();
    throw_write_error(error, fmt::format("{}: writing failed ({}); the file is unchanged", file.string(), reason));
  }
  std::error_code ec;
  // A replaced file keeps its permissions, as it would if it had been overwritten in place.
  if (const auto status = std::filesystem::status(file, ec); !ec && std::filesystem::is_regular_file(status))
    std::filesystem::permissions(temporary, status.permissions(), ec);
  ec.clear();
  std::filesystem::rename(temporary, file, ec);
  if (ec) {
    discard();
    throw_write_error(ec.value(), fmt::format("{}: cannot replace the file ({})", file.string(), ec.message()));
  }
}

} // namespace sdflow
