//! The elements the re-triangulation hook calls degraded, and those halfway there that a local
//! remeshing takes along (degraded_elements.h).
#include "sdflow/flow/degraded_elements.h"
#include "sdflow/geometry/form_sum_anisotropy.h"
#include "sdflow/retri/curvature_targets.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>

namespace sdflow {
namespace {

RetriangulationSchedule uniform_schedule(double ell)
{
  RetriangulationSchedule s;
  s.pipeline.edge_length = ell;
  s.pipeline.edges_per_radius = 0; // uniform ℓ: every target is ℓ
  return s;
}

TEST(DegradedElements, an_edge_between_the_bands_is_worn_but_not_degraded)
{
  // ℓ at 0.6 of the icosphere's mean edge: its edges, within ±20% of the mean, are 1.3–2 ℓ: each
  // face has one outside [ℓ/√2, √2·ℓ], and none is outside [ℓ/2, 2ℓ].
  const Mesh mesh = analytic::icosphere(3);
  double mean = 0;
  for (const auto e : mesh.edges())
    mean += mesh.calc_edge_length(e) / static_cast<double>(mesh.n_edges());
  const DegradedElements worn = degraded_elements(mesh, uniform_schedule(0.6 * mean));
  EXPECT_EQ(worn.total(), 0);
  EXPECT_TRUE(worn.faces.empty());
  EXPECT_EQ(worn.worn_faces.size(), mesh.n_faces());
  EXPECT_EQ(worn.targets, std::vector<double>(mesh.n_vertices(), 0.6 * mean));

  const DegradedElements fine = degraded_elements(mesh, uniform_schedule(mean));
  EXPECT_EQ(fine.total(), 0);
  EXPECT_TRUE(fine.worn_faces.empty()) << "a fresh icosphere's edges are within √2 of their mean";
}

TEST(DegradedElements, a_short_edge_marks_its_two_faces_and_they_are_worn_too)
{
  Mesh mesh = analytic::icosphere(3);
  double mean = 0;
  for (const auto e : mesh.edges())
    mean += mesh.calc_edge_length(e) / static_cast<double>(mesh.n_edges());
  const auto v = *mesh.vertices().begin();
  mesh.set_point(v, mesh.point(v) + 0.9 * (mesh.point(*mesh.vv_iter(v)) - mesh.point(v)));
  const DegradedElements d = degraded_elements(mesh, uniform_schedule(mean));
  EXPECT_GE(d.edges, 1);
  EXPECT_GE(d.faces.size(), 2u);
  EXPECT_TRUE(std::includes(d.worn_faces.begin(), d.worn_faces.end(), d.faces.begin(), d.faces.end()));
  EXPECT_GT(d.worn_faces.size(), d.faces.size());
}

TEST(DegradedElements, with_an_anisotropy_edges_are_measured_against_the_weighted_targets)
{
  // The run's look and the pipeline size by the same curvature (curvature_targets.h): the weighted
  // one when the schedule's pipeline carries the energy's γ.
  const std::array<AnisotropyTerm, 1> term{AnisotropyTerm{.g = {1, 1, 4}}};
  const Mesh wulff = analytic::ellipsoid(3, 1, 1, 2);
  RetriangulationSchedule s;
  s.pipeline.edge_length = 0.5;
  const std::vector<double> geometric = degraded_elements(wulff, s).targets;
  s.pipeline.anisotropy = std::make_shared<const FormSumAnisotropy>(term);
  const std::vector<double> weighted = degraded_elements(wulff, s).targets;
  EXPECT_EQ(weighted, curvature_targets(wulff, s.pipeline, s.pipeline.edge_length));
  EXPECT_NE(weighted, geometric);
}

} // namespace
} // namespace sdflow
