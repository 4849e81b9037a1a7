"""Meshes as numpy arrays: files, validation, repair, statistics, operators and measures, shapes,
and the re-triangulation pipeline with its stages.

V is an n×3 array of reals (float64 C-contiguous arrays are read in place), F an m×3 array of
integer vertex indices (int32 or int64). Results are numpy arrays that own the toolbox's result
through their base object (no copy), and scipy.sparse matrices sharing the toolbox's arrays.
Operators compute on V, F as given (validated, not reoriented: row i is vertex i); the flow, the
statistics and the re-triangulation stages validate and orient them outward as a file is when read.
"""

import math
import os
from typing import NamedTuple

from . import _sdflow


class MeshResult(tuple):
    """(V, F) of a result, which unpacks as ``V, F = result``; `info` holds what the operation
    reported (findings, the stage's statistics), also reachable as ``result.info``."""

    def __new__(cls, V, F, info=None):
        self = super().__new__(cls, (V, F))
        self.info = info if info is not None else {}
        return self

    @property
    def V(self):
        return self[0]

    @property
    def F(self):
        return self[1]

    def __repr__(self):
        return f"MeshResult(V: {self[0].shape}, F: {self[1].shape}, info keys: {sorted(self.info)})"


# -- files and validation -------------------------------------------------------------------------

def read(path):
    """Read a mesh file (OFF, OBJ, PLY ascii/binary, STL ascii/binary, VTP), validated and oriented
    outward as `sdflow` reads it; `.info["findings"]` lists what validation found and repaired."""
    V, F, findings = _sdflow.read(os.fspath(path))
    return MeshResult(V, F, {"findings": findings})


def write(path, V, F, *, binary=False, **vertex_data):
    """Write V, F atomically in the format of the extension (.off .obj .ply .stl .vtp, round-trip
    precision; binary=True for binary PLY/STL), with per-vertex data in .ply and .vtp
    (``write("s.ply", V, F, H=H, N=N)``: 1-D arrays or n×k; PLY names H `quality` and N `nx ny nz`,
    the names MeshLab, PyVista and trimesh read)."""
    _sdflow.write(os.fspath(path), V, F, vertex_data, binary)


def validate(V, F=None):
    """Validation findings (sdflow.Finding: severity, code, message) of V, F or of a mesh file
    (give its path as V); errors are returned, not raised. Codes: README, `sdflow stats`."""
    if F is None and isinstance(V, (str, os.PathLike)):
        return _sdflow.validate_file(os.fspath(V))
    return _sdflow.validate_arrays(V, F)


def stats(V, F=None, *, tetgen=True):
    """What `sdflow stats --json` prints, as a dict with the same keys, for V, F or a mesh file
    (its path as V). tetgen=False skips the TetGen volume cross-check (--no-tetgen)."""
    if F is None and isinstance(V, (str, os.PathLike)):
        return _sdflow.stats_file(os.fspath(V), tetgen)
    return _sdflow.stats_arrays(V, F, tetgen)


def repair(V, F=None, *, merge_tolerance=0.0, remove_self_intersections=False):
    """Make a mesh that validation refuses valid, as `sdflow repair` does, for V, F or a mesh file
    (its path as V; a file may hold polygons, which are triangulated): duplicate vertices merged
    (merge_tolerance: also those closer than this fraction of the bounding-box diagonal, at most
    0.1), degenerate and repeated faces dropped, non-manifold edges and vertices split, faces
    oriented consistently and closed components outward, isolated vertices dropped;
    remove_self_intersections=True then re-triangulates a surface that crosses itself (at most 5
    passes). Returns a MeshResult whose info has the keys of `sdflow repair --json` but `output`
    (`input` for a file only): `repairs` lists {code, count, message} by the code of the finding
    each fixes, `findings` what the repaired mesh still has (e.g. has-boundary). What no repair
    fixes (an index out of range, a non-finite coordinate, no face, a closed component that
    bounds nothing) raises sdflow.InvalidMesh, a ValueError, with the command line's message."""
    if F is None and isinstance(V, (str, os.PathLike)):
        V, F, info = _sdflow.repair_file(os.fspath(V), float(merge_tolerance), bool(remove_self_intersections))
    else:
        V, F, info = _sdflow.repair_arrays(V, F, float(merge_tolerance), bool(remove_self_intersections))
    return MeshResult(V, F, info)


# -- operators and measures -------------------------------------------------------------------------

def normals(V, F, *, boundary="eq8"):
    """Unit vertex normals by eq. (8) (Max's weights), n×3; outward on outward-oriented closed
    components. boundary="equal_weights": the paper's §4.3 rule at boundary vertices."""
    return _sdflow.normals(V, F, boundary)


def mean_curvature(V, F, *, curvature="cotangent", mass="voronoi", boundary="eq8"):
    """Mean curvature per vertex, exactly as a step of the flow computes it (ΔX = 2HN: a sphere of
    radius R has H = −1/R; 0 on boundary vertices).

    curvature: "cotangent" (H = ½ N·ΔX, the flow's default), "normal_integral" (the paper's eq. 9)
    or "normal_integral_angle_sum" (eq. 9 divided by Σα); mass: the areas of the cotangent H,
    "voronoi" or "volume_gradient"; boundary: the normals' rule (see normals)."""
    return _sdflow.mean_curvature(V, F, curvature, mass, boundary)


def cotangent_laplacian(V, F):
    """The symmetric cotangent matrix L of eq. (10), scipy.sparse.csc_matrix (n×n):
    L_ij = (cot β + cot γ)/2, L_ii = −Σ_j L_ij; negative semi-definite, L·1 = 0. Δ = M⁻¹L."""
    return _sdflow.cotangent_laplacian(V, F)


def laplace_beltrami(V, F):
    """Δ = M⁻¹L with M the mixed Voronoi areas, scipy.sparse.csc_matrix (not symmetric)."""
    return _sdflow.laplace_beltrami(V, F)


def vertex_areas(V, F, *, mass="voronoi"):
    """Vertex areas: "voronoi" (mixed Voronoi, Meyer et al. 2003; they sum to the area) or
    "volume_gradient" (N_v·∂V/∂x_v, Surface Evolver's)."""
    return _sdflow.vertex_areas(V, F, mass)


def mass_matrix(V, F, *, mass="voronoi"):
    """M = diag(vertex_areas) as a scipy.sparse.csc_matrix."""
    import scipy.sparse
    return scipy.sparse.diags(vertex_areas(V, F, mass=mass), format="csc")


def largest_principal_curvature(V, F):
    """κ_max = |H| + √max(H² − K, 0) per vertex (cotangent H, angle-defect K)."""
    return _sdflow.largest_principal_curvature(V, F)


class CurvatureDeviation(NamedTuple):
    mean: float           #: H̃ = Σ H_i A_i / Σ A_i
    deviation: float      #: H_dev = Σ |H_i − H̃| A_i / Σ A_i
    deviation_pct: float  #: 100 H_dev / |H̃| (inf when H̃ = 0)


def curvature_deviation(H, areas):
    """H̃ and H_dev (§2.2.4) of per-vertex H with vertex areas (weights)."""
    return CurvatureDeviation(*_sdflow.curvature_deviation(H, areas))


def volume(V, F):
    """Signed enclosed volume by the divergence theorem (positive for outward closed surfaces)."""
    return _sdflow.volume(V, F)


def area(V, F):
    """Total triangle area."""
    return _sdflow.area(V, F)


def component_volumes(V, F):
    """Signed volume of each connected component (in the order of their first faces)."""
    return _sdflow.component_volumes(V, F)


def mean_edge_length(V, F):
    """Mean edge length: the re-triangulation's ℓ when none is given."""
    return _sdflow.mean_edge_length(V, F)


# -- shapes -----------------------------------------------------------------------------------------

def shapes():
    """The catalogue: {name: {"summary": ..., "parameters": {name: (default, description)}}}."""
    return {name: {"summary": summary, "parameters": dict(parameters)}
            for name, summary, parameters in _sdflow.shape_catalogue()}


def shape(name=None, *, vertices=None, edge_length=None, expression=None, box=None, feature_size=0.0,
          iterations=10, edges_per_radius=0.0, grid_cell=0.0, force=False, **parameters):
    """Mesh a catalogue shape (``shape("torus", vertices=15000, major=3, minor=1.5)``) or a formula
    f(x, y, z) = 0, negative inside (``shape(expression="x^2+y^2+z^2-1", box=(-2, -2, -2, 2, 2, 2),
    edge_length=0.1)``), as `sdflow shape` does: give vertices or edge_length. Parameters spelt with
    hyphens take underscores (``shape("packing", count=20, min_distance=2.4, edge_length=0.15)``). Returns a MeshResult
    (closed components oriented outward) whose info has the edge length used and angle statistics."""
    V, F, info = _sdflow.mesh_shape(name or "", {k.replace("_", "-"): float(v) for k, v in parameters.items()},
                                    expression or "",
                                    [float(b) for b in box] if box is not None else [], float(feature_size),
                                    float(edge_length or 0), int(vertices or 0), int(iterations),
                                    float(edges_per_radius), float(grid_cell), bool(force))
    return MeshResult(V, F, info)


# -- the re-triangulation pipeline and its stages ---------------------------------------------------------

def retriangulate(V, F, *, edge_length=0.0, iterations=3, edges_per_radius=4.0, min_edge_fraction=0.25,
                  curved_projection=True, always_rebuild=False, neighbours=18, fill_holes=True,
                  max_hole_length=0.0, min_component_faces=16, min_component_thickness=0.01, force=False):
    """The whole re-triangulation of docs/design.md §3 (retri/pipeline.h), as `sdflow retriangulate`:
    merge of intersecting components, remeshing, removal of intersecting faces, jet normals,
    reconstruction, hole filling, debris. edge_length 0: the input's mean. info has the keys of
    `sdflow retriangulate --json`."""
    V, F, info = _sdflow.retriangulate(V, F, edge_length, iterations, edges_per_radius, min_edge_fraction,
                                       curved_projection, always_rebuild, neighbours, fill_holes, max_hole_length,
                                       min_component_faces, min_component_thickness, force)
    return MeshResult(V, F, info)


def remesh(V, F, *, edge_length=0.0, iterations=10, keep_boundary=False, curved_projection=False, force=False):
    """Isotropic remeshing (Botsch & Kobbelt 2004) onto the input surface; edge_length 0: the mean.
    keep_boundary: boundary vertices and edges stay exactly as they are, and the vertices beside them
    then settle, which evens out the edges to the boundary (`sdflow remesh --keep-boundary`)."""
    V, F, info = _sdflow.remesh(V, F, edge_length, iterations, keep_boundary, curved_projection, force)
    return MeshResult(V, F, info)


def intersections(V, F, V2=None, F2=None):
    """Intersecting face pairs (k×2 int32), exactly decided: of one surface (first ≤ second; (f, f)
    marks a degenerate face), or between two (face of the first, face of the second)."""
    return _sdflow.intersections(V, F, V2, F2)


def remove_intersections(V, F):
    """The surface without its intersecting faces and the vertices they leave alone (stage 2)."""
    V, F, info = _sdflow.remove_intersections(V, F)
    return MeshResult(V, F, info)


def point_normals(points, *, neighbours=18, agreement_deg=40.0, min_agreement=0.5):
    """Oriented normals by jet fitting and MST orientation (stage 3): (points kept, normals,
    source index of each kept point, removed indices)."""
    return _sdflow.point_normals(points, neighbours, agreement_deg, min_agreement)


def reconstruct(points, normals, *, beta_deg=0.52 * 180 / math.pi, radius_ratio=5.0,
                normal_deviation_deg=60.0):
    """Advancing-front reconstruction from oriented points (stage 4)."""
    V, F, info = _sdflow.reconstruct(points, normals, beta_deg, radius_ratio, normal_deviation_deg)
    return MeshResult(V, F, info)


def fill_holes(V, F, *, max_loop_length=math.inf, stages="fair", weights="cotangent"):
    """Fill boundary loops (Liepa 2003; stage 5): stages "triangulate", "refine" or "fair"."""
    V, F, info = _sdflow.fill_holes(V, F, max_loop_length, stages, weights)
    return MeshResult(V, F, info)


def components(V, F, *, min_faces=1, keep_largest=0, min_thickness=0.0, split=False):
    """Keep the components with at least min_faces triangles (then the keep_largest largest); with
    split=True a list of (V, F), one per kept component, largest first."""
    result = _sdflow.components(V, F, min_faces, keep_largest, min_thickness, split)
    if split:
        return [MeshResult(v, f) for v, f in result]
    return MeshResult(*result)


def union(V1, F1, V2, F2):
    """The boundary of the union of two surfaces (a surface with a boundary keeps it)."""
    V, F, info = _sdflow.union(V1, F1, V2, F2)
    return MeshResult(V, F, info)
