//! resolve_self_intersections re-triangulates until nothing crosses, and leaves a clean surface alone.
//! (Not every fold comes out clean within the passes: the level-3 sphere folded the same way still
//! has 53 pairs after 5; the count reported is then the truth, as below.)
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/surface_repair.h"
#include "sdflow/spatial/intersect.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

TEST(ResolveIntersections, a_sphere_pushed_through_itself_comes_out_clean_and_closed)
{
  // The cap above z = 0.2 folded down through the rest of the sphere.
  const Mesh pushed = test::mapped(analytic::icosphere(2), [](const Eigen::Vector3d& p) {
    Eigen::Vector3d q = p;
    if (q.z() > 0.2)
      q.z() = 0.2 - 2.2 * (q.z() - 0.2);
    return q;
  });
  const ResolveResult r = resolve_self_intersections(pushed);
  EXPECT_GT(r.pairs_before, 0u);
  EXPECT_EQ(r.pairs_after, 0u) << ::testing::PrintToString(r.summaries);
  EXPECT_LE(r.summaries.size(), 5u);
  EXPECT_EQ(self_intersections(r.mesh).size(), r.pairs_after);
  for (const ComponentTopology& c : component_topology(r.mesh))
    EXPECT_TRUE(c.closed());
}

TEST(ResolveIntersections, a_clean_surface_is_left_alone)
{
  const Mesh sphere = analytic::icosphere(2);
  const ResolveResult r = resolve_self_intersections(sphere);
  EXPECT_EQ(r.pairs_before, 0u);
  EXPECT_TRUE(r.summaries.empty());
  EXPECT_EQ(r.mesh.n_faces(), sphere.n_faces());
  EXPECT_THROW(resolve_self_intersections(sphere, {.max_passes = 0}), InvalidParameter);
}

} // namespace
} // namespace sdflow
