#pragma once
/// @file
/// A brute-force reference simulator of small translational drive lines (tests only, issue 27): the
/// independent answer the random campaign compares the engine with. Written from docs/model-files.md
/// and docs/hybrid.md alone; it calls none of the engine's element laws, decision code, steppers or
/// compile. Deliberately simple and slow:
///
/// - state y = [q; v] of n ≤ 8 bodies (SI: m, m/s, kg, N); in a mode
///     M a = f(t, q, v) − Σ_sliding r_k s_k F_k(t) − Gᵀ λ,   G a = 0,
///   r_k = e_A − e_B the element's row (the ground left out), G the rows of the stuck elements;
///   λ = (G M⁻¹ Gᵀ)⁻¹ G M⁻¹ f̃; where two stuck elements lock one motion the weighted least norm
///   min Σ λ²/W (W = F_s,k(t), a lock 1: the locked load shared in proportion to the static
///   limits; a lock loaded against its hold direction takes no share), and where that leaves an
///   element beyond its bounds (|λ| ≤ F_s, lock·λ ≥ −F_drag) the same problem within the bounds,
///   solved by enumerating its active sets (docs/hybrid.md, "Redundant locks: the bounded split");
/// - classical fixed-step RK4 with h = `omega_h`/ω_max (ω_max: the fastest spring or damper rate),
///   every step ending on the breakpoints of the signals and on the output rows;
/// - after every step every switching function is evaluated (gaps: distance or flank force; stuck
///   friction: F_s − |λ|; one-sided holds: lock·λ; sliding: s u; stops: the distance; the kink of the
///   elasto-backlash law) and the first crossing is bisected on a fresh RK4 step from the step's start
///   to 1e-13·max(1, t) s; the run continues just past the root;
/// - at an event the gaps that fired toggle, a stop that is reached takes its impact (its velocity
///   jump decides the flanks on the body again: a damped closed flank may open at once) (v⁺ = −e v⁻, rest
///   when e = 0, when the rebound's flight 2|v⁺|/|a| is below 1e-9·max(1, t) s — the engine's
///   1e-12 is below what a fixed-step run can resolve: the rounding of the position at the stop pumps
///   the bounces at ~1e-9 m/s — or when the rebound's height is a few ulps of the position), and the
///   modes of the friction elements at zero sliding speed are chosen by ENUMERATING every
///   combination (stuck / slip+ / slip−, a freewheel stuck / overrunning, a resting stop stuck /
///   leaving) and keeping the consistent ones: stuck within the limit (one-sided ones pressing, a
///   freewheel holding while λ ≥ −F_drag: at zero overrun speed its drag is a friction level, without
///   which a backward load below the drag has no consistent mode at all), sliding ones accelerating in
///   their direction. A decision that leaves a switching function negative is an error (it would
///   never be armed). Where several are consistent the documented rule picks (all stuck if that holds,
///   else release the most overloaded one after the other, else fewest sliding first); where the
///   consistent ones give different accelerations the run says so (`ambiguous_from`): the physics
///   is not unique there and a comparison after it is not meaningful.
///
/// Ideal gears (q_a = i q_b) are held as rows J of the inverse mass: a = P f with
/// P = M⁻¹ − M⁻¹Jᵀ(J M⁻¹ Jᵀ)⁻¹J M⁻¹ (no reduction to a master, as compile does); the stuck set's λ
/// solves (G P Gᵀ) λ = G P f̃.
///
/// Gear meshes (elastic, with backlash and efficiency) are force elements of their own: a mode per
/// mesh (the flank, or τ's sign without backlash, and the assumed signs σ_a, σ_b of the speeds, read
/// again where a speed crosses 0 on a flank: its sign after the instant, at 0 its acceleration's),
/// its switching functions those of a gap (the flank's c e + d Δ', the elasto-backlash kink) and
/// σ ω of each body on a flank.
///
/// Planetary gears are the Willis row e_sun + z e_ring − (1 + z) e_carrier of J (every member with
/// inertia). A model's bodies are all translational or all rotational (the same equations), but for
/// `linear` bodies of a rotational model: hooks slaved to drums by ideal gears in rad/m.
///
/// A prescribed body (speed or acceleration) has no row or column in P; its acceleration is the
/// signal's (a speed's right slope), so a stuck contact's λ carries its neighbour along.
///
/// Spatial ropes (SwayRope) are force elements on a point-mass load's coordinates (or a planar rigid
/// load's x, z and ψ, pulled at a point of its own), a trolley, a bridge and a drum, written from
/// docs/sway.md: a mode per rope (taut, slack), its switching function F (taut) or −e (slack); a
/// ground stop under the load's z makes the lift-off. No jib.
///
/// Two-stage lossy gearboxes (LossyTrain) are solved by reducing the train from its last body inward
/// (each stage's relation turns the bodies behind it into an inertia and a force on its input), their
/// mode (stuck, or rolling in s with each stage's driving side) decided at every event by enumerating
/// the directions and side combinations; switching functions: stuck, −s α_s for both s; rolling, s v_a
/// (rest) and each stage's side function s X or −s Y.
///
/// Limits (what the generator respects): link ratio 1, no lossy gears but two-stage trains, massless gear members, `position`
/// motions, buffers other than linear, drives other than the DC motor, machines; releases only on free bodies without gears, at t_r > 0;
/// prescribed bodies only with contacts to free bodies (no ground friction, freewheel, stop or gear on
/// them), a speed without jumps; at most two friction elements to the ground on a planetary gear's
/// members (three would lock it redundantly, where the engine weights the joint's row in the share);
/// signals of every kind but `sum` and `file` (expressions only of the form c0 + c1 t + A sin(2π f t +
/// φ) + B e^(−t/τ)); speed-dependent kinetic levels (tables, Stribeck) only on contacts given by levels,
/// no moving surfaces; a contact's normal force stays positive; end stops only on bodies without
/// friction to another body and without gears (an impact through a stuck contact would need an impulsive
/// friction law); an ideal gear's slave carries no friction element and is the first end of its links; a
/// freewheel is the only friction element on its pair of bodies.

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace machdyn::reference {

/// A signal of time: every kind of docs/model-files.md ("Signals") but `sum` and `file`.
///   constant  value
///   step      `before` for t < t0, `value` from t0 on
///   ramp      `before` until t0, linear to `value` at t1
///   sine      `offset` before t0, then offset + A sin(2π f (t − t0) + phase)
///   table     piecewise linear through `points` (two points at one time: a jump, the second value
///             from that time on); outside the end values held, or with `extrapolate` the end
///             segments continued
///   pulse     `value` (high) for `width` at the start of each period P from t0, `count` times
///             (−1: no end), `before` (low) otherwise
///   expression  c0 + c1 t + A sin(ω t + phase) + B exp(−t/τ) (written as the expression language's
///             text; no breakpoints)
struct Signal {
  enum class Kind { constant, step, ramp, sine, table, pulse, expression } kind = Kind::constant;
  double value = 0.0;   ///< constant, step's and ramp's final value, pulse's high
  double before = 0.0;  ///< step and ramp: the value before; pulse: low
  double t0 = 0.0;      ///< step's time, ramp's start, sine's and pulse's start
  double t1 = 0.0;      ///< ramp's end
  double amplitude = 0.0, frequency_hz = 0.0, phase = 0.0, offset = 0.0;  ///< sine (expression: A, ω/(2π), phase, c0)
  std::vector<std::pair<double, double>> points;  ///< table: (t, s), t non-decreasing
  bool extrapolate = false;                       ///< table: `outside: extrapolate`
  double period = 0.0, width = 0.0;               ///< pulse
  long count = -1;                                ///< pulse: −1 = no end
  double slope = 0.0, decay = 0.0, tau = 1.0;     ///< expression: c1, B, τ
  [[nodiscard]] double at(double t) const;
  /// ds/dt on the right of t (a ramp's, a table segment's slope; 0 for steps and pulses).
  [[nodiscard]] double slope_at(double t) const;
  /// The times in [0, t_end] where the signal jumps or kinks (the stepper ends a step there); with
  /// `zeros`, also where it crosses zero (a clutch's or brake's normal force opening and closing).
  void breakpoints(std::vector<double>& out, double t_end, bool zeros = false) const;
};

constexpr int kGround = -1;

/// A body; with `motion` a prescribed motion (docs/model-files.md, "Prescribed motion"): q'' = a(t)
/// (`acceleration`, from q0, v0) or q' = v(t) (`speed`: q'' = dv/dt on the right, v(0) the start).
/// Its mass then weighs nothing (P has no row or column for it): every element on it still acts.
struct Body {
  Body() = default;
  Body(std::string name_, double m_, double q0_, double v0_) : name(std::move(name_)), m(m_), q0(q0_), v0(v0_) {}
  std::string name;
  double m = 1.0, q0 = 0.0, v0 = 0.0;  ///< kg, m, m/s
  bool linear = false;  ///< translational in a rotational model (a rope drum's hook: m, N)
  bool angular = false;  ///< rotational in a translational model (a spatial rope's drum: rad, kg·m², N·m)
  /// A coordinate of a point-mass load (a spatial rope's; its name LOAD.x, LOAD.y or LOAD.z): the
  /// model file writes the load's coordinates as one `type: point-mass` body LOAD; z carries −m g.
  bool load_coordinate = false;
  enum class Motion { free, acceleration, speed } motion = Motion::free;
  Signal prescribed;
  [[nodiscard]] double prescribed_acceleration(double t) const {
    return motion == Motion::acceleration ? prescribed.at(t) : prescribed.slope_at(t);
  }
};

/// A spring-damper link between bodies a and b (either may be kGround): δ = q_a − q_b, the load F
/// acts on b with +F and on a with −F (docs/model-files.md, Links).
struct Link {
  enum class Kind { plain, gap, one_sided, rope } kind = Kind::plain;
  std::string name;
  int a = 0, b = 1;
  double c = 0.0, d = 0.0;     ///< N/m, N·s/m
  double gap = 0.0, gap_start = 0.0;  ///< gap: Δ and the position inside it at δ = 0
  double flank = 0.0;          ///< one_sided: δ₊ (any sign); rope: the slack (≥ 0)
  bool elasto = false;         ///< flank_law: elasto-backlash
  /// A linear buffer (docs/model-files.md, Buffers) is this one-sided law against the ground:
  /// `max` x_b is [body, ground] with δ₊ = x_b, `min` x_b is [ground, body] with δ₊ = −x_b (the file
  /// writes it under `buffers:`).
  bool buffer = false;
  [[nodiscard]] bool has_flanks() const { return kind != Kind::plain; }
  [[nodiscard]] double hi() const { return kind == Kind::gap ? gap - gap_start : flank; }  ///< δ₊
  [[nodiscard]] double lo() const {  ///< δ₋ (−∞ for a one-sided link or rope)
    return kind == Kind::gap ? -gap_start : -std::numeric_limits<double>::infinity();
  }
};

struct Load {
  std::string name;
  int body = 0;
  Signal s;
};

/// A friction element. Sliding velocity u = v_a − v_b (v of kGround = 0); while sliding in s = sign u
/// it loads b with +s F_k and a with −s F_k; stuck, with +λ and −λ.
struct Friction {
  enum class Kind { contact, brake, clutch, freewheel, stop } kind = Kind::contact;
  std::string name;
  int a = 0, b = kGround;
  // contact: levels, given directly or as normal force and coefficients (F = N μ); the normal force
  // N(t) = `normal` when fN is a constant 0 signal, else fN (a signal kept positive by the generator)
  bool via_mu = false;
  double Fs = 0.0, Fk = 0.0, normal = 0.0, mu_s = 0.0, mu_k = 0.0;
  // brake on body a: holding = Fs, braking = Fk, applied over r(t) = 0 → 1 from `time` over `ramp`,
  // or (with_application) by the signal r(t) = `application` (0 released, 1 full levels)
  double time = 0.0, ramp = 0.0;
  bool with_application = false;
  Signal application;
  // clutch between a and b: F = μ f_N(t) (f_N ≤ 0 opens it)
  Signal fN;
  // freewheel [a, b] (a may be kGround: a backstop on b): holds while λ ≥ 0, overruns with u < 0
  double drag = 0.0;
  // contact with levels: F_k0(s) a table [(s, F)] from s = 0 (held beyond its ends), or the Stribeck
  // law F_k0(s) = F_k + (F_s − F_k) exp(−(s/w_s)^δ) (stribeck_speed w_s > 0)
  std::vector<std::pair<double, double>> kinetic_table;
  double stribeck_speed = 0.0, stribeck_exponent = 1.0;
  // stop on body a: `min` (stop_max false) or `max` at stop_pos, restitution e
  bool stop_max = false;
  double stop_pos = 0.0, e = 0.0;

  [[nodiscard]] bool one_sided() const { return kind == Kind::freewheel || kind == Kind::stop; }
  /// The static limit F_s(t) and kinetic level F_k(t) (∞ / the drag for one-sided elements).
  [[nodiscard]] double static_limit(double t) const;
  /// F_k(t, s) at sliding speed s ≥ 0 (a contact's table or Stribeck law; the others constant in s).
  [[nodiscard]] double kinetic_level(double t, double speed = 0.0) const;
  /// Whether a brake or clutch is engaged at t (r > 0 or about to rise: the right limit).
  [[nodiscard]] bool engaged(double t) const;
  /// A brake's application r(t) ∈ [0, 1].
  [[nodiscard]] double application_at(double t) const;
  /// A contact's normal force N(t).
  [[nodiscard]] double normal_at(double t) const {
    return fN.kind == Signal::Kind::constant && fN.value == 0.0 ? normal : fN.at(t);
  }
  void breakpoints(std::vector<double>& out, double t_end) const;
};

/// An ideal gear (docs/model-files.md, "Ideal gears"): q_a = i q_b, rigid, no losses. Body b is
/// slaved to a (later in the file than a, no friction element on it, links on it only as their
/// first end, no other gear on it; a is no slave).
/// With `planetary`: a planetary gear (Willis) among sun a, ring b and carrier c, all with inertia:
/// ω_a + z ω_b − (1 + z) ω_c = 0, z = `ratio` > 1 (nobody slaved: a row of P like the ideal gear's).
struct Gear {
  std::string name;
  int a = 0, b = 1;
  double ratio = 1.0;  ///< i ≠ 0 (planetary: z = z_ring/z_sun > 1)
  bool planetary = false;
  int c = -1;          ///< planetary: the carrier
};

/// A release (docs/model-files.md, "Releases"): body `body` loses Δm at t_r > 0, its position and
/// velocity continuous.
struct Release {
  std::string name;
  int body = 0;
  double dm = 0.0, t = 0.0;  ///< kg (kg·m²), s
};

/// An elastic gear mesh (docs/model-files.md, "Elastic gear mesh"; `type: gear-mesh` under `links:`)
/// between a pinion a and a wheel b, both rotational with inertia: deflection Δ = φ_a − i φ_b at the
/// pinion; the tooth moment τ the elasto-backlash flank law of a gap with flanks ±b/2 (b = 0: τ =
/// c Δ + d Δ', both flanks in contact); torques −τ on the pinion and i τ on the wheel, the efficiency
/// η on the driven side: the pinion drives (τ ω_a > 0 and τ i ω_b > 0, the speeds' signs as assumed
/// by the mode: a speed at 0 keeps its sign) → the wheel gets η i τ; the wheel drives (both < 0) →
/// the pinion gets −η τ; otherwise the ideal torques.
struct Mesh {
  std::string name;
  int a = 0, b = 1;
  double i = 1.0, c = 0.0, d = 0.0, backlash = 0.0, eta = 1.0;  ///< ratio, N·m/rad, N·m·s/rad, rad, η ∈ (0, 1]
};

/// A DC motor (docs/model-files.md, Drives): L di/dt = u(t) − R i − k v, force k i on its body; the
/// current i is a state of its own (after [q; v]).
struct DcMotor {
  std::string name;
  int body = 0;
  double R = 1.0, L = 0.01, k = 1.0, i0 = 0.0;  ///< Ω, H, N/A (= V·s/m), A
  Signal u;                                     ///< V
};

/// A spatial rope (docs/sway.md, docs/model-files.md "Spatial rope"; `type: spatial-rope`): a
/// point-mass load r = (x, y, z) (its coordinate bodies, y or x may be absent: 0) on a rope from the
/// suspension point p = (x_t, y_b, h) (a trolley's and a bridge's positions, 0 without; a fixed
/// height), its free length per fall L(φ) = L0 − s (φ − φ0), s = R/n, set by a drum's angle φ (φ0
/// its initial angle; L0 without a drum). ℓ = |p − r|, u = (p − r)/ℓ, e = ℓ − L, ė = u·(ṗ − ṙ) + s φ̇.
/// Taut: F = c e + d ė with c = n EA/L(φ); slack: F = 0. Forces: the load F u, the trolley −F u_x,
/// the bridge −F u_y, the drum −F s − ½ (dc/dφ) e² (dc/dφ = n EA s/L²). Modes taut (slack where
/// F reaches 0) and slack (taut where e reaches 0). A load's z body (a `load_coordinate` body named
/// LOAD.z) carries −m g (RefModel::g), with or without a rope.
/// A rigid load (docs/sway.md, docs/model-files.md "Rigid loads"; `type: rigid-load`, planar in x, z):
/// its centre c = (x, z) and its angle ψ (the rotational body LOAD.psi of inertia J, no weight); the
/// rope pulls at its point r = c + R(ψ) a, a = (a_h, a_z) the rope's `attach` point in the load's
/// frame, R(ψ) turning the horizontal axis towards z: r_h = x + a_h cos ψ − a_z sin ψ,
/// r_z = z + a_h sin ψ + a_z cos ψ; the suspension point lies `offset` d along x from the trolley's
/// (the two ropes of a spreader). The pull F u at r: F u on the centre's coordinates and the moment
/// F u · ∂r/∂ψ = F (u_h (−a_h sin ψ − a_z cos ψ) + u_z (a_h cos ψ − a_z sin ψ)) on ψ.
struct SwayRope {
  std::string name, load;  ///< the rope's and the point-mass load's names
  int x = -1, y = -1, z = 0;  ///< the load's coordinate bodies (x or y −1: absent)
  int psi = -1;               ///< a rigid load's angle body (−1: a point mass)
  int trolley = -1, bridge = -1, drum = -1;
  double L0 = 1.0, EA = 1e5, falls = 1.0, d = 0.0, h = 1.0, R = 0.1;  ///< m, N, -, N·s/m, m, m
  double attach[2] = {0.0, 0.0};  ///< a rigid load's rope point (a_h, a_z) in its frame, m
  double offset = 0.0;            ///< the suspension point's offset along x, m
};

/// A two-stage lossy gearbox (docs/model-files.md "Two stages", docs/hybrid.md "Modes" step 5): the
/// lossy gear `name1` between a and m (v_a = i1 v_m) and `name2` between m and c (v_m = i2 v_c), ratios
/// > 0, no bearing friction. Each gear: X the torque its side a delivers into it, Y the torque it
/// delivers to side b (its body b receives i Y, a receives −X); side a drives (power a → b): Y = e X,
/// side b drives: X = r Y (e, r: `efficiency`, `efficiency_reverse`); rolling in s = sign(v_a) side a
/// drives while s X ≥ 0, side b while s Y ≤ 0. At rest the train starts in s where the rolling motion
/// in s with consistent sides has s α > 0, else it is stuck (every speed 0). No friction element,
/// ideal gear or mesh on its bodies.
struct LossyTrain {
  std::string name1, name2;
  int a = 0, m = 1, c = 2;
  double i1 = 1.0, i2 = 1.0, e1 = 1.0, r1 = 1.0, e2 = 1.0, r2 = 1.0;
};

struct RefModel {
  bool rotational = false;  ///< every body rotational (φ in rad, kg·m², N·m): the same equations
  std::vector<Body> bodies;
  std::vector<Gear> gears;
  std::vector<Link> links;
  std::vector<Load> loads;
  std::vector<Friction> frictions;
  std::vector<Release> releases;
  std::vector<DcMotor> motors;
  std::vector<Mesh> meshes;
  std::vector<SwayRope> sway;
  std::vector<LossyTrain> trains;
  double g = 9.80665;  ///< gravity on the loads' z bodies, m/s²
  double t_end = 1.0, dt_out = 0.01;
};

/// The engine's absolute tolerance in the campaign (to_yaml: rtol 1e-10, atol 1e-12): a lock's hold
/// allowance ε_h = hold_allowance(k, atol) (machdyn/elements/hold_allowance.hpp, the one allowance of
/// the engine, its audit and this reference: the resolution of λ) is formed with it.
constexpr double kCampaignAtol = 1e-12;

/// The resolution of a load the integration forms, relative to the model's force scale: an event
/// function of loads (a stuck contact's F_s − |λ|, a freewheel's lock·λ + F_d + ε_h) is known to
/// δ = kLoadResolution × that scale — the engine at rtol 1e-10 accumulates 1e3 rtol over a run (the
/// allowance of its energy books), the reference's own error is 4.4e-8 of a velocity's scale
/// (self-convergence, reference_test.cpp).
constexpr double kLoadResolution = 1e-7;

struct RefEvent {
  double t = 0.0;
  std::string kind;     ///< gap_closed, gap_opened, stick, slip, reversal, impact, applied; a gear mesh's
                        ///< `mesh` (on a flank: contact, a body reversing, b = 0: τ changing sign)
                        ///< and `free play` (the contact ends)
  std::string element;
  /// s: how well the model itself fixes the instant — the time before t over which the function
  /// that fired lies within its resolution δ of its value at t (0: sharper than 1e-7 s, or an
  /// instant of a signal). A root of multiplicity k, g ≈ c (t − t₀)^k, moves by (δ/c)^(1/k) for an
  /// error δ in g: a freewheel whose load grows from 0 as c (t − t₀)⁶ through a chain of springs
  /// slips where it passes the allowance ε_h of the hold rule, and 1e-11 N of λ, far below any
  /// integration's resolution of the loads, moves that instant by 1e-6 s. Events at the same instant
  /// as the one that fired (its decision's) share its window.
  double window = 0.0;
  /// The event time's sensitivity to the state of one body, for the campaign's tolerance of this
  /// event (campaign.hpp): an event at a zero of g(x) moves by δg/|ġ| when the state moves by δx.
  /// body −1: none (the fixed tolerance alone); else the tolerance is
  /// dt_dq δq + dt_dsqrtq √δq + dt_dv δv of that body (and of body2: δq, δv are the sums over
  /// both). A gap closing (g the distance δ₊ − δ or δ − δ₋ of its flank, |ġ| = |v_a − v_b|), or
  /// opening from a flank without damping (g = c e): dt_dq = 1/|v_a − v_b| on its two bodies; a damped flank opening
  /// (g = c e + d δ̇, δg = c δq + d δv): dt_dq = c/|ġ|, dt_dv = d/|ġ|, ġ = c δ̇ + d δ̈ in the closed mode. An end stop's impact at speed v⁻ (g its
  /// distance, |ġ| = |v⁻|): dt_dq = 1/|v⁻|. A plastic rest (e = 0) is that impact. The rest that
  /// ends a series of bounces (e > 0) is the accumulation instant t∞ = t_k + 2 e v_k/(a (1 − e)),
  /// from any bounce k at speed v_k under the acceleration a towards the stop: an offset δq of the
  /// body at bounce k moves t_k by δq/v_k and v_k by a δq/v_k, so t∞ by (δq/v_k)(1 + e)/(1 − e);
  /// a bounce is resolved by the position only while its apex height v_k²/(2a) exceeds δq, so
  /// v_k ≥ √(2 a δq) and dt_dsqrtq = (1 + e)/((1 − e) √(2a)); a velocity error moves it by
  /// dt_dv = 2 e/(a (1 − e)); and dt_dq = 1/|v₀| of the series' first impact. A slide ending where
  /// its u = v_a − v_b reaches 0 (its `stick` or `reversal`; g = s u, |ġ| = |u̇| in the slide):
  /// dt_dv = 1/|u̇| on its two bodies.
  /// A gear mesh's free play reaching a flank, or its undamped contact ending (g the distance to the
  /// flank, or c e, with Δ = φ_a − i φ_b: |ġ| = |Δ'|): dt_dq = 1/|Δ'| on the pinion and the wheel,
  /// the wheel's δq, δv weighted by i (w2).
  int body = -1, body2 = -1;
  double w2 = 1.0;         ///< the weight of body2's δq, δv (1; a gear mesh's wheel: its ratio i)
  double dt_dq = 0.0;      ///< s/m
  double dt_dsqrtq = 0.0;  ///< s/√m
  double dt_dv = 0.0;      ///< s/(m/s)
};

struct RefOptions {
  double omega_h = 0.02;  ///< h ω_max of the fixed step (its error: ReferenceSimulator.ConvergesWithTheStep…)
  double h_max = 2e-3;    ///< s, upper bound of the step (also for models without springs)
  long max_events = 20000;
};

struct RefResult {
  std::vector<double> t;                  ///< the output rows k dt_out, k = 0 … round(t_end/dt_out)
  std::vector<std::vector<double>> q, v;  ///< [row][body]
  std::vector<std::vector<double>> lam;  ///< [row][friction element] its stuck load λ (0 unless stuck)
  std::vector<RefEvent> events;
  /// Where the consistent mode combinations gave different accelerations (the documented rule chose
  /// one): +∞ when never. Compare only before it.
  double ambiguous_from = std::numeric_limits<double>::infinity();
  std::string error;                      ///< non-empty: the reference could not run (why)
  long steps = 0;
};

/// Runs the reference simulation of `m`. Never throws for a model the generator makes; a model it
/// cannot run (chattering, no consistent mode) returns with `error` set.
RefResult simulate_reference(const RefModel& m, const RefOptions& o = {});

}  // namespace machdyn::reference
