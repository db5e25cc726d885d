#pragma once
/// @file
/// The linear model of a drive in one topology, element by element (elements/linear_model.hpp):
/// bodies add M = diag(I(q)), links their K and D (elements/link.hpp), contacts their constraint
/// rows or kinetic slopes (elements/contact.hpp), drives their linear terms (model/element.hpp:
/// a DC motor's quasi-static slope, a speed drive's PI law in its linear mode as damper and spring).

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The linearization of `m` in topology `topo` at time t and state y = [q; v] (2n values; null: the
/// initial positions and velocities). Throws std::invalid_argument when topo's sizes do not match
/// the model (gaps: one per link, contacts and engaged: one per contact or empty).
LinearModel linearize(const Model& m, const Topology& topo, double t = 0.0, const double* y = nullptr);

/// Adds drive d's linear terms in `mode` (Element::add_linear_at about positions q of the model's
/// bodies and the element's states x; null: Element::add_linear) to lin: on its bodies, or, on a
/// joint member without inertia (Drive::terms), a term c at X spread as ρ_i ρ_j c over its bodies i, j.
void add_drive_linear(const Drive& d, int mode, LinearModel& lin, const double* q = nullptr, const double* x = nullptr);

/// The topology the initial state implies: gaps closed where they press (LinkLaw::natural_mode),
/// contacts stuck where the sliding velocity is zero, else sliding; brakes engaged when applied at t.
Topology initial_topology(const Model& m, double t = 0.0);

}  // namespace machdyn
