#pragma once
//! \file limits.h
//! \brief Plausibility limits: what a request will produce, estimated before the work, and the
//! refusal (InvalidParameter, with the estimate and what to do) of what will not fit in memory,
//! cannot be meshed, or would run for no purpose. Every check can be overridden (`force`).

#include "sdflow/mesh.h"
#include "sdflow/user_terms.h"

#include <Eigen/Geometry>

#include <string>
#include <string_view>

namespace sdflow {

struct SizeLimits {
  //! Most vertices of one surface: the flow's factorisation and the re-triangulation's point
  //! structures need about `bytes_per_vertex` each, so 20 million already need some 40 GB.
  double max_vertices = 2e7;
  //! Fewest vertices a surface re-triangulated to an edge length may have: the jet normals of the
  //! rebuild fit 18 neighbours, and a closed surface coarser than an icosahedron loses its shape.
  double min_vertices = 20;
  //! Most iterations of remeshing (a few converge: Botsch & Kobbelt 2004 use 5 to 10).
  long max_iterations = 1000;
  //! Most time steps of one run.
  long max_steps = 100'000'000;
  //! Latest end time of a run, in units of D⁴ for the bounding-box diagonal D of its surface.
  //! Surface diffusion relaxes a body of size D long before: the slowest shape mode of a sphere of
  //! radius R decays at the rate 24/R⁴ (Mullins 1957), so D⁴ ≈ 144 R⁴ is some 3500 decay times. A
  //! later end only steps through the equilibrium, with τ held near the displacement bound.
  double max_end_time_scales = 1000;
  //! Memory per vertex of the heaviest verb (measured peak of `run --retriangulate`, rounded up).
  double bytes_per_vertex = 2048;
  //! Skip every check (`--force`).
  bool force = false;
  //! How the user asks for that, in messages ("force=True" in Python); empty: they cannot.
  std::string force_option = "--force";
};

//! Vertices of a triangulation of `area` with edges of about `edge_length`: equilateral triangles
//! of area √3/4 ℓ², and about half as many vertices as triangles on a closed surface.
double estimated_vertices(double area, double edge_length);

//! Vertices of a surface meshed with edges of about `edge_length` inside `box`, before it exists:
//! its area taken as half the box's (a sphere in its bounding cube has 0.52 of it).
double estimated_vertices_in_box(const Eigen::AlignedBox3d& box, double edge_length);

//! Refuse a surface of `vertices` (an estimate) that is larger than the limit or than half this
//! machine's physical memory at `bytes_per_vertex`, or (when `check_minimum`) smaller than
//! `min_vertices`. `what` names the request in the message ("remesh --edge-length 1e-05").
void check_surface_size(double vertices, std::string_view what, const SizeLimits& limits = {},
                        bool check_minimum = true);

//! Check the surface `mesh` becomes when re-triangulated to `edge_length` (the estimate above
//! from its area).
void check_remeshed_size(const Mesh& mesh, double edge_length, std::string_view what, const SizeLimits& limits = {});

//! Refuse a run of `mesh` to `end_time` (finite) later than max_end_time_scales · D⁴, or, with a
//! constant τ (`constant_tau` > 0), one that needs more than max_steps steps to get there; the
//! message names the parameters in `terms`.
void check_end_time(const Mesh& mesh, double end_time, double constant_tau, const SizeLimits& limits = {},
                    const UserTerms& terms = {});

//! ", or --force" in the limits' terms (empty when they cannot be skipped), to end a refusal.
std::string or_force(const SizeLimits& limits);

//! Refuse more than `limit` iterations or steps (`what` names the option).
void check_count(long count, long limit, std::string_view what, const SizeLimits& limits = {});

} // namespace sdflow
