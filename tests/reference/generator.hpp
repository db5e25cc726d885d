#pragma once
/// @file
/// Random small models for the reference campaign (issue 27): one description (RefModel) from which
/// both the engine's model file (to_yaml) and the reference simulator's input are made, so the two
/// see the very same numbers (every value written with 17 significant digits).
///
/// Families (each model has a chain of 2–6 bodies with springs, spring-dampers and 1–2 loads, plus
/// the family's elements):
///   chain            springs and dampers only
///   gap              gap links, both flank laws (linear, elasto-backlash)
///   one-sided        one-sided links (`flank`) and ropes with slack
///   ground-friction  friction contacts to the ground (levels or normal force · μ), also in parallel
///   body-friction    friction contacts between bodies
///   brake            brakes applied at a time, step or ramp
///   clutch           clutches with a step or ramp normal force
///   freewheel        freewheels between bodies and backstops, with and without drag
///   stop             end stops, plastic and with restitution
///   mixed            a bit of everything above
///   signals          1–3 loads of every signal kind (tables with jumps, pulses, expressions besides
///                    constants, steps, ramps, sines), contacts with a varying normal force, brakes
///                    with an application signal, clutches opened and closed by their normal force
///   gear             bodies slaved to the chain by ideal gears (ratio ±0.3–3), with loads and
///                    links of their own, a contact and a brake on the masters
///                    (in half its models, from a stream of its own, a two-stage lossy gearbox on
///                    three bodies of its own, ratios 0.4–3, efficiencies 0.5–1, reverse ones 0.3–1
///                    or 0, driven from a chain body through a spring, with loads on its ends)
///   planetary        rotational bodies (inertias, torques) with a planetary gear among three of
///                    them (z = 1.5–5), a contact and a brake (time, ramp or application) on members
///   motion           a chain body moved by a prescribed speed (ramp, sine from its zero, table
///                    without jumps, expression) or acceleration (every kind), with 0–2 contacts
///                    from it to free bodies
///   release          1–2 chain bodies losing 20–60 % of their mass at an instant, with 0–2 contacts
///                    on the first (to the ground or another body)
///   kinetic          1–3 contacts with a kinetic level over the sliding speed: a table from speed
///                    0 or the Stribeck law
///   buffer           1–2 linear buffers (`buffers:`, with or without damping) against the ground
///   dc-motor         a DC (linear) motor on a chain body, its voltage of every signal kind, with
///                    0–2 ground contacts
///   drum             rotational bodies (drums) with translational bodies (hooks) slaved by ideal
///                    gears in rad/m (i = 1/R, R = 0.1–0.5 m), hook loads in N, hook links to the
///                    ground, a contact and a brake on the drums
///   gear-mesh        rotational bodies with 1–2 chain links made elastic gear meshes (ratio 0.3–3,
///                    damping, backlash 0 or 0.5–5 mrad, efficiency 1 or 0.85–0.99), a contact and a
///                    brake to the ground
///   sway             a load on a spatial rope from a chain body (the trolley; in space also the
///                    bridge), wound on a drum in some, hanging swinging or resting on a ground stop;
///                    in some planar models a rigid load (from a stream of its own: the other models
///                    keep their numbers) on one rope at a point of its own or a spreader on two ropes
/// The first seven families draw their loads from constant, step, ramp and sine only (their models
/// are those of the first campaigns); brake, clutch, mixed, signals, gear, planetary, motion, release and kinetic from every kind.

#include <cstdint>
#include <string>
#include <vector>

#include "reference/reference.hpp"

namespace machdyn::reference {

const std::vector<std::string>& all_families();

/// The model number `index` of a campaign with seed `seed` in family `family` (deterministic).
RefModel random_model(const std::string& family, std::uint64_t seed, std::uint64_t index);

/// The model file of `m` for the engine (translational bodies, SI units), run with `integrator`
/// (dopri5 or bdf) at rtol 1e-10, atol 1e-12.
std::string to_yaml(const RefModel& m, const std::string& integrator, const std::string& header = "");

}  // namespace machdyn::reference
