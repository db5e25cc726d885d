#pragma once
/// @file
/// The law of a spatial rope (`type: spatial-rope` under `links:`): a load hanging on an elastic,
/// tension-only rope from a suspension point that moves with the model's bodies — a trolley's
/// travel, a bridge's travel, a slewing jib's angle with the trolley's radius on it — its free
/// length set by a hoist drum's angle; stated once as an Element on N bodies (model/element.hpp;
/// derivation and sign conventions: docs/sway.md).
///
///   load         r = (x, y, z), m: the coordinates of a point-mass load (model/compile_point_mass.hpp;
///                absent ones 0), z up; on a rigid load (planar, angle ψ) the rope's point
///                r = c + R(ψ) a of its centre c and its `attach` point a = (a_h, a_z) in the load's
///                frame, R(ψ) turning the plane's horizontal axis h towards z:
///                r_h = c_h + a_h cos ψ − a_z sin ψ, r_z = c_z + a_h sin ψ + a_z cos ψ
///   suspension   p(q) = (x_t + r cos θ, y_b + r sin θ, h): trolley x_t, bridge y_b (m, 0 without),
///                jib angle θ (rad) with the radius r (a body's position, or a constant; no r term
///                without a jib), a fixed height h; a planar load's rope may hang from a point at
///                `offset` d along the plane's horizontal axis (the two ropes of a spreader)
///   length       ℓ = |p − r|, u = (p − r)/ℓ the unit vector from the load to the suspension point
///   free length  L(φ) = L0 − s (φ − φ0) per fall, s = R/n (drum radius R, n falls, φ0 the drum's
///                initial angle: positive φ hoists); L0 without a drum
///   stretch      e = ℓ − L(φ) (the hook's, m), ė = ℓ̇ + s φ̇
///   force        taut: F = c(φ) e + d ė (N, the hook load), c(φ) = n E A / L(φ); slack: F = 0.
///                The scalar law is a winding rope's (elements/link.hpp, LinkLaw with `winding`,
///                one positive flank at e = 0): the same c(φ), the winding term W = ½ c′ e², the
///                events and the natural mode.
///   forces       by virtual work, on port k with coordinate q_k: M_k = −F ∂e/∂q_k (− W on the drum),
///                ∂e/∂q_k = u · ∂(p − r)/∂q_k (+ s on the drum): the load is pulled along u, the
///                trolley and bridge back towards the load, the jib feels the moment r (u × …) of the
///                horizontal pull, the drum the rope torque F s (+ W)
///   energy       V = ½ c(φ) e² taut (0 slack); P_heat = d ė² taut; Σ M_k v_k = −dV/dt − P_heat
///                A rigid load's ψ is a port like the others: ∂(p − r)/∂ψ = −R′(ψ) a, and the
///                Hessian's u · ∂²(p − r)/∂ψ² = u · R(ψ) a.
/// Modes: 0 taut, 1 slack. Events (≥ 0 while the mode holds): taut g₀ = c e + d ė (the rope goes slack
/// where it reaches 0, the load in free flight: a load swinging past the horizontal is a slack rope);
/// slack g₀ = −e (tightens). Valid for ℓ > 0 (at ℓ = 0, u is taken as (0, 0, 1)) and L above
/// L_min = 1e-3 L0 (below it c is held, as for the winding rope). Nothing is thrown.

#include <string>

#include "machdyn/elements/link.hpp"
#include "machdyn/model/element.hpp"

namespace machdyn {

class SpatialRope final : public Element {
 public:
  /// What each port is (the order of the ports: load z, x, y, then trolley, bridge, jib, radius, drum
  /// as present).
  enum class Role : int { load_x, load_y, load_z, trolley, bridge, jib, radius, drum, load_psi };
  static constexpr int kRoles = 9;
  Role role[ElementMotion::kMax] = {};
  int n_ports = 0;
  int port_of[kRoles] = {-1, -1, -1, -1, -1, -1, -1, -1, -1};  ///< the port of each Role, −1 without
  LinkLaw law;         ///< the scalar law: one positive flank at e = 0, c = nEA/L0, K = nEA, s, φ0, d
  double h = 0.0;      ///< the suspension point's height, m
  double r0 = 0.0;     ///< the jib's radius without a radius body, m
  double attach[2] = {0.0, 0.0};  ///< a rigid load's rope point (a_h, a_z) in its frame, m
  double offset = 0.0;            ///< a planar load's suspension offset d along its horizontal axis, m
  double mass = 0.0;   ///< the load's mass, kg (the description, the summary's rigid force)
  double sway_after = -1.0;  ///< t_r of the summary's residual sway, s (`sway_after`; < 0: none)

  /// Where the rope is at the motion b: the points, its length, direction and the gradients.
  struct Geometry {
    double p[3], w[3];  ///< suspension point, w = p − r
    double l;           ///< ℓ
    double u[3];        ///< w/ℓ
    double dw[ElementMotion::kMax][3];  ///< ∂w/∂q_k
    double a[ElementMotion::kMax];      ///< ∂e/∂q_k
    double e, rate, qa;  ///< e, ė, the drum's angle (φ0 without)
  };
  [[nodiscard]] Geometry geometry(const ElementMotion& b) const;
  /// H_kj = ∂²ℓ/∂q_k∂q_j at g (the ports' count squared, row-major into H).
  void hessian(const ElementMotion& b, const Geometry& g, double* H) const;
  /// F in `mode`.
  [[nodiscard]] double tension(const Geometry& g, int mode) const;
  /// A point-mass load's hanging rest under the suspension point at the bodies' positions b: its
  /// x, y under p (the offset and the jib included), z = h − (L(φ) + m g/c(φ)), where the rope's
  /// tension c e is the weight m g (`gravity` g); b's load ports are set, the rest kept. False (b
  /// unchanged) for a rigid load (its rest depends on ψ and on its other ropes).
  bool hang(ElementMotion& b, double gravity) const;
  [[nodiscard]] bool has(Role r) const { return port_of[static_cast<int>(r)] >= 0; }
  [[nodiscard]] double at(const ElementMotion& b, Role r, double fallback = 0.0) const {
    return has(r) ? b.q[port_of[static_cast<int>(r)]] : fallback;
  }

  [[nodiscard]] const char* type() const override { return "spatial-rope"; }
  [[nodiscard]] int bodies() const override { return n_ports; }
  [[nodiscard]] int states() const override { return 0; }
  void initial_states(double*) const override {}
  void forces(double t, const ElementMotion& b, const double* x, int mode, double* M) const override;
  void rates(double, const ElementMotion&, const double*, int, double*) const override {}
  [[nodiscard]] ElementJacobian jacobian(double t, const ElementMotion& b, const double* x, int mode) const override;
  [[nodiscard]] bool reads_positions() const override { return true; }
  [[nodiscard]] bool dissipates() const override { return law.d > 0.0; }
  [[nodiscard]] double heat_power(double t, const ElementMotion& b, const double* x, int mode) const override;
  [[nodiscard]] double source_power(double, const ElementMotion&, const double*, int) const override { return 0.0; }
  [[nodiscard]] bool has_energy() const override { return true; }
  [[nodiscard]] double energy(const ElementMotion& b, const double* x, int mode) const override;
  [[nodiscard]] double stored_power(double t, const ElementMotion& b, const double* x, int mode) const override;

  [[nodiscard]] bool has_events() const override { return true; }
  void events(double t, const ElementMotion& b, const double* x, int mode, double* g) const override;
  [[nodiscard]] int mode_after(int mode, int) const override { return mode == 0 ? 1 : 0; }
  [[nodiscard]] int natural_mode(double t, const ElementMotion& b, const double* x, int current) const override;
  [[nodiscard]] const char* mode_name(int mode) const override { return mode == 0 ? "taut" : "slack"; }
  [[nodiscard]] const char* switch_kind(int now) const override { return now == 0 ? "taut" : "slack"; }

  /// The linear terms about the configuration b at rest: K = ∂²V/∂q² (the rope's axial stiffness
  /// along u and the geometric stiffness F ∂²ℓ/∂q², a pendulum's m g/L), D = d (∂e/∂q)(∂e/∂q)ᵀ;
  /// taut only. add_linear() without a configuration adds nothing.
  void add_linear_at(const int* body, const ElementMotion& b, const double* x, int mode,
                     LinearModel& lin) const override;
  [[nodiscard]] const char* state_name(int) const override { return ""; }
  [[nodiscard]] std::string state_unit(int, BodyKind) const override { return ""; }
  /// The tension F, the length ℓ, the free length L, the sway angles (x, y: in the travel directions;
  /// with a jib also radial and tangential), the horizontal force on the suspension point, the mode.
  [[nodiscard]] std::vector<std::string> output_names(BodyKind) const override;
  void outputs(double t, const ElementMotion& b, const double* x, int mode, double* out) const override;
  [[nodiscard]] std::string describe(BodyKind) const override;
};

}  // namespace machdyn
