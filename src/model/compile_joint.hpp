#pragma once
/// @file
/// Joints: rigid velocity constraints among three bodies, kept as always-stuck contacts with a
/// general row (model/model.hpp FrictionContact::joint, law in elements/contact.hpp).
///   planetary gear (`type: planetary-gear` under links; Modelica's IdealPlanetary, no inertia, no
///   losses), ratio z = z_ring/z_sun:   ω_sun + z ω_ring − (1 + z) ω_carrier = 0
///   ideal gear on a housing body (`type: ideal-gear` with `housing: BODY`; Modelica's IdealGear with
///   its support on a body), i = ratio:  (ω_a − ω_h) − i (ω_b − ω_h) = 0
/// Each member may be a body with inertia or, for at most one member, a body of zero inertia (a
/// massless ring, as in Modelica's SimpleGearShift): that member has no equation of motion of its
/// own and the joint eliminates it, q_X = Σ_j c_j q_j (c_j = −w_j / w_X) over the other members,
/// so the joint adds no constraint at all; a contact on X (a brake, a clutch) gets X's terms
/// rewritten (a general row), and X's position and velocity are still written (RigidSlave with two
/// masters). A link on X (a spring, damper or gap on a gear's massless output flange, as in Modelica's
/// ElasticBearing) gets X's term rewritten likewise: its deflection becomes a linear form over up to
/// three bodies (model.hpp: Link::b_weight, e; law in elements/link.hpp). A load, drive or lossy gear
/// on X, and a machine's output point, winding rope, buffer or crane rope on it, are errors (X would
/// need an equation of motion, or the element's law has no such form).

#include <string>
#include <unordered_set>
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// A joint as read from the file: its members by name with their coefficients w_j.
struct JointSpec {
  std::string name;
  std::string what;                 ///< "planetary gear 'NAME'" or "ideal gear 'NAME'" for messages
  std::vector<std::string> member;  ///< body names in the file
  std::vector<std::string> role;    ///< "sun", "ring", "carrier" or "a", "b", "housing"
  std::vector<double> w;            ///< the row's coefficients in the members' coordinates
  Location where;                   ///< the joint's key
};

/// Reads a `type: planetary-gear` link: sun, ring, carrier (body names) and the ratio z = z_ring/z_sun
/// (`ratio: z`, z > 1, or `teeth: {sun: z_s, ring: z_r}` with whole numbers that can be built:
/// z_r > z_s ≥ 1 with z_r − z_s even, the planets' z_p = (z_r − z_s)/2 ≥ 1; with `planets: N`
/// also (z_s + z_r) divisible by N, the assembly condition of equally spaced planets).
void read_planetary_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<JointSpec>& out,
                         Diagnostics& diag);

/// Reads a `type: ideal-gear` link whose `housing:` is a body: between [a, b], ratio i.
void read_housed_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<JointSpec>& out,
                      Diagnostics& diag);

/// The members of the joints that have zero inertia in the file (resolve_rigid lets them pass).
std::unordered_set<std::string> massless_members(const Model& m, const std::vector<JointSpec>& joints);

/// Puts the joints on the bodies left by the ideal-gear merge (ratios ρ of slaved members), checks
/// the initial velocities, eliminates a member without inertia and appends one joint contact per
/// remaining joint to m.contacts. `bodies`: the file's `bodies:` section (initial-condition places).
void resolve_joints(Model& m, const std::vector<JointSpec>& joints, const SpecNode* bodies, Diagnostics& diag);

}  // namespace machdyn::detail
