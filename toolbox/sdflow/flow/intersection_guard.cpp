#include "sdflow/flow/intersection_guard.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

namespace sdflow {

SelfIntersectionGuard::SelfIntersectionGuard(const Mesh& mesh) : tracker_(mesh) {}

void SelfIntersectionGuard::check(const Mesh& mesh, long step, double time)
{
  const std::vector<FacePair>& pairs = tracker_.update(mesh);
  if (pairs.empty())
    return;
  throw SolverFailure(fmt::format(
      "step {} (t = {}) makes the surface intersect itself ({} intersecting face pairs, the first faces {} and {}): "
      "a pinch-off, a seal or bodies touching, which only re-triangulation carries the flow through, and it is off; "
      "run with --retriangulate (scenario key retriangulation.enabled = true; MeshLab: Re-triangulate)",
      step, time, pairs.size(), pairs.front().first, pairs.front().second));
}

} // namespace sdflow
