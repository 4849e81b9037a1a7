//! libFuzzer harness: two steps of `sdflow run` with its defaults (re-triangulation on) on a small
//! mesh read from OFF text, after what `run` does before step 1 (check_run_input, run/run_input.h:
//! the checks, and the exact refinement of a surface too coarse for the default ℓ). A refusal with
//! a reason (an sdflow::Error) is fine, and so is a SolverFailure of the flow itself. Findings,
//! besides a crash, a sanitizer report or another exception: a failure from inside the
//! re-triangulation (a message from a stage, which no user should see) and a surface after the
//! steps with a zero-area or non-finite face. Inputs above `max_vertices`, or refined by `run`
//! beyond `max_refined_vertices`, are skipped, which keeps each under about a second; libFuzzer's
//! -timeout catches a slow one (scripts/fuzz.sh).
#include "fuzz_common.h"

#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/limits.h"
#include "sdflow/remesh/exact_refinement.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/run/coarse_input.h"
#include "sdflow/run/parameters.h"
#include "sdflow/run/run_input.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

namespace {

constexpr std::size_t max_vertices = 400;
constexpr std::size_t max_refined_vertices = 2000;

[[noreturn]] void finding(const std::string& what)
{
  std::fprintf(stderr, "fuzz_run: %s\n", what.c_str());
  std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  // One thread: a finding replays exactly (the look-ahead's trial runs beside the look otherwise).
  static tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  sdflow::Mesh mesh;
  try {
    const sdflow::PolygonSoup soup =
        sdflow::detail::read_off(sdflow::detail::without_byte_order_mark(bytes, sdflow::MeshFormat::off), "fuzz.off");
    if (soup.points.size() > max_vertices)
      return 0;
    mesh = sdflow::build_mesh(soup, "fuzz.off").mesh;
  } catch (const sdflow::Error&) {
    return 0;
  }
  sdflow::RunParameters parameters;
  parameters.steps = 2;
  std::optional<sdflow::CheckedRunParameters> checked;
  try {
    checked.emplace(parameters);
    // Refining a coarse input is exact but, on uneven triangles, may make tens of thousands of
    // vertices (a 79-vertex spike made 59 000), whose checks alone outlast the per-input limit in
    // this instrumented build: an input `run` would refine beyond max_refined_vertices is skipped
    // before, not after (the same refinement as refine_coarse_input's, stopped at the bound).
    if (const auto ell = sdflow::coarse_input_edge_length(mesh, parameters.retriangulation.pipeline, "fuzz.off"))
      if (sdflow::refine_exactly(mesh, {.max_edge_length = sdflow::kRemeshSplitRatio * *ell,
                                         .max_vertices = max_refined_vertices})
              .stopped)
        return 0;
    sdflow::check_run_input(mesh, parameters, "fuzz.off", sdflow::FrontEnd::command_line,
                            sdflow::run_input_limits(sdflow::FrontEnd::command_line, false));
    // A thin part makes `run` take a finer ℓ: skipped, as above, when its remeshing would outgrow
    // what two steps take in about a second.
    const double ell = parameters.retriangulation.pipeline.edge_length;
    if (ell > 0 && sdflow::estimated_vertices(sdflow::surface_area(mesh), ell) > max_refined_vertices)
      return 0;
    checked.emplace(parameters);
  } catch (const sdflow::Error&) {
    return 0; // refused up front, as `run` refuses it
  }
  if (mesh.n_vertices() > max_refined_vertices)
    return 0; // refined by `run` beyond what two steps take in about a second
  std::optional<sdflow::SurfaceDiffusion> made;
  try {
    made.emplace(mesh, checked->flow());
  } catch (const sdflow::Error&) {
    return 0; // a mesh the scheme cannot use, refused with its reason before step 1
  }
  sdflow::SurfaceDiffusion& flow = *made;
  try {
    while (!flow.finished())
      flow.step();
    sdflow::check_geometry(flow.mesh(), "the surface after two steps");
  } catch (const sdflow::SolverFailure& e) {
    if (std::string_view(e.what()).find("re-triangulation after step") != std::string_view::npos)
      finding(e.what());
  } catch (const sdflow::InvalidMesh& e) {
    finding(e.what());
  } catch (const sdflow::Error&) {
  }
  return 0;
}
