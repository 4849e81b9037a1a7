#include "sdflow/run/checkpoint.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

namespace sdflow {
namespace {

static_assert(std::endian::native == std::endian::little, "checkpoints are written on little-endian machines");

constexpr char magic[8] = {'S', 'D', 'F', 'L', 'O', 'W', 'C', 'K'};
constexpr std::uint32_t version = 8;

std::uint64_t fnv1a(const char* data, std::size_t size)
{
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= static_cast<unsigned char>(data[i]);
    hash *= 1099511628211ull;
  }
  return hash;
}

class Writer {
public:
  template <typename T>
  void put(const T& value)
  {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  void put_doubles(const double* data, std::size_t count)
  {
    put<std::uint64_t>(count);
    bytes_.append(reinterpret_cast<const char*>(data), count * sizeof(double));
  }
  void put_ints(const std::vector<int>& values)
  {
    put<std::uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(int));
  }
  void put_string(const std::string& s)
  {
    put<std::uint64_t>(s.size());
    bytes_ += s;
  }
  std::string& bytes() { return bytes_; }

private:
  std::string bytes_;
};

class Reader {
public:
  Reader(const std::string& bytes, const std::filesystem::path& file) : bytes_(bytes), file_(file) {}
  template <typename T>
  T get()
  {
    T value;
    take(&value, sizeof(T));
    return value;
  }
  std::vector<double> get_doubles()
  {
    const auto count = get<std::uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(double))
      truncated();
    std::vector<double> values(count);
    take(values.data(), count * sizeof(double));
    return values;
  }
  std::vector<int> get_ints()
  {
    const auto count = get<std::uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(int))
      truncated();
    std::vector<int> values(count);
    take(values.data(), count * sizeof(int));
    return values;
  }
  std::string get_string()
  {
    const auto size = get<std::uint64_t>();
    if (size > bytes_.size() - at_)
      truncated();
    std::string s = bytes_.substr(at_, size);
    at_ += size;
    return s;
  }

private:
  void take(void* out, std::size_t size)
  {
    if (size > bytes_.size() - at_)
      truncated();
    if (size > 0)  // memcpy's pointers must be valid even for zero bytes
      std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  [[noreturn]] void truncated() const
  {
    throw IoError(fmt::format("{}: checkpoint is truncated or corrupt", file_.string()));
  }
  const std::string& bytes_;
  const std::filesystem::path& file_;
  std::size_t at_ = 0;
};

VertexVectors to_vectors(const std::vector<double>& values, const std::filesystem::path& file)
{
  if (values.size() % 3 != 0)
    throw IoError(fmt::format("{}: checkpoint holds a vertex array of {} numbers", file.string(), values.size()));
  VertexVectors v(values.size() / 3, 3);
  std::copy(values.begin(), values.end(), v.data());
  return v;
}

void put_solver(Writer& w, const SolverRecord& s)
{
  w.put<std::int64_t>(s.counters.solves_since_factorisation);
  w.put<std::int64_t>(s.counters.iterations_since_factorisation);
  w.put<std::int32_t>(s.counters.last_iterations);
  w.put<std::uint8_t>(s.anchor.has_value());
  const FactorAnchor none;
  const FactorAnchor& anchor = s.anchor ? *s.anchor : none;
  w.put_doubles(anchor.positions.data(), static_cast<std::size_t>(anchor.positions.size()));
  w.put(anchor.tau_beta);
}

SolverRecord get_solver(Reader& r, const std::filesystem::path& file)
{
  SolverRecord s;
  s.counters.solves_since_factorisation = r.get<std::int64_t>();
  s.counters.iterations_since_factorisation = r.get<std::int64_t>();
  s.counters.last_iterations = r.get<std::int32_t>();
  const bool has_anchor = r.get<std::uint8_t>() != 0;
  FactorAnchor anchor{.positions = to_vectors(r.get_doubles(), file)};
  anchor.tau_beta = r.get<double>();
  if (has_anchor)
    s.anchor = std::move(anchor);
  return s;
}

} // namespace

void write_checkpoint(const Checkpoint& c, const std::filesystem::path& file)
{
  const StepBookkeeping& b = c.bookkeeping;
  Writer w;
  w.bytes().append(magic, sizeof magic);
  w.put(version);
  w.put<std::int64_t>(c.step);
  w.put(c.time);
  w.put_doubles(c.positions.data(), static_cast<std::size_t>(c.positions.size()));
  w.put<std::uint64_t>(static_cast<std::uint64_t>(c.triangles.rows()));
  w.bytes().append(reinterpret_cast<const char*>(c.triangles.data()), c.triangles.size() * sizeof(int));
  w.put_doubles(c.previous_w.data(), static_cast<std::size_t>(c.previous_w.size()));
  w.put(b.controller.next_tau);
  w.put<std::int32_t>(b.controller.rejections);
  put_solver(w, b.solver);
  w.put<std::uint64_t>(c.snapshots.size());
  for (const auto& s : c.snapshots) {
    w.put(s.time);
    w.put_string(s.file.generic_string());
  }
  w.put<std::int64_t>(c.tolerated_degraded);
  put_solver(w, b.half_solver);
  w.put<std::int64_t>(b.controller.table_lag);
  w.put(b.controller.fallback_left);
  w.put_doubles(c.earlier_w.data(), static_cast<std::size_t>(c.earlier_w.size()));
  for (const SolverState* s : {&b.solver.counters, &b.half_solver.counters}) {
    w.put_ints(s->ordering);
    w.put(s->fresh_fill);
  }
  w.put(c.debris_volume);
  w.put(b.controller.turning_since_tau);
  w.put(fnv1a(w.bytes().data(), w.bytes().size()));
  write_atomically(file, [&](std::ostream& out) { out.write(w.bytes().data(), static_cast<std::streamsize>(w.bytes().size())); });
}

Checkpoint read_checkpoint(const std::filesystem::path& file)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw IoError(fmt::format("{}: cannot open the checkpoint", file.string()));
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < sizeof magic + sizeof(std::uint64_t) || std::memcmp(bytes.data(), magic, sizeof magic) != 0)
    throw IoError(fmt::format("{}: not an sdflow checkpoint", file.string()));
  std::uint64_t stored = 0;
  std::memcpy(&stored, bytes.data() + bytes.size() - sizeof stored, sizeof stored);
  if (stored != fnv1a(bytes.data(), bytes.size() - sizeof stored))
    throw IoError(fmt::format("{}: checkpoint fails its checksum (truncated or corrupt)", file.string()));

  Reader r(bytes, file);
  r.get<std::array<char, sizeof magic>>();
  const auto file_version = r.get<std::uint32_t>();
  if (file_version < 1 || file_version > version)
    throw IoError(fmt::format("{}: checkpoint version {} (this sdflow reads versions 1 to {})", file.string(),
                              file_version, version));
  Checkpoint c;
  StepBookkeeping& b = c.bookkeeping;
  c.step = r.get<std::int64_t>();
  c.time = r.get<double>();
  c.positions = to_vectors(r.get_doubles(), file);
  const auto triangle_count = r.get<std::uint64_t>();
  if (triangle_count > bytes.size() / (3 * sizeof(int)))
    throw IoError(fmt::format("{}: checkpoint is truncated or corrupt", file.string()));
  c.triangles.resize(static_cast<Eigen::Index>(triangle_count), 3);
  for (Eigen::Index i = 0; i < c.triangles.size(); ++i)
    c.triangles.data()[i] = r.get<int>();
  const std::vector<double> w = r.get_doubles();
  c.previous_w = Eigen::Map<const Eigen::VectorXd>(w.data(), static_cast<Eigen::Index>(w.size()));
  b.controller.next_tau = r.get<double>();
  b.controller.rejections = r.get<std::int32_t>();
  b.solver = get_solver(r, file);
  const auto snapshot_count = r.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < snapshot_count; ++i) {
    SeriesEntry s;
    s.time = r.get<double>();
    s.file = r.get_string();
    c.snapshots.push_back(std::move(s));
  }
  if (file_version >= 2)
    c.tolerated_degraded = r.get<std::int64_t>();
  if (file_version >= 3)
    b.half_solver = get_solver(r, file);
  if (file_version >= 4) {
    b.controller.table_lag = r.get<std::int64_t>();
    b.controller.fallback_left = r.get<double>();
    if (b.controller.table_lag < 0 || b.controller.table_lag > c.step || !(b.controller.fallback_left >= 0) ||
        !std::isfinite(b.controller.fallback_left))
      throw IoError(fmt::format("{}: checkpoint's τ table position is corrupt", file.string()));
  }
  if (file_version >= 5) {
    const std::vector<double> earlier = r.get_doubles();
    c.earlier_w = Eigen::Map<const Eigen::VectorXd>(earlier.data(), static_cast<Eigen::Index>(earlier.size()));
  }
  if (file_version >= 6)
    for (SolverState* s : {&b.solver.counters, &b.half_solver.counters}) {
      s->ordering = r.get_ints();
      s->fresh_fill = r.get<double>();
      if (!s->ordering.empty() && s->ordering.size() != static_cast<std::size_t>(c.positions.rows()))
        throw IoError(fmt::format("{}: checkpoint's Cholesky ordering has {} entries for {} vertices", file.string(),
                                  s->ordering.size(), c.positions.rows()));
    }
  if (file_version >= 7) {
    c.debris_volume = r.get<double>();
    if (!std::isfinite(c.debris_volume))
      throw IoError(fmt::format("{}: checkpoint's debris volume is not finite", file.string()));
  }
  if (file_version >= 8) {
    b.controller.turning_since_tau = r.get<double>();
    if (!(b.controller.turning_since_tau >= 0) || !std::isfinite(b.controller.turning_since_tau))
      throw IoError(fmt::format("{}: checkpoint's τ at which triangles began turning over is corrupt", file.string()));
  }
  return c;
}

} // namespace sdflow
