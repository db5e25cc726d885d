#pragma once
/// @file
/// The compiled, immutable model of a drive: flat arrays of bodies, links and loads with every
/// quantity in SI. Built only by compile_model() (model/compile.hpp), which has checked it.
///
/// Coordinates. Each body has one generalized coordinate q: an angle φ in rad (rotational body,
/// "inertia" I in kg·m²) or a displacement x in m (translational body, "mass" m in kg). The ground
/// has q ≡ 0. Positive loads act in the direction of positive q.
///
/// Links. A link joins body a to body b (either may be the ground) through a ratio i (default 1):
///   deflection     δ = q_a / i − q_b                   (rad or m, in b's coordinate)
///   load           F = c δ + d δ̇                       (N·m or N; positive = tension of the paper's
///                                                        M12 = c1 (φ1 − φ2))
///   acts on b with +F and on a with −F / i.
/// A gear stage with ratio i = ω_a/ω_b and an elastic output shaft, or a rope drum (i in rad/m, the
/// drum's 1/R) are links with a ratio. A link to the ground has i = 1.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/model/signal.hpp"

namespace machdyn {

class Expression;  // common/expression.hpp
class Machine;  // model/machine.hpp: a body with position-dependent reduced inertia
class Element;  // model/element.hpp: an element with states of its own on one body

enum class BodyKind { rotational, translational };

/// How a body moves: by its equation of motion (`free`), or prescribed by a signal (`motion:`, Modelica's
/// Translational/Rotational.Sources.Accelerate, Speed and Position): its acceleration a(t)
/// (`acceleration`), its speed v(t) (`speed`: a = dv/dt, v(0) = v(t = 0)) or its position s(t)
/// (`position`: a = d²s/dt², q(0) = s(0), v(0) = ds/dt(0); s smooth before t_end). The law:
/// elements/prescribed_motion.hpp.
enum class MotionKind { free, acceleration, speed, position };

struct Body {
  std::string name;
  BodyKind kind = BodyKind::rotational;
  /// I in kg·m² (rotational) or m in kg (translational); > 0 in a compiled model. The file may give
  /// 0 (a massless flange) only on a body that an ideal gear ties to one with inertia (RigidSlave).
  double inertia = 0.0;
  double q0 = 0.0;       ///< initial position, rad or m
  double v0 = 0.0;       ///< initial velocity, rad/s or m/s
  /// Gravity (`vertical:` of a translational body): +1 when q points up (its weight −m g acts
  /// along −q), −1 when q points down (weight +m g), 0 for no weight. The weight is a constant load
  /// "NAME.weight" added by compile (Model::gravity), so every consumer sees an ordinary load.
  int vertical = 0;
  /// Variable inertia I(q) (crank-slider, rolling wheel, table, expression; model/machine.hpp), or
  /// null for a constant one. When set, `inertia` holds I(q0) (used where the model is linearized).
  std::shared_ptr<const Machine> machine;
  /// Prescribed motion (`motion:`): the signal is a(t) in rad/s² or m/s² (acceleration), v(t) in
  /// rad/s or m/s (speed) or s(t) in rad or m (position); unused while `motion` is free.
  MotionKind motion = MotionKind::free;
  Signal motion_signal;
};

/// Standard gravity g_n (ISO 80000-3), m/s²: the default of `gravity:`.
inline constexpr double kStandardGravity = 9.80665;

/// Index of the ground in Link::a / Link::b.
inline constexpr int kGround = -1;

enum class LinkKind { spring, damper, spring_damper };

struct Link {
  std::string name;
  LinkKind kind = LinkKind::spring;
  int a = kGround;     ///< body index or kGround
  int b = kGround;     ///< body index or kGround
  /// The ends as the file names them, for display (report, Python): compile may move an end onto an
  /// ideal-gear group's master or a joint's other members (RigidSlave). Empty: the name of a, b.
  std::string given_a, given_b;
  double ratio = 1.0;  ///< i, nonzero; dimension of q_a / q_b
  double c = 0.0;      ///< stiffness, N·m/rad or N/m (in b's coordinate), >= 0
  double d = 0.0;      ///< damping, N·m·s/rad or N·s/m, >= 0
  /// δ₀, the deflection of the unstretched spring of a link without a gap: F = c (δ − δ₀) + d δ̇ (law:
  /// elements/link.hpp). From `free_length` ℓ₀ (MSL's s_rel0, φ_rel0: δ₀ = −ℓ₀) or `preload` P, the
  /// load at δ = 0 (δ₀ = −P/c). 0: the spring is unstretched at δ = 0.
  double delta0 = 0.0;
  /// Backlash (law: elements/link.hpp). With a gap the link transmits load only on a flank:
  ///   δ ≥ δ₊: F = max(0, c (δ − δ₊) + d δ̇),  δ ≤ δ₋: F = min(0, c (δ − δ₋) + d δ̇),  else F = 0,
  /// δ₋ = −gap_start, δ₊ = gap − gap_start. gap_start = 0: the link must take up the whole gap in
  /// the positive direction before it pulls. Initial positions with δ(0) > δ₊ give a preload.
  bool has_gap = false;
  /// One-sided: a rope (`type: rope`, δ₊ = gap = the slack ≥ 0) or a link's `flank` (δ₊ = gap, any sign:
  /// MSL's ElastoGap). No negative flank (δ₋ = −∞): below δ₊ it carries nothing, however far.
  bool tension_only = false;
  /// A rope wound on a drum (`length` with `EA`, or `elastic_modulus` and `area`; `falls`). Law and
  /// derivation: elements/link.hpp. n falls carry body b (the hook); `ratio` is then n/R (the drum's
  /// angle per metre of hook travel), compiled from the file's drum ratio 1/R times n. The free
  /// length of one fall is L_f(q_a) = L_f0 − (q_a − q_a0)/i: positive q_a winds the rope up (hoists).
  /// The hook stiffness c(q_a) = n E A / L_f(q_a); `c` holds its value at q_a0. EA = 0: constant c.
  int falls = 1;           ///< n, the number of falls carrying b, >= 1
  /// Reeving as drawn (elements/reeving.hpp): n_e rope ends wound on the drum (4/2 reeving: n = 4,
  /// n_e = 2; `ratio` is then (n/n_e)/R) and the efficiency η of one sheave (1: frictionless).
  int rope_ends = 1;              ///< n_e >= 1, n a multiple of n_e
  double sheave_efficiency = 1.0; ///< η in (0, 1]
  double EA = 0.0;         ///< axial stiffness E·A of the rope, N (0: a rope of constant stiffness c)
  double length = 0.0;     ///< L_f0, the free length of one fall at q_a = q_a0, m (> 0 when EA > 0)
  double drum_q0 = 0.0;    ///< q_a0: the drum's position (body a's initial position) where L_f = L_f0
  /// The flank law of a gap or a rope (`flank_law: elasto-backlash`, Modelica's ElastoBacklash and
  /// ElastoGap): the damping force on a flank is capped at the spring force, so the load starts from
  /// 0 at contact instead of jumping to d δ̇ (law: elements/link.hpp).
  bool damping_capped = false;
  double gap = 0.0;        ///< total gap Δ, rad or m (in b's coordinate), >= 0
  double gap_start = 0.0;  ///< position inside the gap at δ = 0, from the negative flank, in [0, Δ]
  /// An end on a member without inertia that a joint eliminated (a gear's massless output flange,
  /// model/compile_joint.hpp): q_X = Σ c_j q_j over the other members turns the deflection into
  ///   δ = q_a / i − w_b q_b + w_e q_e      (w_b = 1 and e = kGround for every other link),
  /// and the load acts on a with −F/i, on b with +F w_b, on e with −F w_e (virtual work); the law is
  /// stated in elements/link.hpp. Never together with a machine's output point, a winding rope or a buffer.
  double b_weight = 1.0;   ///< w_b, nonzero
  int third = kGround;         ///< e: a third body, or kGround
  double third_weight = 0.0;   ///< w_e ([δ]/[q_e]), nonzero when e is a body
  /// The end is the machine's output point p(q) (e.g. `crank.piston`) instead of q itself:
  /// δ = p_a(q_a)/i − p_b(q_b); the load acts on a with −F p_a′/i and on b with +F p_b′.
  bool a_point = false, b_point = false;
  /// A buffer (`buffers:` section, model/compile_crane.cpp): a one-sided spring (and damper) between
  /// a body and the ground that pushes the body back once it passes the buffer's position x_b. It is
  /// this link law's single flank: an upper buffer (`max: x_b`) is [body, ground] with δ = q and
  /// δ₊ = x_b, a lower one (`min: x_b`) is [ground, body] with δ = −q and δ₊ = −x_b; the load
  /// F = c (δ − δ₊) + d δ̇ ≥ 0 is the buffer force (compression). `gap` holds δ₊ (any sign here).
  bool buffer = false;
  /// A buffer's characteristic (`characteristic:`; the law in elements/link.hpp). With e = δ − δ₊ ≥ 0
  /// the stroke and δ̇ its rate, the buffer force is F = F_e(e) + F_v(δ̇):
  ///   linear       F_e = c e                      F_v = d δ̇
  ///   progressive  F_e = c e^n (n > 1, c = F_ref / s_ref^n, N/mⁿ)   F_v = d δ̇
  ///   hydraulic    F_e = c e (a return spring, c ≥ 0)               F_v = d δ̇ + k δ̇|δ̇|
  ///   table        F_e = the force–stroke table (s, F) interpolated linearly, s₀ = 0, F₀ = 0, beyond
  ///                the last point its last slope continues           F_v = d δ̇
  /// For `progressive` and `table` Link::c holds a representative stiffness (the slope n F_ref/s_ref at
  /// the reference stroke; the table's steepest slope) for step-size bounds and tolerances only.
  enum class Characteristic { linear, progressive, hydraulic, table };
  Characteristic characteristic = Characteristic::linear;
  double exponent = 1.0;              ///< n of `progressive`
  double coefficient = 0.0;           ///< c of `progressive`, N/mⁿ (Link::c is then n F_ref/s_ref)
  double hydraulic_k = 0.0;           ///< k of `hydraulic`, N·s²/m² (N·m·s²/rad²)
  std::vector<double> table_stroke;   ///< s of `table`, m (rad), increasing from 0
  std::vector<double> table_force;    ///< F of `table`, N (N·m), from 0
};

/// Friction between body a and body b (or the ground, which may move with a prescribed surface
/// velocity w(t)) — wheel–rail adhesion, a clutch, the static resistance W, a brake.
/// Sliding velocity u = v_a − v_b (v_b = w(t) for the ground). The friction load F acts on b with
/// +F and on a with −F (as a link's load):
///   stuck  (u ≡ 0):  F from the equations of motion, |F| ≤ F_s(t)
///   sliding (u ≠ 0): F = sign(u) F_k(t, |u|)
/// F_s(t) = r(t) F_s0 and F_k(t, s) = r(t) F_k0(s), F_s0 ≥ F_k0(0) ≥ 0. r(t) is the application:
///   r ≡ 1                        a contact with constant levels (`applied` false)
///   r(t) = max(0, g s(t))        a signal s (model/signal.hpp): a brake's application (0 released,
///                                1 full; `time` and `ramp` are the ramp 0 → 1), or the normal force
///                                f_N(t) of a clutch or brake in N, with g = 1/f_N,ref; a negative
///                                normal force opens it (as Modelica's Clutch: free while fn ≤ 0).
/// A clutch or brake given by friction coefficients (Modelica's Rotational.Components.Clutch,
/// cgeo = z r, fn = f_N):
///   F_s0 = z r μ_s f_N,ref,   F_k0(s) = z r μ_k(s) f_N,ref    (rotational: N·m; translational: z = r = 1)
/// z: number of friction surfaces, r: effective radius in m, f_N,ref: the largest |f_N| (a scale only:
/// the loads depend on f_N(t) alone). μ_k(s) is a constant, a table over the sliding speed, or the
/// Stribeck law
///   μ_k(s) = μ_c + (μ_s − μ_c) exp(−(s / w_s)^δ),   w_s > 0, δ ≥ 1  (μ_c: `mu_k`, the Coulomb level)
/// which falls from μ_s at rest to μ_c while sliding fast (the same law for F_k0 in N or N·m).
/// A freewheel (one-way clutch, `lock` = ±1) transmits load in one direction only:
///   stuck   (u ≡ 0):  holds while lock·λ ≥ 0 (no upper limit; static_limit unused)
///   sliding:          only in the free direction, sign(u) = −lock, F = −lock F_k0(|u|) (drag)
/// lock = +1: A drives B forward and B may overrun (u < 0); written [ground, A] it is a backstop
/// that lets A move forward only (stored as a = A, b = ground, lock = −1).
/// A hard end stop (`stop` = true) is a lock to the ground that engages by position: free while the
/// body is off the stop (no force; its event is the distance −lock·(q − q_stop) reaching 0), at the
/// stop it holds like a backstop (lock·λ ≥ 0). The impact is an event with the velocity jump
/// v⁺ = −e v⁻ (e: restitution in [0, 1]); a rebound too slow to leave the stop within the event time
/// resolution, and every impact with e = 0, ends at rest on the stop. A lower stop (q ≥ q_stop) has
/// lock = −1, an upper one lock = +1.
/// The lumped thermal model of a friction element (`thermal:` of a brake, clutch, contact or freewheel;
/// law and valid range: elements/thermal.hpp). SI: J/K, W/K, K.
struct ThermalMass {
  double heat_capacity = 0.0;  ///< C > 0, J/K
  double conductance = 0.0;    ///< G ≥ 0, W/K (0: adiabatic)
  double ambient = 293.15;     ///< T_a, K
  double initial = 293.15;     ///< T(0), K
};

/// The velocity row of a contact or joint, u = Σ_j w_j v_j over at most four bodies (the ground
/// has no term; a contact to the ground subtracts its surface velocity w(t) from u). Empty (terms =
/// 0): the unit row u = v_a − v_b of FrictionContact's a and b. Compile writes a general row for a
/// joint (a planetary gear, a gear on a housing body) and for a contact on a planetary gear's member
/// without inertia, which the gear eliminates (model/compile_planetary.hpp).
struct VelocityRow {
  static constexpr int kMaxTerms = 4;
  int terms = 0;
  int body[kMaxTerms] = {0, 0, 0, 0};   ///< body indices, distinct, never the ground
  double w[kMaxTerms] = {0, 0, 0, 0};   ///< coefficients w_j, nonzero ([u]/[v_j])
};

struct FrictionContact {
  std::string name;
  /// A joint: a rigid velocity constraint u ≡ 0 with no limit (an ideal planetary gear, a gear whose
  /// housing is a body), always stuck; its force λ is the constraint's load (N·m or N per unit of u).
  bool joint = false;
  VelocityRow row;                   ///< u = Σ w_j v_j (terms > 0), else v_a − v_b
  bool brake = false;
  bool clutch = false;               ///< from `clutches:` (between two bodies, by its normal force)
  int lock = 0;                      ///< freewheel: +1 or −1 (see above); 0: a friction contact or brake
  bool stop = false;                 ///< a hard end stop (then lock ≠ 0, b = ground)
  double stop_position = 0.0;        ///< q_stop, rad or m
  double restitution = 0.0;          ///< e in [0, 1]
  int a = 0;                         ///< body index
  int b = kGround;                   ///< body index or kGround
  std::string given_a, given_b;      ///< a, b as the file names them (display; as Link::given_a)
  double static_limit = 0.0;         ///< F_s0, N or N·m, > 0
  std::vector<double> speeds;        ///< sliding speeds of the kinetic table (ascending from 0), or empty
  std::vector<double> kinetic;       ///< F_k0: one value (constant; μ_c with Stribeck) or one per speed
  double stribeck_speed = 0.0;       ///< w_s > 0: F_k0 follows the Stribeck law; 0: constant or table
  double stribeck_exponent = 1.0;    ///< δ ≥ 1
  /// peak = F_s0 / F_k0(0) ≥ 1 (MSL's `peak`): the static limit over the kinetic law's level at rest.
  /// The Stribeck law starts from F_s0 / peak; a constant or tabulated kinetic level is F_k0 itself.
  double peak = 1.0;
  std::vector<double> surface_times; ///< prescribed ground velocity w(t): table times, or empty (w = const)
  std::vector<double> surface_velocities;  ///< w values (one value if constant; empty: w = 0)
  bool applied = false;              ///< r(t) from `application` (else r ≡ 1)
  Signal application;                ///< s(t): 0…1, or the normal force f_N(t) in N
  double application_gain = 1.0;     ///< g: 1, or 1/f_N,ref
  bool by_normal_force = false;      ///< s is a normal force (compile scales by f_N,ref once t_end is known)
  double t_apply = 0.0;              ///< the first time r > 0 (0: from the start), for displays
  std::optional<ThermalMass> thermal;  ///< the element's temperature is an output (none: no thermal model)

  [[nodiscard]] double scale(double t) const;             ///< r(t)
  /// Whether r is 0 at t and stays 0 just after (r(t) = 0 and no rise on the right): released.
  [[nodiscard]] bool released(double t) const;
  [[nodiscard]] double kinetic_level(double speed) const;  ///< F_k0(|u|), a table held constant outside
  /// dF_k0/ds at sliding speed s ≥ 0 (0 outside a table and for a constant level).
  [[nodiscard]] double kinetic_level_slope(double speed) const;
  [[nodiscard]] double surface_velocity(double t) const;   ///< w(t)
  [[nodiscard]] double surface_acceleration(double t) const;  ///< dw/dt (piecewise constant)
  /// Times in (0, t_end) where r(t) jumps or has a kink: the breakpoints of s and its zero crossings.
  [[nodiscard]] std::vector<double> application_times(double t_end) const;
};

enum class LoadKind {
  constant, signal, expression, speed_table, position_table, drag, eddy_current, motor_linear, motor_kloss, motor_table
};

/// The eddy-current brake's law (Kloss form), stated once: the load `eddy-current-brake` and every
/// element that brakes by eddy currents call it:
///   M = −2 M_k x / (1 + x²),  x = v/ω_k        dM/dv = −2 M_k (1 − x²) / (1 + x²)² / ω_k
/// M_k its largest torque (N·m or N), reached at the speed ω_k > 0 (rad/s or m/s); against the motion.
/// Writes dM/dv to *dMdv when given.
inline double eddy_current_law(double v, double M_k, double omega_k, double* dMdv) {
  const double x = v / omega_k, den = 1.0 + x * x;
  if (dMdv) *dMdv = -2.0 * M_k * (1.0 - x * x) / (den * den) / omega_k;
  return -2.0 * M_k * x / den;
}

/// A torque (rotational body) or force (translational body) on one body, the load law
///   M = M(t, q, v)      (q, v: the body's position and velocity; positive M acts along +q)
///   constant:        M = value
///   signal:          M = s(t), any signal (model/signal.hpp): step, ramp, table, sine, pulse,
///                    expression of t, measured data, sums
///   expression:      M = f(t, q, v), an expression in t and the body's coordinate and velocity
///                    (`phi`, `omega` on a rotational body; `x`, `v` on a translational one)
///   speed_table:     M(v) piecewise linear through (v_k, M_k), held constant outside
///   position_table:  M(q) piecewise linear through (q_k, M_k), held constant outside
///   drag:            M = −k v |v|          (fan, air or water drag ∝ v², always against the motion)
///   eddy_current:    M = −2 M_k (v/ω_k) / (1 + (v/ω_k)²)   (eddy-current brake; M_k its largest
///                    torque, reached at the speed ω_k; against the motion)
///   motor_linear:    f(v) = M_s (1 − v/ω0)             (M_s stall torque, ω0 no-load speed)
///   motor_kloss:     f(v) = 2 M_k s s_k / (s² + s_k²),  s = (ω0 − v)/ω0   (Kloss formula; M_k
///                    breakdown torque, s_k breakdown slip, ω0 synchronous speed)
///   motor_table:     f(v) piecewise linear through the catalogue curve (v_k, M_k), held outside
/// A motor gives M = on(t) · d(t) · f(d(t) · v): `on` is 1 while its contactor is closed and 0 while
/// it is open, `d` is +1 forward and −1 reversed (the mirror image of the characteristic: the
/// reversed motor turns the other way with the same torque–speed curve).
struct Load {
  std::string name;
  LoadKind kind = LoadKind::constant;
  int body = 0;
  double value = 0.0;   ///< constant: M; motor_linear: M_s; motor_kloss: M_k; drag: k; eddy_current: M_k
  double omega0 = 0.0;  ///< motor_linear, motor_kloss: ω0; eddy_current: ω_k (rad/s, m/s on a translational body)
  double s_k = 0.0;     ///< motor_kloss: breakdown slip, 0 < s_k < 1
  /// signal: s(t). speed_table, position_table, motor_table: the table over v or q (a Signal::table
  /// whose "time" is the speed or the position).
  Signal signal;
  std::shared_ptr<const Expression> law;  ///< expression: f over (t, q, v) in that order
  /// ρ ≠ 1 when the load was given on a body slaved by ideal gears (q_slave = ρ q_body, RigidSlave):
  /// the law sees the slave's own position and velocity and acts on `body` reduced by the ratio,
  ///   M_body(t, q, v) = ρ M(t, ρ q, ρ v)     (virtual work: M δq_slave = ρ M δq_body)
  /// at(), slopes_at() and spread() apply it (the Jacobian's entries ρ² ∂M). A constant load is reduced
  /// by compile into `value` instead (ρ stays 1).
  double ratio = 1.0;
  /// A load on a joint member X without inertia (model/compile_joint.cpp, RigidSlave with two masters)
  /// acts on two bodies. X moves with q_X = ρ q[body] + ρ₂ q[body2]; the law sees X's own q_X and v_X;
  /// by virtual work M δq_X = ρ M δq_body + ρ₂ M δq_body2 the bodies get
  ///   f_body += ρ M,   f_body2 += ρ₂ M,   power M v_X = Σ f_i v_i.
  /// body2 = -1: one body, the form above. Every consumer goes through own(), at() and spread().
  int body2 = -1;
  double ratio2 = 0.0;
  /// The body as the file names it, for display (report, Python): `body` may be a master the load
  /// was moved to. Empty: bodies[body]'s name.
  std::string given_body;
  /// motors: the contactor, 0 or 1; drag, eddy-current-brake and tables over speed or position: the
  /// `scale` s(t), M = s(t) f(q, v) (MSL's Vehicle: a rolling resistance times cos α(t)).
  Signal on = Signal::constant(1.0);
  Signal direction = Signal::constant(1.0);  ///< motors: +1 or −1
  bool switched = false;                     ///< `on` (or `scale`) or `direction` is not the constant 1

  /// Times in (t0, t1) where M jumps or has a kink in t (model/signal.hpp).
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t1) const;

  /// The load's own coordinate from the bodies' x (positions or velocities): ρ x[body] + ρ₂ x[body2].
  [[nodiscard]] double own(const double* x) const;
  /// M(t, q_X, v_X), the law at the load's own point, from the bodies' positions q and velocities v.
  [[nodiscard]] double at(double t, const double* q, const double* v) const;
  /// ∂M/∂q_X and ∂M/∂v_X at the load's own point (the Jacobian adds ρ_i ρ_j ∂M to entry (i, j)).
  void slopes_at(double t, const double* q, const double* v, double* dMdq, double* dMdv) const;
  /// Adds the generalized forces of a load M on its point to f (over the bodies): ρ M, ρ₂ M.
  void spread(double M, double* f) const;
  /// Its bodies and weights into b[2], w[2] ({body, ρ}, {body2, ρ₂}); returns how many (1 or 2).
  int terms(int* b, double* w) const;
};

/// An element behind the one interface (model/element.hpp) placed on its bodies: from the section
/// `drives:` an element on one body (`body`) with states of its own — a DC motor, a speed-controlled
/// drive, an eddy-current brake with its temperature; from `links:` a registered element between
/// two bodies (`body`, `others`) — an elastic gear mesh — or on several (a spatial rope on its load
/// and the bodies its suspension point follows). Each type states its law and holds its compiled SI parameters in its own file under
/// elements/ (an Element, model/element.hpp) and registers its `type:` and compile function there;
/// this struct only places it. Its states follow [q; v] in the drive system's state
/// (analysis/drive_system.hpp), in the order of Model::drives.
struct Drive {
  std::string name;
  int body = 0;
  std::shared_ptr<const Element> law;  ///< never null in a compiled model; shared, immutable
  /// A drive on a joint member X without inertia (model/compile_joint.cpp) acts on two bodies as a
  /// Load does: the element sees ω_X = ρ v[body] + ρ₂ v[body2] and by virtual work M δq_X the bodies
  /// get f_body += ρ M, f_body2 += ρ₂ M. ρ = 1, body2 = −1: on `body` itself. Every consumer goes
  /// through own(), spread() and terms().
  double ratio = 1.0;
  int body2 = -1;
  double ratio2 = 0.0;
  std::string given_body;  ///< the body as the file names it (display; as Load::given_body)
  /// Ports 1 … n−1 of an element on several bodies (Element::bodies() ≥ 2: a gear mesh under
  /// `links:` on its second body, a spatial rope on its load's coordinates and its suspension
  /// bodies): port p ≥ 1 sees x[others[p − 1]] and puts M_p on that body (a plain body with inertia
  /// of its own; compile refuses a slaved one). Empty: an element on one body.
  std::vector<int> others;
  std::vector<std::string> given_others;  ///< those bodies as the file names them

  /// ρ x[body] + ρ₂ x[body2]: the element's own velocity (or acceleration) from the bodies' x.
  [[nodiscard]] double own(const double* x) const;
  /// Adds ρ M, ρ₂ M to f.
  void spread(double M, double* f) const;
  /// Its bodies and weights into b[2], w[2]; returns how many (1 or 2).
  int terms(int* b, double* w) const;
  /// The number of its ports (bodies it acts on as the element sees them): 1 + others.size().
  [[nodiscard]] int ports() const { return 1 + static_cast<int>(others.size()); }
  /// Port p's coordinate from the bodies' x: own(x) for p = 0, x[others[p − 1]] for p ≥ 1.
  [[nodiscard]] double at(const double* x, int p) const {
    return p == 0 ? own(x) : x[others[static_cast<size_t>(p - 1)]];
  }
  /// Adds the forces M[p] of every port to f (port 0 by spread()).
  void spread_all(const double* M, double* f) const {
    spread(M[0], f);
    for (size_t p = 0; p < others.size(); ++p) f[others[p]] += M[p + 1];
  }

  /// Number of continuous states (Element::states).
  [[nodiscard]] int states() const;
  /// Times in (t0, t1) where a signal of the element jumps or has a kink (Element::breakpoints).
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t1) const;
};

enum class IntegratorChoice { automatic, dopri5, bdf };

/// The `crane:` section (docs/crane-factors.md): the classes the crane analysis (analysis/crane.hpp)
/// compares with and the elements of its cases. Indices into Model::bodies / Model::links; −1 (or
/// empty) where not given, and then the case that needs it does not run.
struct CraneSpec {
  bool given = false;
  int hoisting_class = 2;         ///< HC1…HC4 as 1…4
  int drive_class = 1;            ///< HD1…HD5 as 1…5
  double hoist_speed = 0.0;       ///< vh,max, the steady hoisting speed of the hook, m/s
  double creep_speed = 0.0;       ///< vh,CS, m/s (HD2, HD3)
  int load = -1;                  ///< the hook load (a vertical translational body)
  int rope = -1;                  ///< the rope link that carries it (the load is its second end)
  double release_mass = -1.0;     ///< Δm of the φ3 case, kg (< 0: no φ3 case)
  bool rapid_release = true;      ///< β3 = 1.0 (rapid) or 0.5 (grabs, slow release)
  /// t_r of the φ3 case, s: the load loses Δm at t_r of a run (a Release, below). < 0 (not given):
  /// at once, the case's mass reduced from the start of the hanging equilibrium (the original case).
  double release_time = -1.0;
  /// With release_time: the φ3 run hoists as the φ2 case does (the load starting on the ground, the
  /// drive at vh,max) instead of hanging at rest with the drum held.
  bool release_hoisting = false;
  std::vector<int> drive_links;   ///< links of the φ5 case (the model's own run)
  int force_change = 1;           ///< φ5 range: 0 centrifugal, 1 smooth, 2 sudden, 3 backlash
  std::vector<int> buffers;       ///< buffer links of the φ7 case (the model's own run)
};

/// How the run starts: from the bodies' `position`/`velocity` as given, or from static equilibrium
/// under the loads at t = 0 (analysis/equilibrium.hpp: the elastic part solves K q = f, the rigid-body
/// motions keep the given position and velocity).
enum class InitialState { given, equilibrium };

/// Run settings, one struct for the file, the JSON summary and `--set simulation.FIELD=...`.
struct SimulationSettings {
  double t_end = 1.0;      ///< s
  double dt_out = 0.0;     ///< output step, s (0: t_end / 1000)
  double rtol = 1e-8;      ///< relative tolerance
  double atol = 1e-10;     ///< absolute tolerance (SI units of each state)
  IntegratorChoice integrator = IntegratorChoice::automatic;
  long max_steps = 50'000'000;
  InitialState initial = InitialState::given;  ///< `initial: given | equilibrium`
};

/// A body that loses part of its mass (or inertia) at an instant (`releases:`): a grab opening, a load
/// slipping off the hook. At t_r the body's inertia drops from I to I − ΔI, position and velocity are
/// continuous: the released part leaves with the body's velocity and carries away ½ ΔI v² of kinetic
/// energy. A body with `vertical:` loses the released part's weight too: its constant load
/// "NAME.weight" changes by `weight_change` = vertical · Δm · g at t_r. The state at t = 0 (given or
/// `initial: equilibrium`) belongs to the masses before every release, also for t_r = 0 (the release
/// then acts at 0⁺). Compile checks 0 < ΔI, Σ ΔI of a body < its own inertia, t_r ≥ 0, and a body
/// with a constant inertia that no ideal gear slaves. The Model keeps the masses at t = 0 (what
/// modes, equilibrium and the integrator choice see); a run keeps the current ones (DriveSystem::
/// apply_release), and model_after_releases() is the model between two releases.
struct Release {
  std::string name;
  int body = 0;                ///< index into Model::bodies
  double amount = 0.0;         ///< ΔI in kg·m² (rotational) or Δm in kg (translational), > 0
  double time = 0.0;           ///< t_r, s, >= 0
  int weight_load = -1;        ///< index of the body's "NAME.weight" in Model::loads, or −1 (no weight)
  double weight_change = 0.0;  ///< the change of that load at t_r, N: +vertical · Δm · g (0 without one)
};

/// A body removed by compile because ideal gears (`type: ideal-gear` under links) tie it rigidly to
/// another body, its master (model/compile_rigid.cpp). Its motion follows the master's exactly,
///   q_slave = ρ q_master,   v_slave = ρ v_master      (ρ: the product of the gear ratios on the path,
///                                                      dimension [q_slave]/[q_master]),
/// and its inertia is part of the master's reduced inertia I_master + Σ ρ² I_slave. Its loads act
/// on the master reduced by ρ (Load::ratio); its links end on the master with ratio i/ρ. The run
/// still writes its position and velocity columns (analysis/run.cpp).
struct RigidSlave {
  std::string name;      ///< the slaved body's name
  BodyKind kind = BodyKind::rotational;
  int master = 0;        ///< index into Model::bodies
  double ratio = 1.0;    ///< ρ = q_slave / q_master, nonzero
  double inertia = 0.0;  ///< its own inertia (kg·m² or kg) as given, >= 0
  /// A planetary gear's member without inertia moves with two bodies (model/compile_planetary.hpp):
  /// q_slave = ρ q_master + ρ₂ q_master2 (master2 = -1: the one-master form above).
  int master2 = -1;
  double ratio2 = 0.0;
};

/// The torques of a gear joint whose member X has no inertia (model/compile_joint.cpp eliminates X,
/// so the joint has no load λ of its own). X's torque balance is τ_X + f_X = 0, f_X what the other
/// elements put on X in X's coordinate; the joint's row (weights w_k over its members) puts
/// τ_k = −w_k λ on member k, so
///   λ = f_X / w_X,   τ_k = −w_k f_X / w_X   (τ_X = −f_X; Σ τ_k ω_k = −λ Σ w_k ω_k = 0),
///   f_X = Σ ρ_l M_l (loads) − Σ F_l ∂δ_l/∂q_X (links) − Σ w_c f_c (contacts and joints on X).
/// The outputs NAME.torque_MEMBER_N_m, as for a joint with inertia on every member.
struct EliminatedJoint {
  std::string name;                  ///< the joint
  std::vector<std::string> members;  ///< its members, in the order of its row
  std::vector<double> w;             ///< the row's weights w_k (members' own coordinates)
  double wx = 1.0;                   ///< X's weight in the row over the bodies (w_X ρ, q_member = ρ q_X)
  BodyKind kind = BodyKind::rotational;
  std::vector<int> loads;            ///< loads on X (indices into Model::loads): f_X += weight · Load::at()
  std::vector<double> load_weight;
  std::vector<int> links;            ///< links with an end on X: f_X −= F · ∂δ/∂q_X (the weight)
  std::vector<double> link_weight;
  std::vector<int> contacts;         ///< contacts and joints on X: f_X −= w_c f_c (the weight w_c)
  std::vector<double> contact_weight;
  std::vector<int> drives;           ///< drives on X (indices into Model::drives): f_X += weight · M
  std::vector<double> drive_weight;
};

/// The torque an ideal gear merged by compile passes (model/compile_rigid.cpp): the gear between A
/// and B (q_A = i q_B) splits its rigid group into two sides; the side S without the group's master
/// holds only slaved bodies, whose elements are loads and links' first ends. Summing the equations
/// of motion of S (virtual work in the master's coordinate, q_s = ρ_s q_M):
///   Σ_{s∈S} ρ_s (I_s ρ_s q̈_M − f_s) = ρ_E τ_E      (E: the gear's body on side S)
/// gives the torque τ_E the gear exerts on E. The output is τ_B, the torque on B in B's coordinate
/// (MSL's −flange_b.tau): τ_B = τ_E on B's side, else τ_B = −i τ_A (the gear does no work,
/// τ_A ω_A + τ_B ω_B = 0). No entry for a gear in a loop of gears or with a machine or a released
/// body on S.
struct MergedGear {
  std::string name;
  int body = 0;               ///< the group's master (index into Model::bodies)
  bool side_b = true;         ///< S is B's side (else A's: the master is on B's side)
  BodyKind kind_b = BodyKind::rotational;  ///< B's kind: the output's unit (N·m or N)
  double ratio = 1.0;         ///< i of the gear, q_A = i q_B
  double rho = 1.0;           ///< ρ_E of the gear's body E on side S (q_E = ρ_E q_M)
  double inertia = 0.0;       ///< Σ_{s∈S} ρ_s² I_s, reduced to the master
  std::vector<int> loads;     ///< loads on S (indices into Model::loads; their forces act on `body`)
  std::vector<int> links;     ///< links whose first end a is on S (their −F/i acts on `body`)
  std::vector<std::string> side;  ///< names of S's bodies (for compile's checks after the merge)
};

/// A lossy gear (`type: lossy-gear` under links; law, modes and derivation in elements/lossy_gear.hpp,
/// Modelica's Rotational.Components.LossyGear): the rigid kinematics of an ideal gear between two
/// degrees of freedom, v_a = i v_b, plus the mesh loss (efficiency η_mf1 while power flows from a to
/// b, η_mf2 from b to a) and the bearing friction τ_bf1, τ_bf2; at rest it may be stuck (self-locking).
/// Unlike an ideal gear its two sides stay two bodies of the model (each may be an ideal-gear group):
/// the gear's torques are constraint forces, solved in each mode by its law.
struct LossyGear {
  std::string name;
  int a = 0, b = 0;      ///< the two bodies (indices into Model::bodies after the ideal-gear merge), a ≠ b
  double ratio = 1.0;    ///< i = v_a / v_b in the bodies' coordinates (the file's ratio times ρ_B/ρ_A)
  /// ρ_A: the file's body A moves as q_A = ρ_A q_a (1 unless ideal gears slave A to a); the
  /// efficiencies and bearing friction are given over |v_A| and in A's coordinate.
  double rho_a = 1.0;
  double rho_b = 1.0;    ///< ρ_B of the file's body B (q_B = ρ_B q_b), for its torque column
  /// |v_A| of the loss table (ascending from 0), or empty: constant values (one entry each below).
  std::vector<double> speeds;
  std::vector<double> eta_forward;   ///< η_mf1 ∈ (0, 1]: a drives b
  std::vector<double> eta_reverse;   ///< η_mf2 ∈ [0, 1]: b drives a (0: self-locking)
  std::vector<double> bearing_forward;  ///< τ_bf1 ≥ 0 (a drives), N·m or N in A's coordinate
  std::vector<double> bearing_reverse;  ///< τ_bf2 ≥ 0 (b drives), N·m or N in A's coordinate
};

struct Model {
  std::string name;         ///< from the file's `name:` (or its file name)
  std::string description;
  std::string source;       ///< the file it was compiled from
  std::vector<Body> bodies;
  std::vector<Link> links;
  std::vector<Load> loads;
  std::vector<FrictionContact> contacts;  ///< friction contacts and brakes (law: elements/contact.hpp)
  std::vector<Drive> drives;              ///< elements behind the interface (`drives:`, registered `links:`)
  std::string load_case;                  ///< the case applied from the file's `cases:`, or empty
  /// g in m/s² (`gravity:`), the acceleration of gravity that gives every body with `vertical` its
  /// weight; 0 when no body is vertical.
  double gravity = 0.0;
  SimulationSettings simulation;
  CraneSpec crane;                        ///< the `crane:` section (given = false without one)
  /// Bodies removed by ideal gears (RigidSlave), in the file's order; empty without ideal gears.
  std::vector<RigidSlave> slaves;
  std::vector<std::string> ideal_gears;   ///< names of the ideal gears compile resolved
  std::vector<MergedGear> merged_gears;   ///< the merged ideal gears with a torque output (MergedGear)
  std::vector<EliminatedJoint> eliminated_joints;  ///< gear joints with a member without inertia
  /// Bodies losing part of their mass during the run (Release), in the order of their times (file
  /// order at equal times); empty without `releases:`.
  std::vector<Release> releases;
  std::vector<LossyGear> lossy_gears;     ///< lossy gears (law: elements/lossy_gear.hpp)

  [[nodiscard]] int dof() const { return static_cast<int>(bodies.size()); }
  /// Index of the body called `name`, kGround for "ground", or -2 if none. A hashed look-up once
  /// index_bodies() has run (compile does), so compiling N links is O(N), not O(N²).
  [[nodiscard]] int body_index(const std::string& name) const;
  /// Builds the name index of `bodies` for body_index(); call again after changing `bodies`.
  void index_bodies();
  std::unordered_map<std::string, int> body_lookup;  ///< name → index (index_bodies())
  /// Where each element (body, link, load, contact, brake) is defined: name → its key's place in
  /// the file. Compile fills it, so a check after compile (energy, steady running) can be located.
  std::unordered_map<std::string, Location> element_where;
  /// The place of `element` (a name), or the model file without a line if unknown.
  [[nodiscard]] Location where(const std::string& element) const;
  /// Whether the model needs the hybrid (event-driven) simulation: a gap, a contact, a brake or a
  /// lossy gear.
  [[nodiscard]] bool is_hybrid() const;
  /// Times in (0, t_end), increasing without repeats, where a load, the application of a brake or
  /// clutch (its normal force), a surface velocity or a prescribed motion jumps or has a kink in t, or a
  /// body releases part of its mass: the integrator stops there (solve/event_system.hpp).
  [[nodiscard]] std::vector<double> breakpoints(double t_end) const;
};

/// The release of `amount` (ΔI, kg·m² or kg) from body `body` of `m` (a body of its own, not a slave)
/// at `time`, s: the rule of Release for its weight, +vertical · Δm · g on the body's "NAME.weight"
/// load when it has one. Compile and the crane's φ3 case build their releases with it.
Release body_release(const Model& m, std::string name, int body, double amount, double time);

/// `m` after its first `count` releases (Model::releases, in time order): each released body's
/// inertia less ΔI and its weight load changed by the release's weight_change; those releases are
/// removed from the copy, the later ones kept. count = 0 gives a copy of `m`.
Model model_after_releases(const Model& m, std::size_t count);

/// Whether link l is a rope with falls (n > 1) or a free length (EA > 0): its runs add the columns
/// "NAME.fall_tension_N" (T = F/n) and, with a length, "NAME.fall_length_m" (L_f).
[[nodiscard]] inline bool is_rope_with_falls(const Link& l) { return l.tension_only && (l.falls > 1 || l.EA > 0.0); }
/// Whether a rope states its reeving beyond the falls (`rope_ends` > 1 or a `sheave_efficiency`): its
/// runs add "NAME.rope_force_N", the force in the rope part at the drum (elements/reeving.hpp).
[[nodiscard]] inline bool has_reeving(const Link& l) {
  return l.tension_only && (l.rope_ends > 1 || l.sheave_efficiency < 1.0);
}

/// The name of body `body` for display, or `given` (the name the file wrote, Link::given_a etc.) when
/// not empty; "ground" for kGround.
std::string shown_body(const Model& m, int body, const std::string& given);
/// Link l's ratio as the file gives it, for display beside the given names: compile divides it by ρ
/// when its first end is a body an ideal gear slaves (RigidSlave), this multiplies it back.
double shown_ratio(const Model& m, const Link& l);
/// A constant load's value as the file gives it, for display: compile reduces it by ρ when its body
/// is slaved (Load::ratio), this divides it back. Other kinds: Load::value.
double shown_value(const Model& m, const Load& ld);

/// Unit suffixes for output columns: "rad" or "m", "rad/s" or "m/s", "N*m" or "N".
const char* position_unit(BodyKind k);
const char* velocity_unit(BodyKind k);
const char* load_unit(BodyKind k);
/// The unit of a link's load: that of body b (or a, for a link to the ground).
const char* link_load_unit(const Model& m, const Link& l);
/// A unit as a suffix of an output column name: "N*m" → "N_m", "rad/s" → "rad_s".
std::string unit_suffix(const char* unit);
/// The columns every simulation writes: "t_s", then per body "NAME.position_rad|m" and
/// "NAME.velocity_rad_s|m_s", then per link "NAME.load_N_m|N".
std::vector<std::string> chain_column_names(const Model& m);

/// The bodies that release mass (Model::releases), ascending, each once: a run writes the column
/// "NAME.mass_kg" (translational) or "NAME.inertia_kg_m2" (rotational) of its current inertia.
std::vector<int> released_bodies(const Model& m);

/// Output columns a run of `m` holds in memory, at most: the chain columns, three per contact or
/// brake, one per gap, up to eight per machine body (its parts' loads, output point, extras),
/// three per drive (torque, and current or reference speed, and the limiter mode), one per released
/// body, one per body with prescribed motion (its driving force), four per lossy gear (mode, the torques at its two bodies, loss power), one per merged ideal gear (its torque) and one per thermal model.
std::size_t output_columns_bound(const Model& m);
/// Bytes the output grid of `m` needs in memory, at most: (t_end/dt_out + 2) rows × output_columns_bound
/// × 8 bytes. The runs reserve all of it before the first step, so compile checks it against
/// kMaxOutputBytes first (a located input error at dt_out, instead of std::bad_alloc mid-run).
double output_bytes_bound(const Model& m);
inline constexpr double kMaxOutputBytes = 2.0 * 1024 * 1024 * 1024;  ///< 2 GiB

}  // namespace machdyn
