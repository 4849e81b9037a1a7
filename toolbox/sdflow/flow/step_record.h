#pragma once
//! \file step_record.h
//! \brief What a flow reports of its steps: each accepted step's record (τ, trials, events, wall
//! time by stage), the measures of the surface it reached, and the notes of its log (a run
//! directory's metrics.csv, timings.csv and events.log).

#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/step_event.h"

#include <string>
#include <vector>

namespace sdflow {

//! A line of a flow's log: a rejected trial, a re-triangulation, a warning, at the step and time
//! where it happened (a run directory keeps them in events.log).
struct FlowNote {
  long step = 0;
  double time = 0;
  std::string text;
  bool warning = false;
  std::string line() const; //!< "step N t=T: text"
};

//! Wall time of one step by stage, in seconds, over all its trials (a run's timings.csv).
struct StepTimes {
  double operators = 0;      //!< N, H, L, M of each new surface (scheme.h, flow_operators)
  double assembly = 0;       //!< M + τβ L M⁻¹ L (solver.h)
  double factorisation = 0;  //!< CHOLMOD's analysis and numeric factorisation
  double solve = 0;          //!< triangular solves, CG, residuals
  double acceptance = 0;     //!< the time-step rule's checks (turned triangles, volumes)
  double retriangulation_check = 0; //!< the hook's look for self-intersections and degraded elements
  RetriangulationResult::Seconds pipeline; //!< the re-triangulation pipeline's stages, when it ran
  double volume_restoration = 0; //!< components given back their volume after re-triangulating
  //! The re-triangulation's work outside the stages above (RetriangulationReport::other_seconds).
  double retriangulation_other = 0;
  //! Seconds counted by two of the stages above at once, as they ran side by side on two threads:
  //! the pipeline's (RetriangulationResult::Seconds::side_by_side) and, for a step whose first
  //! trial was taken ahead, the time that trial ran beside the previous step's look at the surface.
  //! The stages sum to at most total + side_by_side.
  double side_by_side = 0;
  //! The whole step. A step whose first trial was taken ahead counts the part of that trial that
  //! ran after the previous step's look had ended; that step's total leaves it out.
  double total = 0;
  double cpu = 0;            //!< CPU seconds of the whole step, all threads (process_cpu_seconds)
};

//! One accepted step.
struct StepRecord {
  long step = 0;
  double time = 0;
  double tau = 0;
  int rejections = 0;      //!< trials rejected before the accepted one
  int cg_iterations = 0;
  bool factorised = false;
  //! Its first trial ran beside the last step's look at the surface (FlowOptions::look_ahead):
  //! its stage times then overlap that step's, and its `total` leaves them out.
  bool taken_ahead = false;
  //! A start step (time_step.h): τ_s taken on stability alone, the volumes restored after it.
  bool start = false;
  //! What happened besides the step, in order (step_event.h); event_names() joins them as
  //! metrics.csv writes them.
  std::vector<StepEvent> events;
  StepTimes times;
};

//! The measures of one row of metrics.csv (the step, time, τ and event aside).
struct FlowMetrics {
  long vertices = 0, faces = 0;
  int components = 0, genus = 0;
  double area = 0;
  double volume = 0; //!< material volume (material_volume.h): closed by flat caps over boundary loops
  //! Material volume of the components dropped whole as debris so far (RetriangulationReport::
  //! dropped_volume): volume + debris_volume is the material's, which a run conserves.
  double debris_volume = 0;
  double mean_curvature = 0, curvature_deviation_pct = 0; //!< H̃ and δH (measures.h)
  double d1 = 0, d2 = 0;                                  //!< from the reference sphere
  double energy = 0; //!< ∫ γ dA, the value of the flow's surface energy (the area for the isotropic one)
};

} // namespace sdflow
