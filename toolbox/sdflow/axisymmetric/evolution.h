#pragma once
//! \file evolution.h
//! \brief Surface diffusion of axisymmetric bodies through their pinch-offs (diffusion_step with
//! adaptive time steps and node redistribution), with the events the exact flow has: a neck
//! pinching off (an open curve's interior node reaching the axis) or a torus's hole sealing (a
//! closed curve reaching it). Near such a singularity the neck radius goes as (t* − t)^{1/4}
//! (Bernoff, Bertozzi & Witelski 1998), so t* is extrapolated by fitting r⁴ linearly in t.

#include "sdflow/axisymmetric/curve.h"

#include <functional>
#include <limits>
#include <vector>

namespace sdflow::axisymmetric {

enum class EventKind { pinch_off, seal };

struct Event {
  EventKind kind = EventKind::pinch_off;
  double time = 0;              //!< when the neck radius fell below the stop radius
  //! t* from the fit of r⁴ = C (t* − t), and, with EvolutionOptions::richardson, also
  //! extrapolated in the time step: 2 t*(δ/2) − t*(δ) (the time error is first order in δ)
  double extrapolated_time = 0;
  double z = 0;                 //!< where on the axis
};

//! The state after each accepted step, for observers and the time series.
struct Sample {
  double time = 0;
  double area = 0;         //!< summed over the bodies
  double volume = 0;       //!< summed over the bodies
  double neck_radius = 0;  //!< smallest neck over the bodies (infinity when none has a neck)
  int bodies = 0;
  long steps = 0;
};

struct EvolutionOptions {
  double end_time = std::numeric_limits<double>::infinity();
  //! Node spacing; 0 in max_length / min_length: 1/100 and 1/20 000 of the largest r of the start.
  Spacing spacing{.max_length = 0, .min_length = 0, .edges_per_radius = 16};
  //! Accuracy of the time steps: each step moves a node by at most this fraction of the local
  //! radius of curvature (time error first order in it).
  double max_displacement = 0.005;
  //! Largest time step (the displacement bound alone lets a small perturbation take large steps).
  double max_tau = std::numeric_limits<double>::infinity();
  //! An event is declared when a neck's radius falls below this fraction of the start's largest r.
  double stop_radius = 0.005;
  //! Evolve the pieces after a pinch-off (to count the bodies), or stop at the first event.
  bool continue_after_event = true;
  //! Run at max_displacement δ and δ/2 and extrapolate the event times (`Event::extrapolated_time`);
  //! the rest of the result is the finer run's.
  bool richardson = true;
  long max_steps = 10'000'000;
  std::function<void(const Sample&)> observer; //!< optional, after every accepted step
};

struct EvolutionResult {
  std::vector<Event> events;          //!< in time order
  std::vector<GeneratingCurve> bodies; //!< at the end (a sealed torus is kept as it was at the seal)
  Sample last;                        //!< the final state
  double initial_volume = 0; //!< of the start at the working spacing (redistributed)
  double initial_area = 0;
};

//! Evolve `start` (checked by check_curve) until `end_time`, or until its first event without
//! `continue_after_event`. Throws InvalidParameter for bad options or curves, SolverFailure when
//! the time step collapses. (The observer sees the finer run only.)
EvolutionResult evolve(const GeneratingCurve& start, const EvolutionOptions& options = {});

} // namespace sdflow::axisymmetric
