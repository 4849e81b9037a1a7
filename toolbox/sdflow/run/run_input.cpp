#include "sdflow/run/run_input.h"

#include "sdflow/check/span.h"
#include "sdflow/flow/substrate_boundary.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/limits.h"
#include "sdflow/log.h"
#include "sdflow/retri/input_checks.h"
#include "sdflow/run/coarse_input.h"
#include "sdflow/run/parameter_schema.h"
#include "sdflow/run/resolution_check.h"

#include <fmt/format.h>

#include <optional>
#include <string>

namespace sdflow {
namespace {

//! `key`'s entry: every key the checks name is one of the schema's.
const ParameterEntry& entry(std::string_view key)
{
  const ParameterEntry* e = find_parameter(std::string(key));
  if (!e)
    throw std::logic_error(fmt::format("run_input: {} is not a run parameter", key));
  return *e;
}

std::string flag_setting(std::string_view key, std::string_view value)
{
  const std::string& flag = entry(key).flag;
  return value.empty() ? flag : fmt::format("{} {}", flag, value);
}

//! A keyword argument: `end_time=10`, or in a section `retriangulation={"edge_length": 0.1}`.
std::string keyword_setting(std::string_view key, std::string_view value)
{
  const ParameterEntry& e = entry(key);
  const std::string section = e.section();
  if (section.empty())
    return value.empty() ? e.key : fmt::format("{}={}", e.key, value);
  return value.empty() ? fmt::format("{}[\"{}\"]", section, e.name())
                       : fmt::format("{}={{\"{}\": {}}}", section, e.name(), value);
}

//! A dialog parameter: `Time step τ (Tau) = 0.01`; the scenario key for one the dialog lacks.
std::string dialog_setting(std::string_view key, std::string_view value)
{
  const ParameterEntry& e = entry(key);
  const std::string name = e.meshlab.name.empty() ? e.key : fmt::format("{} ({})", e.meshlab.label, e.meshlab.name);
  return value.empty() ? name : fmt::format("{} = {}", name, value);
}

//! How much finer than its mean edge length a run makes its ℓ by itself to resolve a thin part.
//! Measured on CGAL's data set (docs/robustness.md, 120 s each): at 1.2 times `camel.off` and
//! `couplingdown.off` reach T, and with build 804993c so does `femur.off` at 2.1 times (64 s beside
//! a compilation); at 2.7–3.1 times `dino.off` and `rotor_small.off` do not (wall budget, at 2% and
//! 22% of T: their fins and blades evolve at their own thickness's pace, τ ≈ 10⁻² ℓ⁴), where a
//! refusal at least says what to do. A vertex pulled out into a spike 0.0067 thick on edges of 0.44
//! (tests/data/fuzz_run) asked for 18 times, and its run took 12 GB before it was stopped.
constexpr double kThinPartMaxRefinement = 2.5;

//! The resolution check (resolution_check.h) at the run's ℓ. A part thinner than the finest edge of
//! its sizing is only warned about when the user gave that ℓ. With the automatic ℓ (the mean edge
//! length) the run resolves it: it returns the ℓ that does, when that is at most
//! kThinPartMaxRefinement times finer and the surface re-triangulated to it stays within
//! kCoarseInputMaxVertices (estimated from its area); otherwise the part is refused with that ℓ,
//! which the user may still give.
std::optional<double> resolve_thin_parts(const Mesh& mesh, RetriangulationOptions pipeline, const UserTerms& terms)
{
  const bool given = pipeline.edge_length > 0;
  if (!given)
    pipeline.edge_length = mean_edge_length(mesh);
  if (!(pipeline.edge_length > 0))
    return std::nullopt; // a surface without edges is refused by the checks before this one
  const std::optional<ThinPart> thin = thinnest_unresolved_part(mesh, pipeline);
  if (!thin)
    return std::nullopt;
  const std::string what = describe_thin_part(*thin, pipeline.edge_length, terms);
  const std::string key = terms.name("retriangulation.edge_length");
  if (given) {
    logger().warn("{}; running with the {} given", what, key);
    return std::nullopt;
  }
  const double ell = thin->resolving_edge_length;
  const double vertices = estimated_vertices(surface_area(mesh), ell);
  const double refinement = pipeline.edge_length / ell;
  if (ell > 0 && refinement <= kThinPartMaxRefinement && vertices <= kCoarseInputMaxVertices) {
    logger().info("{}: the run takes that ℓ = {:.2g} (about {:.0f} vertices) instead of the mean edge length {:.4g} "
                  "(give {} to choose another)",
                  what, ell, vertices, pipeline.edge_length, key);
    return ell;
  }
  const std::string why =
      refinement > kThinPartMaxRefinement
          ? fmt::format("{:.3g} times finer than the surface's mean edge, more than a run refines by itself ({:g} "
                        "times)",
                        refinement, kThinPartMaxRefinement)
          : fmt::format("about {:.0f} vertices, more than a run takes by itself ({:.0f})", vertices,
                        kCoarseInputMaxVertices);
  throw InvalidParameter(fmt::format("{}, but that ℓ is {}: give that {} to run at it anyway, or a coarser one", what,
                                     why, key));
}

} // namespace

UserTerms run_input_terms(FrontEnd front_end)
{
  UserTerms terms;
  switch (front_end) {
  case FrontEnd::command_line:
    terms.setting = flag_setting;
    break;
  case FrontEnd::python:
    terms.setting = keyword_setting;
    terms.adaptive = "time_step=\"adaptive\"";
    terms.join = "sdflow.retriangulate(V, F) and run what it returns";
    terms.refine = "refine the surface first with sdflow.remesh(V, F, edge_length={edge_length})";
    terms.uncross = "sdflow.repair(V, F, remove_self_intersections=True) cuts them out and closes the surface "
                    "again (sdflow.intersections(V, F) lists them)";
    terms.merge = "sdflow.repair(V, F, merge_tolerance=...) merges vertices closer than a fraction of the size; "
                  "sdflow.stats(V, F) shows the same finding";
    break;
  case FrontEnd::meshlab:
    terms.setting = dialog_setting;
    terms.adaptive = dialog_setting("time_step", "");
    terms.join = "the filter \"Surface diffusion: re-triangulate\" and run on its result";
    terms.refine = "refine the mesh first with the filter \"Remeshing: Isotropic Explicit Remeshing\" (target "
                   "length {edge_length})";
    terms.uncross = "The filter \"Select Self Intersecting Faces\" shows them; `sdflow repair "
                    "--remove-self-intersections` cuts them out and closes the surface again";
    terms.merge = "the filter \"Merge Close Vertices\" merges vertices closer than a threshold";
    break;
  }
  return terms;
}

SizeLimits run_input_limits(FrontEnd front_end, bool force)
{
  SizeLimits limits{.force = force};
  limits.force_option = front_end == FrontEnd::command_line ? "--force"
                        : front_end == FrontEnd::python     ? "force=True"
                                                            : "";
  return limits;
}

void check_run_input(Mesh& mesh, RunParameters& p, std::string_view source, FrontEnd front_end,
                     const SizeLimits& limits)
{
  const UserTerms terms = run_input_terms(front_end);
  check_count(p.steps, limits.max_steps, terms.name("steps"), limits);
  check_span(mesh, source, terms);
  check_crossings(mesh, source, terms);
  if (p.scheme.boundary == BoundaryCondition::substrate) // in the front end's words, before any refinement
    SubstrateBoundary(p.scheme.substrate).check_surface(mesh, terms);
  if (p.retriangulation.enabled) {
    refine_coarse_input(mesh, p.retriangulation.pipeline, source, terms);
    const double ell = p.retriangulation.pipeline.edge_length;
    check_remeshed_size(mesh, ell,
                        fmt::format("run with {}", terms.setting("retriangulation.edge_length", fmt::format("{}", ell))),
                        limits);
    check_retriangulation_input(mesh, p.retriangulation.pipeline, source, terms);
    if (const std::optional<double> resolving = resolve_thin_parts(mesh, p.retriangulation.pipeline, terms))
      p.retriangulation.pipeline.edge_length = *resolving;
  }
  check_end_time(mesh, p.end_time, p.time_step.mode == TimeStepMode::constant ? p.time_step.tau : 0.0, limits, terms);
}

} // namespace sdflow
