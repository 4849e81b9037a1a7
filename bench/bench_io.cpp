//! Reading and writing meshes: sdflow's readers (parse only, and parse + validation) beside
//! OpenMesh's own readers on the same files, and the atomic writers.
//! Run: build/bench/bench_io --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include "sdflow/io/io.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <set>
#include <string>

namespace {

//! A torus of around × tube quads split in two: 2·around·tube triangles, every vertex valence 6.
sdflow::Mesh torus(int around, int tube)
{
  sdflow::VertexVectors x(around * tube, 3);
  sdflow::FaceIndices t(2 * around * tube, 3);
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      const double u = 2 * std::numbers::pi * i / around, v = 2 * std::numbers::pi * j / tube;
      x.row(i * tube + j) << (1 + 0.3 * std::cos(v)) * std::cos(u), (1 + 0.3 * std::cos(v)) * std::sin(u),
          0.3 * std::sin(v);
      const int a = i * tube + j, b = ((i + 1) % around) * tube + j, c = ((i + 1) % around) * tube + (j + 1) % tube,
                d = i * tube + (j + 1) % tube;
      t.row(2 * (i * tube + j)) << a, b, c;
      t.row(2 * (i * tube + j) + 1) << a, c, d;
    }
  return sdflow::make_mesh(x, t);
}

struct Sample {
  std::string name;
  sdflow::Encoding encoding;
};

const Sample samples[] = {{"off", sdflow::Encoding::ascii},      {"obj", sdflow::Encoding::ascii},
                          {"ply", sdflow::Encoding::ascii},      {"ply", sdflow::Encoding::binary},
                          {"stl", sdflow::Encoding::binary}};

std::filesystem::path sample_file(const Sample& s)
{
  return std::filesystem::temp_directory_path() /
         ("sdflow_bench_io_" + std::string(s.encoding == sdflow::Encoding::binary ? "binary." : "ascii.") + s.name);
}

const sdflow::Mesh& bench_mesh()
{
  static const sdflow::Mesh mesh = torus(400, 250); // 100k vertices, 200k triangles
  return mesh;
}

//! Write the sample once per run (never trust a file left by an older build).
void prepare(const Sample& s)
{
  static std::set<std::filesystem::path> written;
  if (written.insert(sample_file(s)).second)
    sdflow::write_mesh(bench_mesh(), sample_file(s), {.encoding = s.encoding});
}

void read_soup(benchmark::State& state, Sample s)
{
  prepare(s);
  for (auto _ : state)
    benchmark::DoNotOptimize(sdflow::read_polygon_soup(sample_file(s)));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench_mesh().n_faces()));
}

void read_and_validate(benchmark::State& state, Sample s)
{
  prepare(s);
  for (auto _ : state)
    benchmark::DoNotOptimize(sdflow::read_mesh(sample_file(s)));
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench_mesh().n_faces()));
}

void openmesh_read(benchmark::State& state, Sample s)
{
  prepare(s);
  for (auto _ : state) {
    sdflow::Mesh mesh;
    if (!OpenMesh::IO::read_mesh(mesh, sample_file(s).string()))
      state.SkipWithError("OpenMesh could not read the file");
    benchmark::DoNotOptimize(mesh);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench_mesh().n_faces()));
}

void write(benchmark::State& state, Sample s)
{
  const auto file = std::filesystem::temp_directory_path() / ("sdflow_bench_io_write." + s.name);
  for (auto _ : state)
    sdflow::write_mesh(bench_mesh(), file, {.encoding = s.encoding});
  std::filesystem::remove(file);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(bench_mesh().n_faces()));
}

const int registered = [] {
  for (const Sample& s : samples) {
    const std::string label = s.name + (s.encoding == sdflow::Encoding::binary ? "_binary" : "_ascii");
    benchmark::RegisterBenchmark(("read_soup/" + label).c_str(), read_soup, s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("read_mesh/" + label).c_str(), read_and_validate, s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("openmesh_read/" + label).c_str(), openmesh_read, s)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("write_mesh/" + label).c_str(), write, s)->Unit(benchmark::kMillisecond);
  }
  return 0;
}();

} // namespace

BENCHMARK_MAIN();
