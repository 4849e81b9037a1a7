#pragma once
//! \file validate.h
//! \brief Turning a polygon soup into a valid oriented mesh, with precise findings.
//!
//! Errors (throw InvalidMesh, listing every problem found with its element and line):
//! `empty-mesh`, `non-finite-coordinate`, `face-too-few-vertices`, `face-index-out-of-range`,
//! `face-repeated-index`, `zero-area-face` (also corners at one point after merging),
//! `duplicate-vertex`, `non-manifold-edge`, `non-manifold-vertex`, `inconsistent-orientation`,
//! `coordinate-too-large` (beyond ±1e60: areas and normals would overflow), `self-intersecting-face`
//! (a polygon whose outline crosses itself, a bow-tie), `zero-volume-component` (a closed component
//! that bounds no body: flat, folded onto itself). Warnings (the mesh is repaired): `polygon-triangulated`,
//! `isolated-vertex` (removed). Information: `orientation-flipped` (a closed component had inward
//! normals: normals point out of the material, so a cavity, enclosed by an odd number of other
//! components, an open one closed by the cap over its boundary, has a negative signed volume;
//! components that cross each other are bodies that overlap), `duplicate-vertices-merged` (STL), `has-boundary`.
//!
//! Messages name the source, the element (vertex or face index, 0-based in the file's order, a
//! face being one polygon of the file) and its line when known, e.g.
//! `bad.off:14: face 3 uses vertex 12, but there are only 8 vertices`.

#include "sdflow/errors.h"
#include "sdflow/io/soup.h"
#include "sdflow/mesh.h"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sdflow {

enum class Severity { info, warning, error };

//! The severity's name as reports print it: "info", "warning" or "error".
const char* severity_name(Severity severity);

//! One validation finding: a stable code (documented above) and a human message.
struct Finding {
  Severity severity = Severity::info;
  std::string code;
  std::string message;
};

//! The InvalidMesh thrown by validation: what() lists the errors (capped at about 20 lines),
//! findings() holds every one of them with its code.
class MeshValidationError : public InvalidMesh {
public:
  MeshValidationError(const std::string& message, std::vector<Finding> findings)
      : InvalidMesh(message), findings_(std::move(findings))
  {
  }
  const std::vector<Finding>& findings() const { return findings_; }

private:
  std::vector<Finding> findings_;
};

//! How a soup becomes a mesh.
struct BuildOptions {
  //! Flip closed components whose signed volume is negative (docs/design.md §1).
  bool orient_outward = true;
  //! Merge vertices with bit-identical coordinates instead of reporting them (STL stores no
  //! shared vertices, so its reader turns this on).
  bool merge_duplicate_vertices = false;
  //! A triangle is degenerate when its area is below this fraction of its longest edge squared.
  double zero_area_tolerance = 1e-12;
};

//! A valid mesh and what was found (and repaired) on the way.
struct BuiltMesh {
  Mesh mesh;
  std::vector<Finding> findings;
};

//! True when triangle abc's area is at most `tolerance` times its longest edge squared: the test
//! of `zero-area-face` (BuildOptions::zero_area_tolerance).
bool has_zero_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double tolerance);

//! Validate `soup` and build the mesh; `source` names it in messages (usually the file path).
//! Throws InvalidMesh when any error-level finding exists, with all of them in the message.
BuiltMesh build_mesh(const PolygonSoup& soup, std::string_view source, const BuildOptions& options = {});

//! Check a mesh built in memory: finite coordinates and no zero-area triangles.
//! Throws MeshValidationError (an InvalidMesh) naming the first offending vertex or face;
//! `what` prefixes the message.
void check_geometry(const Mesh& mesh, std::string_view what, double zero_area_tolerance = 1e-12);

} // namespace sdflow
