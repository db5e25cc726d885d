#pragma once
/// @file
/// The plots of the papers, each one small function from a result to a plot::Figure (io/plot.hpp);
/// `--plot` renders them with gnuplot (SVG + PNG), `report` draws the same figures with uPlot.
/// A new kind of plot (ω against distance with the limit line of `energy`, the load cyclogram of a
/// travel start-up, ...) is one more function here returning a Figure.

#include <vector>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/gears_output.hpp"
#include "machdyn/io/plot.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// Link loads against time, one curve per link, with the quasi-static value (the particular
/// solution, paper 002 eq. 22: M12*, M23*) of each link as a dashed line in its colour.
/// Links in N (translational) go on the right axis when the chain also has links in N·m.
plot::Figure link_loads_figure(const Model& m, const SimulationResult& r);

/// Body velocities against time (rad/s on the left axis, m/s on the right when both occur).
plot::Figure body_speeds_figure(const Model& m, const SimulationResult& r);

/// The figures `simulate --plot` writes: link loads (when the model has links), body speeds.
std::vector<plot::Figure> simulation_figures(const Model& m, const SimulationResult& r);

/// Elastic mode shapes: amplitude per body (x: the bodies in model order, named), one curve per
/// mode, each scaled to max |φ_i| = 1 and labelled with its natural frequency.
plot::Figure mode_shapes_figure(const Model& m, const Modes& modes);

/// Paper 003 Fig. 1: both pitch curves in mesh position (wheel centre at 0, pinion centre at
/// L_installed), mm, equal scale, with the radial sector boundaries of every tooth.
plot::Figure gears_pitch_figure(const io::GearReport& r);

/// Paper 003 Fig. 2: the theoretical ratio i(φ) of the law and the stepwise ratio Δθ_j/Δφ_j of the
/// synthesized sectors over one big sector, φ in degrees.
plot::Figure gears_ratio_figure(const io::GearReport& r);

}  // namespace machdyn
