#pragma once
/// @file
/// The plots of the papers, each one small function from a result to a plot::Figure (io/plot.hpp);
/// `--plot` renders them with gnuplot (SVG + PNG), `report` draws the same figures with uPlot.
/// A new kind of plot (ω against distance with the limit line of `energy`, the load cyclogram of a
/// travel start-up, ...) is one more function here returning a Figure.

#include <vector>

#include "machdyn/analysis/energy.hpp"
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

/// Choices of how figures show their quantities.
struct FigureOptions {
  bool rpm = false;  ///< angular speeds in rpm (n = 60 ω / 2π) instead of rad/s
  std::vector<std::string> links;  ///< the links whose loads are drawn (`--links`); empty: all
};

/// The links `links` of `m` by index, in the given order without repeats (all when empty). An
/// unknown name is an InputError at `option` — the option's name where the user wrote the list:
/// `--links` on the command line, `links=` in Python — listing the model's links.
std::vector<std::size_t> chosen_links(const Model& m, const std::vector<std::string>& links,
                                      const std::string& option = "--links");

/// The links `links` (all when empty; an unknown name is an InputError at `--links`, chosen_links)
/// grouped into panels: per unit (N·m, then N), in descending order of the peak |load|, a
/// link whose peak is below 1/8 of its panel's largest starts a new panel — a 0.37 kN·m coupling
/// does not lie flat beside a 40 kN·m drum shaft. Each panel lists its links in the file's order.
/// Unless the links are chosen, a link whose load is 0 throughout the run is in no panel (a panel of
/// zero lines is empty); link_loads_figures names such links in its first panel's title.
std::vector<std::vector<std::size_t>> link_load_groups(const Model& m, const SimulationResult& r,
                                                       const std::vector<std::string>& links = {});
/// One link-loads figure per panel of link_load_groups (ids link_loads, link_loads_2, …; a title
/// naming the panel's links when there is more than one panel or links were chosen).
std::vector<plot::Figure> link_loads_figures(const Model& m, const SimulationResult& r,
                                             const std::vector<std::string>& links = {});
/// The same with options (rpm).
plot::Figure body_speeds_figure(const Model& m, const SimulationResult& r, const FigureOptions& opt);

/// Paper 001: the load cyclogram of a start-up with wheel slip — link loads against time, the static
/// limit F_sc of every slipping contact (= ΔG·μ_s for wheel–rail adhesion: FrictionContact::
/// static_limit) as a dashed black line, the slip phases of those contacts shaded, and the link load
/// at each breakaway marked (the exact slip limit, located at the event; for the travel drive
/// F_slip = [F_sc (mk + m2) − mk W]/m2, not F_sc). The slipping contacts are those between two
/// bodies (adhesion, clutches); a model with only ground contacts (brakes, resistances) uses those.
/// Needs a hybrid result (r.hybrid.active) and at least one link.
plot::Figure load_cyclogram_figure(const Model& m, const SimulationResult& r);

/// Contact forces (left axis) and sliding velocities u = v_a − v_b (right axis) of the friction
/// contacts and brakes against time, slip phases shaded as in the cyclogram.
plot::Figure contacts_figure(const Model& m, const SimulationResult& r);
/// The same for the contacts on bodies of `kind` only (one unit per axis): id `contacts` for the
/// first contact's kind, `contacts_torques` / `contacts_forces` for the other. simulation_figures
/// draws both when a model has contacts of both kinds (a drum brake beside wheel adhesion), so
/// none is left out.
plot::Figure contacts_figure(const Model& m, const SimulationResult& r, BodyKind kind);

/// The figures `simulate --plot` writes: link loads in panels (link_loads_figures; opt.links chooses
/// the links), body speeds; for a
/// hybrid model with links and contacts the load cyclogram and the contacts figure in addition.
std::vector<plot::Figure> simulation_figures(const Model& m, const SimulationResult& r, const FigureOptions& opt = {});

/// Elastic mode shapes: amplitude per body (x: the bodies in model order, named), one curve per
/// mode, each scaled to max |φ_i| = 1 and labelled with its natural frequency; a model mixing
/// rotational (rad) and translational (m) bodies weights each entry by √I_i first (√I_i φ_i is
/// dimensionless, its square the body's share of the mode's kinetic energy), as the title says. At most `max_modes`
/// (the lowest) are drawn, so that a long chain's figure stays readable; the title says so.
plot::Figure mode_shapes_figure(const Model& m, const Modes& modes, int max_modes = 6);

/// Paper 000, Figs. 2–4: the speed ω of a machine against the distance travelled by its output
/// point (the rolling wheel's centre travel x, m), from the energy integral (`machdyn energy`), with
/// the limit speed ω_limit (EnergyResult::omega_limit, as β → π) as a dashed line. A machine without
/// an output point other than a piston is drawn against its angle q in degrees instead
/// (id "speed_angle"). The x range ends where ω is within 1 % of a finite limit, at 90 % of the β
/// range when ω is unbounded, else at the end of the scan (x grows without bound as β → π); the
/// distance curve is the energy integral on 401 points uniform in x.
plot::Figure speed_distance_figure(const Model& m, const EnergyResult& r);

/// Paper 004: the inertia moments M_k = −I_k ε − ½ I_k′ ω² of the machine's parts (crank, rod,
/// piston) and their sum against the angle q in degrees over the scan of the energy integral, with
/// ε = (Q − ½ I′ ω²)/I from the equation of motion (so Σ M_k + Q = 0, d'Alembert).
plot::Figure inertia_moments_figure(const Model& m, const EnergyResult& r);

/// The figures `energy --plot` writes: ω against distance (rolling wheel) or angle, and for a
/// machine with more than one inertia part the inertia moments.
std::vector<plot::Figure> energy_figures(const Model& m, const EnergyResult& r);

/// Paper 003 Fig. 1: both pitch curves in mesh position (wheel centre at 0, pinion centre at
/// L_installed), mm, equal scale, with the radial sector boundaries of every tooth.
plot::Figure gears_pitch_figure(const io::GearReport& r);

/// Paper 003 Fig. 2: the theoretical ratio i(φ) of the law and the stepwise ratio Δθ_j/Δφ_j of the
/// synthesized sectors over one big sector, φ in degrees.
plot::Figure gears_ratio_figure(const io::GearReport& r);

}  // namespace machdyn
