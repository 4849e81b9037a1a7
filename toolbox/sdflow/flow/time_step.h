#pragma once
//! \file time_step.h
//! \brief Time-step control: constant τ, step-range schedules like the paper's Tables 1–3, and
//! automatic adaptive τ (the default).
//!
//! Adaptive rule (after each solve, before accepting the step):
//! - d = max_v τ|w_v| / h_v, the normal displacement relative to the mean length h_v of the edges
//!   at v. The step is rejected if d > max_displacement, and the next τ is scaled by
//!   min(growth, safety · max_displacement / d), at least by `shrink` on a rejection.
//!   So τ grows by at most `growth` per step while the surface is calm.
//! - A step is also rejected when a triangle turns over (its normal reverses), a position is not
//!   finite, or a component's material volume (material_volume.h) changes by more than `max_volume_change`
//!   (relative): τ is then multiplied by `shrink`.
//! - A step is rejected, τ multiplied by `shrink`, when it raises the energy the flow lowers,
//!   W_h = Σ_f γ(a_f) plus the boundary's term (the substrate's −σ A_base; flow_energy, scheme.h),
//!   by more than kEnergyRoundOff relative: the semi-discrete flow lowers it (docs/method.md,
//!   "Substrate", "Energy"), so a rise is the time step's and falls at least like τ². The volume
//!   restoration after the step is not part of the trial. Where the rule finds a rise that does not
//!   fall so (the next trial, of a smaller τ, still rises, by more than kEnergyRateShare · (τ'/τ)^1.5
//!   of it, above round-off or not: a rate, which a region the mesh no longer resolves can have, near
//!   a pinch), it stands aside for that step: the trial is accepted, the next step goes on from the
//!   τ the first trial would have proposed had the energy not risen, and the run says so
//!   (energy_stood_aside). Near the break-up of a ridge on a substrate the rule otherwise held τ at
//!   3·10⁻¹² to 5·10⁻¹² for tens of thousands of steps, where τ·rate met the round-off bound.
//! - With a `tolerance` ε > 0 (extrapolated steps only, scheme.h): e = max_v |X_{τ/2∘τ/2} − X_τ|_v / h_v,
//!   the local error estimate that step doubling provides (Hairer, Nørsett, Wanner I §II.4), must
//!   be ≤ ε, and the next τ is also scaled by at most safety · √(ε / e) (the estimate is O(τ²)).
//! - After `max_rejections` rejections in a row, or when τ would fall below `min_tau`, the run stops
//!   with SolverFailure: the flow cannot be continued stably from this surface.
//! - Triangles that turn over step after step, each step accepted only at a smaller τ, are the
//!   triangulation's fault, not τ's (a sliver whose corner the flow pushes across it): once a trial
//!   turns one over at kTurningCollapse times the τ at which they began (turning_collapsed), the
//!   stepper re-triangulates as for a step no τ makes acceptable (surface_diffusion.h). The τ they
//!   began at is forgotten when an accepted step's τ is back at it. On the 27-sphere packing
//!   (samples/compact_27.toml) τ otherwise crept from 10⁻⁶ to 10⁻¹⁴ over 26 steps, one triangle
//!   turning over in each, before a step failed and the re-triangulation came.
//! Start phase (adaptive steps of a run's first `start_steps` steps): while the surface has a vertex
//! whose curvature varies faster than its edges resolve, |ΔH|_v h_v³ > kUnresolvedVariation (noise,
//! a sharp edge, a crease, a sliver), that vertex, not the scales the run resolves, would set τ. The
//! step is then a backward-Euler step (β = kStartBeta = 1, scheme.h) of τ_s = start_damping · (ℓ/π)⁴
//! for the run's edge length ℓ (which damps the wavelength 2ℓ, the shortest a mesh of edge ℓ
//! carries, by 1 + start_damping); the volume of each closed component is restored after it. Among
//! the run's first steps a start step is accepted unless a triangle turns over or a position is not
//! finite: no displacement bound applies (the phase lasts at most start_steps · τ_s, about 0.3 ℓ⁴:
//! docs/method.md says what that gives up). The start step on a new triangulation mid-run must also
//! keep the displacement bound at the resolved vertices. A rejected start trial is retried, up to
//! kStartRetries times and not below the automatic τ, at a τ shrunk as that bound asks, or by
//! kStartShrink when the resolved vertices kept it.
//! The rule above takes over at the first step whose surface is resolved everywhere, or after
//! start_steps steps (is_start_step), from the last start step's τ. With start_steps > 0, the first
//! step on each new triangulation (after a re-triangulation) is a start step too when its surface
//! has unresolved vertices, of at most the τ the rule would try: fresh triangles carry variation
//! below the mesh's scale, which β = ½ flips rather than damps, so that τ would otherwise collapse.
//! With constant τ or a schedule, a step that turns a triangle over, produces a non-finite
//! position or changes a component's material volume (closed, or open with its boundary) by more
//! than `max_volume_change` (the adaptive bound: such a step is no approximation of the flow, which
//! keeps volumes) stops the run at once (SolverFailure; TimeStepTooLarge for the volume, which says
//! by how much τ is too large), unless `schedule_retries` > 0: then a schedule's step is tried again
//! with τ halved, up to that many times in a row, and the next step returns to
//! the table's τ (the step count follows the table; the time falls behind it by what was halved).
//! A table step that still fails (after a re-triangulation, surface_diffusion.h) for a reason other
//! than the volume bound is covered by
//! adaptive steps instead (fall_back_to_adaptive): they advance the time by exactly the table's τ
//! for that step, and the adaptive steps go on through the following table steps while the adaptive
//! rule's τ stays below the table's; the table then resumes where its count stands.

#include "sdflow/errors.h"
#include "sdflow/mesh.h"
#include "sdflow/parameter_range.h"

#include <Eigen/Core>

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sdflow {

enum class TimeStepMode { constant, schedule, adaptive };

//! Steps first..last (1-based, inclusive) use τ.
struct ScheduleEntry {
  long first_step = 1;
  long last_step = 1;
  double tau = 0;
};

//! A τ table sorted by step, covering 1..last without gaps or overlaps; steps past the last entry
//! keep its τ.
class TauSchedule {
public:
  TauSchedule() = default;
  //! Throws InvalidParameter on an empty table, gaps, overlaps, reversed ranges or τ ≤ 0.
  explicit TauSchedule(std::vector<ScheduleEntry> entries);
  double tau_for_step(long step) const;
  const std::vector<ScheduleEntry>& entries() const { return entries_; }

private:
  std::vector<ScheduleEntry> entries_;
};

//! Read a schedule file: CSV lines `first_step,last_step,tau` (a header line and `#` comments
//! allowed), or TOML (`.toml`) with `schedule = [[first, last, tau], ...]`. The paper's tables
//! start at step 0; step 0 is read as step 1. Throws IoError (file, line) or InvalidParameter.
TauSchedule read_schedule(const std::filesystem::path& file);

struct AdaptiveOptions {
  double initial_tau = 0;          //!< 0: automatic, from the explicit velocity ΔH and the edge lengths
  double max_displacement = 0.05;  //!< bound on max τ|w|/h per step
  double safety = 0.8;             //!< aim below the bound when predicting the next τ
  double growth = 1.25;            //!< largest growth factor of τ per accepted step
  double shrink = 0.5;             //!< factor applied to τ on a rejection
  double max_volume_change = 1e-3; //!< relative change of a component's material volume per step
  double min_tau = 1e-14;          //!< below this τ the run is declared unstable
  double max_tau = std::numeric_limits<double>::infinity();
  int max_rejections = 25;         //!< rejections in a row before the run is declared unstable
  //! ε, the bound on the local error estimate of extrapolated steps relative to the local edge
  //! length (0: off, the displacement bound alone sets τ).
  double tolerance = 0;
  //! Start phase (the rule at the top): at most this many of a run's first steps (0: none).
  int start_steps = 3;
  //! Start phase: τ_s · (π/ℓ)⁴, the damping of the wavelength 2ℓ per start step (> 0).
  double start_damping = 10;
};

struct TimeStepOptions {
  TimeStepMode mode = TimeStepMode::adaptive;
  double tau = 0;                  //!< the constant τ (mode constant)
  TauSchedule schedule;            //!< mode schedule
  std::filesystem::path schedule_file; //!< where the schedule came from (recorded in run.toml)
  int schedule_retries = 0;        //!< halvings of a schedule's τ allowed for one step (0: stop at once)
  AdaptiveOptions adaptive;
};

//! The allowed values of TimeStepOptions, stated here only: validate_time_step_options (and so
//! TimeStepController) checks them and the run schema's `tau`, `schedule_retries` and `adaptive.*`
//! entries take them (run/schema_time_step.cpp).
struct TimeStepRanges {
  ParameterRange tau{.min = 0, .min_open = true};                                          //!< constant τ
  ParameterRange schedule_retries{.min = 0, .max = 60};                                    //!< halvings
  ParameterRange initial_tau{.min = 0};                                                    //!< 0: automatic
  ParameterRange max_displacement{.min = 0, .min_open = true, .infinite_allowed = true};   //!< ∞: no bound
  ParameterRange growth{.min = 1, .infinite_allowed = true};                               //!< ∞: no bound
  ParameterRange shrink{.min = 0, .max = 1, .min_open = true, .max_open = true};
  ParameterRange safety{.min = 0, .max = 1, .min_open = true};
  ParameterRange max_volume_change{.min = 0, .min_open = true, .infinite_allowed = true};  //!< ∞: no bound
  ParameterRange min_tau{.min = 0, .min_open = true};
  ParameterRange max_tau{.min = 0, .min_open = true, .infinite_allowed = true};            //!< ∞: none
  ParameterRange max_rejections{.min = 1};
  ParameterRange start_steps{.min = 0};                                                    //!< 0: none
  ParameterRange start_damping{.min = 0, .min_open = true};
  ParameterRange tolerance{.min = 0};                                                      //!< 0: off
};
inline constexpr TimeStepRanges time_step_ranges{};

//! Throws InvalidParameter, naming the scenario key, for options out of time_step_ranges or
//! inconsistent: τ of the constant mode; the table and its retries of the schedule mode, whose
//! failed steps adaptive steps cover; the adaptive rule's options in those two modes, with
//! min_tau ≤ max_tau; the tolerance in every mode.
void validate_time_step_options(const TimeStepOptions& options);

//! A constant or tabled τ too large for the scheme: its step broke the volume bound, so it is no
//! approximation of the flow. Neither a re-triangulation nor adaptive steps in its place change that.
class TimeStepTooLarge : public SolverFailure {
public:
  using SolverFailure::SolverFailure;
};

//! No τ makes the step acceptable: the last trial failed at `vertices` (the corners of the triangles
//! it turned over, the vertices it moved beyond the displacement bound), where a re-triangulation
//! of the surface the step starts from can begin.
class UnacceptableStep : public SolverFailure {
public:
  UnacceptableStep(const std::string& what, std::vector<int> vertices)
      : SolverFailure(what), vertices(std::move(vertices))
  {
  }
  std::vector<int> vertices;
};

//! Adaptive steps: triangles kept turning over while τ fell by kTurningCollapse (the rule at the
//! top), which calls for a re-triangulation rather than a smaller τ.
class TrianglesTurning : public UnacceptableStep {
public:
  using UnacceptableStep::UnacceptableStep;
};

//! The relative rise of W_h in a trial that the adaptive rule takes for round-off: the sum over
//! the faces of a 10⁵-face surface rounds at about 10⁻¹⁴.
inline constexpr double kEnergyRoundOff = 1e-12;
//! A rise that falls less than this share of (τ'/τ)^1.5 when τ falls to τ' is a rate, not the time
//! step's (which falls like τ'² or faster).
inline constexpr double kEnergyRateShare = 1.0;

//! Why a trial step was not accepted.
struct StepCheck {
  double displacement_ratio = 0;   //!< max τ|w|/h
  int inverted_triangles = 0;
  bool non_finite = false;
  double volume_change = 0;        //!< largest relative material-volume change of a component
  double error_estimate = 0;       //!< max_v |X_{τ/2∘τ/2} − X_τ|_v / h_v of an extrapolated step (else 0)
  double energy_change = 0;        //!< (W_h after − W_h before) / |W_h before|
  bool displacement_exceeded = false;
  bool volume_exceeded = false;
  bool error_exceeded = false;
  bool energy_rose = false;        //!< adaptive mode: energy_change > kEnergyRoundOff
  //! Steps of a constant or tabled τ that broke the volume bound: the τ the adaptive rule would
  //! start with on this surface (automatic_tau), to say how much smaller τ should be (0: unknown).
  double adaptive_tau = 0;
  //! Where the trial failed: the corners of the triangles it turned over and, in adaptive mode,
  //! the vertices it moved beyond the displacement bound (ascending, each once).
  std::vector<int> failed_vertices;
  bool failed() const
  {
    return non_finite || inverted_triangles > 0 || displacement_exceeded || volume_exceeded || error_exceeded ||
           energy_rose;
  }
  std::string describe() const;
};

//! A trial step's motion, as the acceptance checks see it.
struct TrialMotion {
  double tau = 0;
  const VertexVectors& now;           //!< positions before the step
  const VertexVectors& next;          //!< positions after it
  const Eigen::VectorXd& w;           //!< the solved normal speed (|τw| is each vertex's displacement)
  const VertexVectors& error;         //!< the extrapolated step's error estimate (0 rows: none)
  const FaceIndices& triangles;
  const Eigen::VectorXd& edge_lengths; //!< mean length of the edges at each vertex (h_v)
  double volume_change = 0;           //!< largest relative material-volume change of a component
  double energy_change = 0;           //!< relative change of W_h (flow_energy)
};

//! The checks of the rule above on one trial: finite positions, no triangle turned over, the
//! volume bound of `bounds` in every mode, and when `adaptive` the displacement and error bounds
//! and no rise of the energy.
StepCheck check_trial(const TrialMotion& trial, const AdaptiveOptions& bounds, bool adaptive);

//! τ of the first adaptive step when no initial τ is given: the explicit speed |ΔH| bounds the
//! semi-implicit one (the inverse of I + τβΔ² is a contraction), so safety · max_displacement ·
//! min_v h_v / |ΔH|_v meets the displacement bound at once; vertices `held` in place do not count.
//! A surface at rest gets h⁴, the bi-Laplacian's time scale for the mean edge length h.
double automatic_tau(const Eigen::VectorXd& explicit_speed, const std::vector<bool>& held,
                     const Eigen::VectorXd& edge_lengths, const AdaptiveOptions& options);

//! |ΔH|_v h_v³ above which the curvature at v varies faster than its edges resolve: on a smooth
//! surface with n edges per radius of curvature r (h = r/n) it is about 1/n³; noise of amplitude a
//! gives about 100 a/h, a crease of angle θ about θ.
constexpr double kUnresolvedVariation = 1;

//! β of a start step (scheme.h): backward Euler, which damps a mode by 1/(1 + τk⁴) where the
//! scheme's β = ½ would flip the modes it does not resolve in time.
constexpr double kStartBeta = 1;

//! Trials a start step makes before it leaves the step to the adaptive rule.
constexpr int kStartRetries = 6;

//! The factor on a start step's τ when a triangle turned over.
constexpr double kStartShrink = 0.25;

//! Triangles still turning over at this fraction of the τ at which they began (about ten halvings)
//! call for a re-triangulation instead of a smaller τ (the adaptive rule at the top).
constexpr double kTurningCollapse = 1e-3;

//! τ_s = start_damping · (ℓ/π)⁴ of the start phase for the run's edge length ℓ (> 0).
double start_tau(const AdaptiveOptions& options, double edge_length);

//! Per vertex: not `held`, and |ΔH|_v h_v³ ≤ kUnresolvedVariation (explicit_speed = |ΔH|,
//! edge_lengths = h): the curvature there varies no faster than the edges resolve.
std::vector<bool> resolved_vertices(const Eigen::VectorXd& explicit_speed, const std::vector<bool>& held,
                                    const Eigen::VectorXd& edge_lengths);

//! max τ|w_v|/h_v over the `resolved` vertices (0 when there is none).
double resolved_displacement_ratio(double tau, const Eigen::VectorXd& w, const Eigen::VectorXd& edge_lengths,
                                   const std::vector<bool>& resolved);

//! Whether step `step` (1-based) of an adaptive run is a start step: within start_steps, and some
//! vertex not held is not `resolved` (resolved_vertices).
bool is_start_step(const AdaptiveOptions& options, long step, const std::vector<bool>& resolved,
                   const std::vector<bool>& held);

//! The state of the time-step controller between steps (saved in checkpoints).
struct TimeStepState {
  double next_tau = 0;   //!< adaptive steps: τ to try next (0 before the first step)
  int rejections = 0;    //!< rejections in a row
  //! Schedule: steps taken beyond the table's count (adaptive steps that covered a table step);
  //! step n of the flow takes the table's step n − table_lag.
  long table_lag = 0;
  //! Schedule: while adaptive steps cover a table step, the time left of it (0: the table rules).
  double fallback_left = 0;
  //! Adaptive steps: the τ of the trial at which triangles began turning over, in the steps since an
  //! accepted τ was last that large (0: none turned over since).
  double turning_since_tau = 0;
};

//! Decides τ for each trial and whether to accept it.
class TimeStepController {
public:
  //! Throws InvalidParameter for options validate_time_step_options refuses.
  explicit TimeStepController(const TimeStepOptions& options, TimeStepState state = {});

  //! τ for the trial of step `step` (1-based); `automatic_tau` is used by the adaptive mode
  //! before its first step when no initial τ was given. Never past `time_left` (> 0).
  double propose(long step, double automatic_tau, double time_left);

  //! Record the check of the last proposed τ. Returns true if the step is accepted. On a rejection
  //! in adaptive mode the next proposal is smaller; throws SolverFailure when the run is unstable
  //! (any failure in constant or schedule mode, too many rejections or τ < min_tau in adaptive mode).
  bool judge(long step, double tau, const StepCheck& check);

  //! A start step of `tau` was accepted (the start phase at the top): the next adaptive step tries
  //! it again, and the rule above shrinks it as the bounds ask (the automatic τ, from the explicit
  //! speed, would be set again by what the start steps left of the unresolved scales).
  void accept_start_step(double tau);

  //! Whether the next adaptive trial's τ is below kTurningCollapse times the τ at which triangles
  //! began turning over (TimeStepState::turning_since_tau).
  bool turning_collapsed() const;
  //! Forget the τ at which triangles began turning over (the triangulation changed, or could not).
  void forget_turning() { state_.turning_since_tau = 0; }
  //! Whether the last accepted trial raised the energy and was accepted because the rise did not
  //! fall with τ (the energy rule above stood aside), and the rises it saw: the first rejected
  //! trial's τ and rise, then the accepted one's.
  struct EnergyStandAside {
    double rejected_tau = 0, rejected_rise = 0, accepted_tau = 0, accepted_rise = 0;
  };
  const std::optional<EnergyStandAside>& energy_stood_aside() const { return energy_stood_aside_; }

  //! Schedule mode: cover the table's step for flow step `step`, which failed, with adaptive steps
  //! (the rule at the top of this file). Starts from the automatic τ.
  void fall_back_to_adaptive(long step);

  //! The adaptive rule decides the next trial (adaptive mode, or a schedule fallen back to it).
  bool adaptive() const { return options_.mode == TimeStepMode::adaptive || state_.fallback_left > 0; }
  //! The table's step that flow step `step` takes (schedule mode).
  long table_step(long step) const { return step - state_.table_lag; }

  const TimeStepState& state() const { return state_; }
  const TimeStepOptions& options() const { return options_; }

private:
  bool judge_adaptive(long step, double tau, const StepCheck& check);
  std::string too_large(long step, double tau, const StepCheck& check, int retries) const;
  void cover_table_step(long step, double tau);

  TimeStepOptions options_;
  TimeStepState state_;
  //! This step's first trial rejected for the energy alone (τ and rise; τ = 0: none), and the τ it
  //! would have proposed next had the energy not risen.
  double energy_rejected_tau_ = 0, energy_rejected_rise_ = 0, energy_rejected_next_tau_ = 0;
  std::optional<EnergyStandAside> energy_stood_aside_;
};

} // namespace sdflow
