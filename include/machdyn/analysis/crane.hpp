#pragma once
/// @file
/// The crane analysis (docs/crane-factors.md): runs the dynamic-factor cases of EN 13001-2 on a
/// model with a `crane:` section (Model::crane) and puts each simulated factor beside the standard's
/// value (analysis/crane_standard.hpp). Every case is an ordinary simulate() run of a copy of the
/// model with its start changed; nothing about the physics is written here.
///
/// Cases (each runs only when the section names what it needs):
///   φ2  hoisting a grounded load: the load rests on its stop, the rope as the model gives it (slack
///       or taut); the hoist drive (the free group of bodies behind the rope's first end, through
///       springs, ideal and lossy gears; a body with prescribed motion in it runs at constant speed)
///       starts in rigid motion with the rope's end at the characteristic speed vh of the drive class
///       (crane::characteristic_hoisting_speed); HD5 (vh = 0) runs the model's own drive from its own
///       start. Simulated φ2 = max rope force / (m g) of the load; a run that never lifts the load
///       (the rope's maximum below m g) is an InputError.
///   Every case: an extreme at t = t_end gets a warning (CraneFactorRow::warning).
///   φ3  sudden release of Δm: the load hangs at rest in static equilibrium (analysis/equilibrium.hpp;
///       its ground stop removed, the rope's first body held by a holding brake that never slips, the
///       drive's other loads as the model gives them at t = 0); at t = 0 of the case its mass and weight
///       drop to m − Δm, positions and velocities continuous (the run restarts with the changed mass).
///       Simulated φ3 = min rope force / (m g).
///   φ5  drive forces: the model's own run; per named drive link its dynamic factor k_d = peak /
///       quasi-static load (analysis/simulate.hpp), against the range of the kind of force change.
///   φ7  buffers: the model's own run; the peak buffer force over the peak of the rigid-body model (the
///       buffer body's free group lumped into one mass M = Σ m_i (r_i/r_b)² at the group's momentum
///       speed at first contact into the same buffer, no other loads); a run that never reaches the
///       buffer is an InputError. ξb of the buffer from its characteristic
///       (linear spring: ∫F dx / (F_max x_max) = 1/2; damping is not counted), φ7 from ξb.
/// Margin: the standard's value minus the simulated one for φ2, φ5 (upper end of the range) and φ7;
/// the simulated minus the standard's for φ3 (a lower φ3 is the worse case). Positive: the
/// standard's value is on the safe side of the simulation.
///
/// Errors of a model loaded with a load case (Model::load_case) name the case.
/// Throws InputError (located at the `crane:` section's elements) when the model has no `crane:`
/// section or a case's model is not what it needs (the hoist drive tied to the ground, a load without
/// a stop for φ2); SolverError from the runs.

#include <limits>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// "No such number" in a CraneFactorRow field (NaN).
inline constexpr double kCraneNone = std::numeric_limits<double>::quiet_NaN();

/// One line of the crane table.
struct CraneFactorRow {
  std::string factor;        ///< "phi2", "phi3", "phi5", "phi7"
  std::string case_name;     ///< e.g. "hoisting HC2/HD1 at vh = 0.5 m/s", "drive link c1"
  double simulated = 0.0;    ///< the factor from the simulation (NaN: not defined, see note)
  double standard_lo = 0.0;  ///< the standard's value, or the lower end of its range
  double standard_hi = 0.0;  ///< = standard_lo for a single value
  std::string clause;        ///< where the standard's value comes from
  double margin = 0.0;       ///< see the file comment
  std::string note;          ///< the inputs of the case (vh, Δm, ξb, peak force, time of the peak)
  /// The factor's time history on the run's output grid: the link load over the case's reference
  /// (m g for φ2 and φ3, the quasi-static load at the peak for φ5, the rigid-body peak for φ7).
  /// Empty when the case was not simulated.
  std::vector<double> t, history;
  // The numbers of the note as fields (NaN where the row has none; crane.json):
  double extreme = kCraneNone;    ///< the link load's extreme the factor is taken from, N (N·m for φ5)
  double t_extreme = kCraneNone;  ///< its time, s
  /// the case's reference the extreme is divided by: m g (φ2, φ3), the quasi-static load at the peak
  /// (φ5), the rigid-body peak force (φ7)
  double reference = kCraneNone;
  double vh = kCraneNone;         ///< φ2: the characteristic hoisting speed the case ran at, m/s
  double xi_b = kCraneNone;       ///< φ7: the buffer's energy-absorption ratio ξb
  double stroke = kCraneNone;     ///< φ7: the largest buffer stroke of the run s_max, m (rad)
  double contact_speed = kCraneNone;  ///< φ7: the rigid-body reference's speed at first contact, m/s (rad/s)
  double t_contact = kCraneNone;  ///< φ7: the time of first contact with the buffer, s
  /// A warning about the number: its extreme lies at the end of the run (it may not be the extreme
  /// of the case: a longer run may find a larger one). Empty when none.
  std::string warning;
};

struct CraneReport {
  std::string model;
  std::string load_case;  ///< the file's load case the analysis ran (Model::load_case), or empty
  std::vector<CraneFactorRow> rows;
};

/// Runs every case the `crane:` section of `m` enables (see above).
CraneReport crane_analysis(const Model& m);
/// The same with one φ2 row per hoist drive class in `drive_classes` (1…5 for HD1…HD5, in that
/// order; empty: the section's own class): the crane's main hoist in each drive class. A class
/// that hoists at the creep speed (HD2, HD3) without `creep_speed` gives a row without a
/// simulation that says so. Throws std::invalid_argument for a class outside 1…5.
CraneReport crane_analysis(const Model& m, const std::vector<int>& drive_classes);

/// One point of φ2 over the hoisting speed: the φ2 case run at vh beside the standard's line.
struct Phi2Point {
  double vh = 0.0;         ///< m/s
  double simulated = 0.0;  ///< max rope force / (m g)
  double standard = 0.0;   ///< φ2,min + β2 vh of the section's hoisting class and drive class
};
/// φ2(vh) for each speed in `speeds` (m/s, each > 0; std::invalid_argument otherwise): the curve
/// of this drive beside the standard's straight line (docs/crane-factors.md). Needs `load`, `rope`.
std::vector<Phi2Point> phi2_sweep(const Model& m, const std::vector<double>& speeds);

/// The φ2 case's model: a copy of `m` whose hoist drive starts in rigid motion with the rope's end
/// at `vh` (m/s) and the load as given (on its stop). Exposed for tests and sweeps.
Model phi2_case_model(const Model& m, double vh);
/// The φ3 case's model: the hanging equilibrium of `m` with the load's mass (and weight) reduced by
/// `released_mass` (kg) at t = 0.
Model phi3_case_model(const Model& m, double released_mass);
/// The φ3 case released during a run (CraneSpec::release_time t_r ≥ 0): the load loses
/// `released_mass` at t_r (a Release of the model, model.hpp). It hangs in equilibrium with the drum
/// held, as phi3_case_model's start, or, with release_hoisting, it is hoisted as the φ2 case at
/// vh,max (phi2_case_model). Its run's extremes count from t_r (SimulateOptions::extremes_from).
/// Both φ3 cases drop the model's own `releases:`: the case's release is the one it is about.
Model phi3_release_case_model(const Model& m, double released_mass, double release_time);

}  // namespace machdyn
