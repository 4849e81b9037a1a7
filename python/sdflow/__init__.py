"""sdflow: surface diffusion flow (V_N = −ΔH) on triangle meshes, with numpy in and out.

    import sdflow
    V, F = sdflow.shape("torus", vertices=5000, major=3, minor=1.5)
    flow = sdflow.Flow(V, F)                 # re-triangulation on, adaptive τ, cotangent H
    flow.advance(5.0, progress=True)         # through the seal of the hole
    V, F = flow.V, flow.F

See docs/python.md. Conventions (docs/design.md §1): closed components oriented outward, a
sphere of radius R has H = −1/R, Δ = M⁻¹L with L negative semi-definite.
"""

from ._sdflow import (EnvironmentFailure, Error, Finding, InvalidMesh, InvalidParameter, IoError,
                      NumericalError, metrics_header)
from .flow import (Cleaned, Contact, Event, Fallback, Flow, Merged, Refused, Rejected, Remeshed, RunResult, Start,
                   State, Step, Split, Surgery, Touchdown, resume, run)
from .mesh import (CurvatureDeviation, MeshResult, area, component_volumes, components, cotangent_laplacian,
                   curvature_deviation, fill_holes, intersections, laplace_beltrami, largest_principal_curvature,
                   mass_matrix, mean_curvature, mean_edge_length, normals, point_normals, read, reconstruct,
                   remesh, remove_intersections, repair, retriangulate, shape, shapes, stats, union, validate,
                   vertex_areas, volume, write)

#: The toolbox's name for NumericalError (errors.h).
SolverFailure = NumericalError

__version__ = "0.1.0"


def log_to_stderr(level="info"):
    """Send the toolbox's log (re-triangulations, rejected steps, warnings) to stderr, as the
    command line does; level "debug", "info", "warn", "error" or "off"."""
    from . import _sdflow
    _sdflow.log_to_stderr(level)
