#pragma once
//! \file initial_curves.h
//! \brief Generating curves of the surfaces the validation uses, sampled densely (redistribution
//! in `evolve` sets the working spacing), and of any profile read from a file.

#include "sdflow/axisymmetric/curve.h"
#include "sdflow/shapes/dumbbell.h"

#include <filesystem>

namespace sdflow::axisymmetric {

//! The unit sphere with its zonal mode of degree l (2 or 3) of amplitude ε: ρ(θ) = 1 + ε P_l(cos θ).
GeneratingCurve sphere_mode(int degree, double amplitude, int nodes = 400);

//! The torus of centre-circle radius R and tube radius r < R about the z axis.
GeneratingCurve torus(double major, double minor, int nodes = 400);

//! A capsule: a cylinder of radius a with hemispherical caps, total length L = ratio · 2a, along z.
GeneratingCurve capsule(double length_ratio, double radius = 1, int nodes = 2000);

//! The dumbbell of shapes/dumbbell.h (its axis is x there, z here).
GeneratingCurve dumbbell(const DumbbellParameters& parameters = {}, int nodes = 2000);

//! A profile from a text file: one "r z" or "r,z" point a line (a header line and # comments
//! allowed). A first point on the axis makes an open curve (the last must be on the axis too), one
//! off it a closed one. Throws IoError (file, line) or InvalidParameter (check_curve).
GeneratingCurve read_profile(const std::filesystem::path& file);

} // namespace sdflow::axisymmetric
