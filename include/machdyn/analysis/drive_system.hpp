#pragma once
/// @file
/// The one system of equations every model runs through: bodies, links (elements/link.hpp),
/// friction contacts and brakes (elements/contact.hpp), loads and machines, flattened once.
///
/// State y = [q; v; x] (n positions, n velocities, then the states x of the elements with states of
/// their own, e.g. a DC motor's current: model/element.hpp, in the order of Model::drives), plus three energy quadratures [W_src;
/// E_fric; E_damp] when the energy books are kept (DriveSystem(m, true): every event-driven run).
/// Every switching element is in a definite mode and the equations of a mode hold until an event:
///   gap link     open (F = 0), closed+ on the positive flank, closed- on the negative one
///   contact      stuck (u ≡ 0, a bilateral velocity constraint) or sliding in direction ±1
///   element      an element with states of its own in the mode its interface defines (a speed
///                drive's torque limiter linear or limited±: elements/speed_drive.hpp)
///   lossy gear   stuck, or rolling forward/backward with side a or b driving (elements/lossy_gear.hpp):
///                its torques X, Y are solved from the forces on its two bodies after every other
///                force, then a_b = a_a / i exactly; friction elements to the ground on its bodies
///                slide while it rolls and are decided with it at rest (analysis/gear_lock.hpp); a
///                clutch from one of its bodies to another body is decided with it (analysis/gear_clutch.hpp)
/// In a mode:  M(q) v' = f(t, q, v) − Jᵀ F_links − Gᵀ λ − Σ_sliding ĝ_k F_k,
/// where row k of G is the sliding velocity u_k = v_a − v_b of stuck contact k and λ solves
///   (G M⁻¹ Gᵀ) λ = G M⁻¹ f̃ − ẇ     (f̃: all forces but λ; ẇ: the prescribed surface acceleration).
/// G M⁻¹ Gᵀ is singular when two stuck contacts lock one motion; λ is then the weighted least-norm
/// solution (minimum Σ λ_k² / F_s0,k): the locked load is shared in proportion to the static limits,
/// so the motion stays locked exactly while it is within their sum. A one-sided contact (freewheel,
/// end stop: elements/contact.hpp) takes no share of a load against its lock while the others lock
/// the same motion: if its weighted share has lock·λ < 0 and the others alone carry every load
/// (rank unchanged without it), λ is the weighted least-norm solution with its share fixed at 0 —
/// continuous where its share passes 0, and the accelerations are the same for every share. So a
/// freewheel parallel to a holding clutch stays stuck, unloaded, and a body resting on an end stop
/// held by friction stays on the stop. The pseudo-inverse is formed once
/// per set of stuck contacts (complete orthogonal decomposition, rank threshold 1e-12) and cached.
///
/// Bodies with position-dependent inertia (Body::machine, model/machine.hpp): M(q) = diag(I_i(q_i)),
/// the velocity terms −½ I_i′ q_i'² and the machines' forces Q_i(q_i) join f̃ (the Lagrangian form of
/// model/machine.hpp), and links may attach to a machine's output point p(q). When a stuck contact
/// touches a machine, G M(q)⁻¹ Gᵀ is formed at every evaluation. The work of Q counts as source work;
/// the kinetic energy is ½ Σ I_i(q_i) v_i².
///
/// Fast paths, chosen once (each computes the same law): a small chain without events (n ≤ 8, no
/// machines, no energy books, no drives) as fixed-size dense products; within one mode with constant loads and
/// friction levels and no dampers, the whole right-hand side as a cached affine map per mode.
///
/// Jacobian: without energy books (no gaps, no contacts) analytic and sparse for constant inertias
/// (KLU for large systems), by central differences with machines; with energy books none (CVODE
/// forms its own by differences).

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "machdyn/analysis/gear_lock.hpp"
#include "machdyn/analysis/gear_train.hpp"
#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/elements/lossy_gear.hpp"
#include "machdyn/elements/modes.hpp"
#include "machdyn/elements/prescribed_motion.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/solve/ode_system.hpp"

namespace machdyn {

class Machine;

class DriveSystem final : public OdeSystem {
 public:
  /// Keeps a reference: `model` must outlive the system. `energy_books`: carry the three energy
  /// quadratures in the state (source work, friction and damping losses).
  DriveSystem(const Model& model, bool energy_books);

  [[nodiscard]] int size() const override { return 2 * n_ + nx_ + (energy_ ? 3 : 0); }
  /// Inline: the small affine maps (a small chain, a mode's map) are the whole right-hand side.
  void rhs(double t, const double* y, double* dydt) override {
    if (const AffineRows* a = fast_) {  // q̇ = v, then the rows of v̇ (and the energy rates)
      a->apply(y, dydt);
      return;
    }
    rhs_other(t, y, dydt);
  }
  [[nodiscard]] bool has_jacobian() const override { return !energy_ && ng_ == 0; }
  void jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) override;
  [[nodiscard]] bool has_sparse_jacobian() const override { return !energy_ && !has_machines_ && ng_ == 0; }
  void sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) override;
  [[nodiscard]] std::string state_name(int i) const override;

  [[nodiscard]] int dof() const { return n_; }
  [[nodiscard]] bool energy_books() const { return energy_; }
  /// Index of the energy states in y (energy books only): source work, friction loss, damping loss.
  [[nodiscard]] int energy_index() const { return 2 * n_ + nx_; }
  /// y0 from the bodies' initial positions and velocities, the drives' initial states, zero energies.
  void initial_state(double* y) const;

  // Releases (model.hpp: Release): the masses are run state, the Model keeps those at t = 0.
  /// Applies release r at its instant: its body's inertia drops by ΔI and its constant load changes
  /// by the release's weight_change; the dense chain, the affine modes and the stuck contacts'
  /// projectors are formed again for the new mass matrix. The state y is not touched (position and
  /// velocity are continuous); the run restarts the stepper. Returns ½ ΔI v² at velocities `v` (n),
  /// the kinetic energy the released part carries away, J.
  double apply_release(const Release& r, const double* v);
  /// The current inertia of body i: I at t = 0 less the releases applied, kg·m² or kg (a machine's
  /// I(q0) for a body with variable inertia).
  [[nodiscard]] double inertia(int i) const { return inertia_[static_cast<size_t>(i)]; }

  // Modes.
  [[nodiscard]] GapMode gap_mode(int l) const { return gap_[static_cast<size_t>(l)]; }
  [[nodiscard]] ContactMode contact_mode(int k) const { return mode_[static_cast<size_t>(k)]; }
  void set_gap_mode(int l, GapMode g) {
    gap_[static_cast<size_t>(l)] = g;
    mode_changed();
  }
  /// Sets all contact modes and forms the constraint solution of the stuck set.
  void set_contact_modes(const std::vector<ContactMode>& modes);
  [[nodiscard]] const std::vector<ContactMode>& contact_modes() const { return mode_; }
  /// The gap mode a state implies on its own (initial state): closed on a flank it presses.
  [[nodiscard]] GapMode natural_gap_mode(int l, const double* y) const;

  // Elements with states of their own (`drives:`, model/element.hpp), called through their
  // interface only: their states x_d start at y[drive_offset(d)], their modes are ints.
  [[nodiscard]] int drive_count() const { return nd_; }
  [[nodiscard]] const Element& drive(int d) const { return *drives_[static_cast<size_t>(d)]; }
  /// Its (first) body; a drive on a joint member without inertia acts on two (drive_place).
  [[nodiscard]] int drive_body(int d) const { return drive_body_[static_cast<size_t>(d)]; }
  /// Where element d acts: its bodies and weights (model.hpp: Drive::terms, spread).
  [[nodiscard]] const Drive& drive_place(int d) const { return m_.drives[static_cast<size_t>(d)]; }
  /// The velocity ω the element sees: Drive::own over the bodies' velocities (its body's velocity
  /// for a drive on one body).
  [[nodiscard]] double drive_speed(int d, const double* y) const { return drive_place(d).own(y + n_); }
  [[nodiscard]] int drive_offset(int d) const { return drive_off_[static_cast<size_t>(d)]; }
  [[nodiscard]] int drive_mode(int d) const { return drive_mode_[static_cast<size_t>(d)]; }
  void set_drive_mode(int d, int md) { drive_mode_[static_cast<size_t>(d)] = md; }
  /// The mode element d's state implies on its own (initial state, time events; Element::natural_mode,
  /// with the body's acceleration where the element reads it).
  [[nodiscard]] int natural_drive_mode(int d, double t, const double* y);
  /// The mode of element d after its event switches it to `now` (Element::settle where it settles).
  [[nodiscard]] int settle_drive_mode(int d, double t, const double* y, int now);
  /// What element d sees of its bodies at y (Drive::at over positions and velocities; the
  /// accelerations from acc where given, else 0).
  [[nodiscard]] ElementMotion drive_motion(int d, const double* y, const double* acc = nullptr) const {
    const Drive& p = drive_place(d);
    ElementMotion b;
    b.n = p.ports();
    for (int i = 0; i < b.n; ++i) {
      b.q[i] = p.at(y, i), b.v[i] = p.at(y + n_, i);
      if (acc) b.a[i] = p.at(acc, i);
    }
    return b;
  }
  /// What element d sees at (t, y) for its forces and columns: drive_motion(), and on a port it holds
  /// (Element::held_port) the other forces on that body (ElementMotion::load, from the free forces).
  [[nodiscard]] ElementMotion drive_motion_at(int d, double t, const double* y) const;
  /// The body of element d's port p, or −1 for a port spread over two bodies.
  [[nodiscard]] int port_body(int d, int p) const;
  /// The forces M_p of element d on its ports into M (Element::forces).
  void drive_forces_of(int d, double t, const double* y, double* M) const {
    drive(d).forces(t, drive_motion_at(d, t, y), y + drive_offset(d), drive_mode(d), M);
  }
  /// The torque (or force) M_0 of element d at its own point (on its first body; Drive::spread puts it
  /// on the bodies), N·m or N.
  [[nodiscard]] double drive_torque(int d, double t, const double* y) const {
    double M[ElementMotion::kMax] = {};
    drive_forces_of(d, t, y, M);
    return M[0];
  }
  /// Adds element d's forces on every body it acts on to f (Drive::spread_all).
  void drive_spread(int d, double t, const double* y, double* f) const {
    double M[ElementMotion::kMax] = {};
    drive_forces_of(d, t, y, M);
    drive_place(d).spread_all(M, f);
  }
  /// The power element d puts into its bodies, Σ_p M_p v_p, W.
  [[nodiscard]] double drive_power(int d, double t, const double* y) const {
    const ElementMotion b = drive_motion_at(d, t, y);
    double M[ElementMotion::kMax] = {};
    drive(d).forces(t, b, y + drive_offset(d), drive_mode(d), M);
    double P = M[0] * b.v[0];
    for (int i = 1; i < b.n; ++i) P += M[i] * b.v[i];
    return P;
  }
  /// Element d's own output columns at (t, y) (Element::outputs) into out.
  void drive_outputs(int d, double t, const double* y, double* out) const {
    drive(d).outputs(t, drive_motion_at(d, t, y), y + drive_offset(d), drive_mode(d), out);
  }

  // Lossy gears (elements/lossy_gear.hpp), in the order of Model::lossy_gears.
  [[nodiscard]] int gear_count() const { return ng_; }
  [[nodiscard]] const LossyGearLaw& lossy_gear(int g) const { return gears_[static_cast<size_t>(g)]; }
  [[nodiscard]] GearMode gear_mode(int g) const { return gear_mode_[static_cast<size_t>(g)]; }
  /// The mode of the last evaluation: gear_mode(g), except for a gear with a prescribed side, whose
  /// mode every evaluation decides (elements/lossy_gear.hpp "Prescribed side"; the output column).
  [[nodiscard]] GearMode gear_mode_now(int g) const {
    return gear_motion_[static_cast<size_t>(g)] >= 0 ? gear_now_[static_cast<size_t>(g)] : gear_mode(g);
  }
  void set_gear_mode(int g, GearMode md) { gear_mode_[static_cast<size_t>(g)] = md; }
  /// The mode gear g takes at (t, y), the other elements in their modes (LossyGearLaw::decide);
  /// `strict`: its event fired, no rounding allowance on the start margins.
  [[nodiscard]] GearMode natural_gear_mode(int g, double t, const double* y, bool strict);
  /// Gear g's torques X, Y and the acceleration of its body a at (t, y) in its mode.
  [[nodiscard]] LossyGearLaw::Torques gear_torques(int g, double t, const double* y);
  /// Puts both bodies of gear g exactly at rest (its speed reached zero: decided at rest, as a contact);
  /// a gear of a two-stage train (analysis/gear_train.hpp) with all the train's bodies.
  void stop_gear(int g, double* y) const;
  /// The two-stage train gear g belongs to (analysis/gear_train.hpp), −1 for none.
  [[nodiscard]] int gear_train_of(int g) const { return train_of_gear_[static_cast<size_t>(g)]; }
  [[nodiscard]] const GearTrain& gear_train(int t) const { return trains_[static_cast<size_t>(t)]; }
  /// The friction elements to the ground on the gears' bodies (analysis/gear_lock.hpp). While a gear
  /// is stuck with them, evaluate() reports the split of the holding torque and event_functions() the
  /// joint margins in the gear's slots (its contacts' slots read 1: the gear's events are theirs).
  [[nodiscard]] const GearLocks& gear_locks() const { return locks_; }
  /// F_a, F_b: the forces on gear g's bodies from everything but the gear and the stuck loads of its
  /// contacts, at (t, y) in the current modes.
  void gear_loads(int g, double t, const double* y, double* Fa, double* Fb);
  /// Gears with a clutch (a friction contact between one of their bodies and another body) on their
  /// bodies (analysis/gear_clutch.hpp): in such a model the stuck contacts are solved with the gears'
  /// compliance, and F_a, F_b (gear_loads) include the stuck clutches' loads.
  [[nodiscard]] bool has_coupled_gears() const { return coupled_; }
  [[nodiscard]] bool coupled_gear(int g) const { return coupled_ && gear_clutch_[static_cast<size_t>(g)] != 0; }
  /// The lossy gear body i belongs to, −1 for none.
  [[nodiscard]] int gear_of_body(int i) const { return gear_of_body_[static_cast<size_t>(i)]; }
  /// Puts every rolling coupled gear on the driving side consistent with the current contact modes
  /// (analysis/gear_clutch.hpp; analysis/gear_clutch.cpp).
  void settle_gear_sides(double t, const double* y);

  // Prescribed motions (elements/prescribed_motion.hpp), in body order: such a body has inverse
  // inertia 0 (infinitely heavy for stuck contacts and every mass-weighted split) and q'' = a(t).
  [[nodiscard]] int motion_count() const { return static_cast<int>(motions_.size()); }
  [[nodiscard]] const PrescribedMotionLaw& motion(int j) const { return motions_[static_cast<size_t>(j)]; }
  /// The force R of motion j's source at the last evaluate() (or rhs), N·m or N.
  [[nodiscard]] double motion_force(int j) const { return motion_f_[static_cast<size_t>(j)]; }

  [[nodiscard]] const LinkLaw& link(int l) const { return links_[static_cast<size_t>(l)]; }
  [[nodiscard]] const ContactLaw& contact(int k) const { return contacts_[static_cast<size_t>(k)]; }

  // Quantities in the current modes.
  [[nodiscard]] LinkLaw::Kinematics link_kinematics(int l, const double* y) const {
    const LinkLaw& k = links_[static_cast<size_t>(l)];
    if (k.point) [[unlikely]] return point_kinematics(l, y);
    return {k.linear(y), k.linear(y + n_), k.inv_ratio, 1.0};
  }
  [[nodiscard]] double link_load(int l, const double* y) const {  ///< F of link l
    const LinkLaw::Kinematics s = link_kinematics(l, y);
    const LinkLaw& k = links_[static_cast<size_t>(l)];
    return k.load(s.delta, s.rate, gap_[static_cast<size_t>(l)], k.drum(y));
  }
  /// The rate dF/dt of link l from the state y and its derivative dy (0 if open).
  [[nodiscard]] double link_load_rate(int l, const double* y, const double* dy) const {
    const LinkLaw& k = links_[static_cast<size_t>(l)];
    if (k.point) [[unlikely]] return point_load_rate(l, y, dy);
    return k.load_rate(y, dy, dy + n_, gap_[static_cast<size_t>(l)]);
  }
  /// Whether link l's load depends on q nonlinearly (a machine's output point).
  /// Whether link l's load rate needs the state itself (a machine's output point, the capped
  /// flank law, whose branch depends on δ and δ̇, or a winding rope's c(q_a)), not only its derivative.
  [[nodiscard]] bool link_rate_reads_state(int l) const {
    const LinkLaw& k = links_[static_cast<size_t>(l)];
    return k.point || k.capped || k.winding || k.shaped;
  }
  /// Whether some body has a position-dependent inertia or a link a machine's output point.
  [[nodiscard]] bool has_machines() const { return has_machines_; }
  [[nodiscard]] double sliding_velocity(int k, double t, const double* y) const {
    return contacts_[static_cast<size_t>(k)].sliding_velocity(t, y + n_);
  }
  /// The contact forces F_k of evaluate() alone (stuck: λ; sliding: ±F_k): from the mode's affine
  /// map where the model is affine in its state, without solving for the accelerations. Inline: a
  /// mode's small map of them is the whole call (output rows, event functions).
  void contact_forces(double t, const double* y, double* fc) {
    if (const AffineRows* f = force_fast_) {
      f->apply(y, fc);
      return;
    }
    contact_forces_other(t, y, fc);
  }
  /// Accelerations (n) and contact forces F_k (stuck: λ; sliding: ±F_k; size = contacts).
  void evaluate(double t, const double* y, double* acc, double* contact_force);
  /// Generalized external forces f (n): loads, machine forces and the contact forces `fc`.
  void external_forces(double t, const double* y, const double* fc, double* f) const;
  /// Kinetic and elastic energy, J.
  [[nodiscard]] double kinetic_energy(const double* y) const;
  [[nodiscard]] double elastic_energy(const double* y) const;
  /// The loads F of all links (link_load), in one call; with their rates (link_load_rate) from the
  /// state's derivative dy.
  void link_loads(const double* y, double* F) const;
  void link_loads_and_rates(const double* y, const double* dy, double* F, double* rate) const;

  // Events.
  /// Two per link, then two per contact, two per drive, two per lossy gear. Each is ≥ 0 while the
  /// mode holds.
  [[nodiscard]] int event_slots() const { return 2 * (nl_ + nc_ + nd_ + ng_); }
  void event_functions(double t, const double* y, double* g);
  /// The element of a slot: link index (slot < 2·links), contact index or drive index.
  [[nodiscard]] bool slot_is_link(int slot) const { return slot < 2 * nl_; }
  [[nodiscard]] bool slot_is_drive(int slot) const { return slot >= 2 * (nl_ + nc_) && slot < 2 * (nl_ + nc_ + nd_); }
  [[nodiscard]] bool slot_is_gear(int slot) const { return slot >= 2 * (nl_ + nc_ + nd_); }
  /// The element of a slot: link, contact, drive or gear index.
  [[nodiscard]] int slot_element(int slot) const {
    return slot < 2 * nl_            ? slot / 2
           : slot < 2 * (nl_ + nc_)  ? (slot - 2 * nl_) / 2
           : slot_is_gear(slot)      ? (slot - 2 * (nl_ + nc_ + nd_)) / 2
                                     : (slot - 2 * (nl_ + nc_)) / 2;
  }

  /// Sets the sliding velocity of contact k to exactly 0 by the M-orthogonal (momentum-keeping)
  /// velocity change Δv_a = −u/(m_a (1/m_a + 1/m_b)), Δv_b = +u/(m_b (…)): a contact decided at zero
  /// speed (stick, or slide/reverse from rest) starts its new mode at u = 0, not at the ~1e-13 s
  /// location error beyond it — else a sliding mode would start already past its own event.
  void zero_sliding_velocity(int k, double t, double* y) const;
  /// Projects the velocities onto the stuck constraints (M-orthogonally): u_k = 0 exactly.
  void project_velocities(double t, double* y) const;

  /// Evaluates body i's machine (inertia, force, output point) at q clamped to [lo, hi]. For
  /// machines with velocity jumps (stepwise gears) the run keeps this window inside the current
  /// piece, so that a step ending a hair beyond a jump position (the re-integration up to the
  /// located event) does not see the next piece's inertia. Default: no clamp.
  void set_evaluation_window(int body, double lo, double hi);

  [[nodiscard]] const Model& model() const { return m_; }

 private:
  // kMach: the model has machines (position-dependent inertia, point links) or drives (their torques
  // and state rates). The constant-inertia instantiation is the plain code of the linear chain,
  // untouched by the machine and drive terms.
  template <bool kMach>
  void forces(double t, const double* y, double* f, double* fc, double* p_src, double* p_fric, double* p_damp);
  template <bool kMach>
  /// Accelerations and contact forces; the rates of source work, friction and damping losses.
  void evaluate_impl(double t, const double* y, double* acc, double* contact_force, double* src, double* fric,
                     double* damp);
  template <bool kMach>
  void rhs_general(double t, const double* y, double* dydt);
  /// Kinematics of a link to a machine's output point (out of line: the plain links stay inline).
  [[nodiscard]] LinkLaw::Kinematics point_kinematics(int l, const double* y) const;
  [[nodiscard]] double point_load_rate(int l, const double* y, const double* dy) const;
  /// The positions machines are evaluated at (y itself, or clamped into the evaluation windows).
  [[nodiscard]] const double* machine_positions(const double* y) const;
  /// I_i(q_i)⁻¹ of every body into `im` (constant bodies: 1/I).
  void inverse_inertias(const double* y, double* im) const;
  /// G M⁻¹ Gᵀ of the stuck set for the inverse inertias `im`.
  [[nodiscard]] Eigen::MatrixXd stuck_matrix(const double* im) const;
  /// P_ for the inverse inertias `im` and the share weights at t (machines in the stuck set, or a
  /// redundant set with a limit varying in t: at every evaluation).
  void form_stuck_solution(const double* im, double t);
  /// The weight of stuck contact k in the share of a locked load at t: √F_s(t), the static limit at t
  /// (a brake's or clutch's r(t) F_s0 with the rule's allowance, never 0; only in a redundant set with
  /// such a limit, timed_share_: elsewhere √F_s0, the weights do not change λ), so a load locked by several
  /// contacts is shared in proportion to their limits at that instant and stays locked exactly while it
  /// is within Σ F_s,k(t); a freewheel or end stop 1, a gear joint 1e3.
  [[nodiscard]] double share_weight(int k, double t) const;
  /// The one-sided rule of the share (header): moves the share of a redundant freewheel or end stop
  /// loaded against its lock to the other stuck contacts (lam_ from r_).
  void share_one_sided(const double* im, double t);
  /// Solves every lossy gear in its mode on the forces f (before the inertias divide them) and adds
  /// its torques; adds the losses to *p_fric (if given).
  void apply_gears(double t, const double* y, double* f, double* p_fric);
  /// Gear g's torques with its prescribed side on the forces f at (t, y): its mode decided here
  /// (LossyGearLaw::decide_given, kept in gear_now_), then LossyGearLaw::solve_given.
  [[nodiscard]] LossyGearLaw::Torques given_gear_torques(int g, double t, const double* y, const double* f);
  /// a_b = a_a / i exactly (0 when stuck; a with a prescribed side), after the inertias divided the forces.
  void enforce_gears(double* acc) const;
  // Two lossy gears on one body (analysis/gear_train.hpp): solved, decided and evented together.
  std::vector<GearTrain> trains_;
  std::vector<int> train_of_gear_;                // per gear: its train, −1
  std::vector<std::array<double, 3>> train_f_;    // per train: the last evaluation's F on its bodies
  /// Solves train t in its gears' modes on the forces f and adds their torques (apply_gears).
  void apply_train(int t, const double* y, double* f, double* p_fric);
  [[nodiscard]] std::array<double, 3> train_inertia(int t) const;
  /// The split of each stuck gear's holding torque with its stuck contacts (gear_lock.hpp): their
  /// loads into fc, the gear's X, Y (analysis/drive_system_locks.cpp).
  void share_locks(double t, double* fc);
  /// The joint event functions of the stuck gears with contacts into g (event_slots layout).
  void lock_event_functions(double t, double* g) const;
  GearLocks locks_;
  // Coupled gears (analysis/drive_system_coupled.cpp): the stuck contacts solved with the compliance
  // C (acc = C f + c0) of the bodies, diag(1/I) except each gear's block from its law.
  bool coupled_ = false;
  std::vector<char> gear_clutch_;  // per gear: a clutch on one of its bodies
  std::vector<int> gear_of_body_;  // per body: its lossy gear, −1
  /// λ of the stuck contacts with C, the accelerations, the gears' torques and losses (*fric) again.
  void solve_coupled(double t, const double* y, double* acc, double* fc, const double* im, double* src, double* fric);
  /// u ≡ 0 exactly on the stuck contacts of a coupled model: each gear's bodies keep their values (the
  /// gear holds them on v_a = i v_b), the bodies stuck to them or to the ground take theirs.
  void enforce_coupled(double t, double* x, const double* im, bool velocities) const;
  /// Where the stuck set's split leaves a stuck coupled gear beyond its locking range or a contact
  /// beyond its limit: the split again with the gears as bounded rows (analysis/gear_split.hpp) into
  /// lam_; true when it replaced it (those gears flagged in gear_joint_).
  bool split_stuck_gears(double t, const double* acc, const double* im, const std::vector<double>& ka,
                         const std::vector<double>& kb);
  std::vector<char> gear_joint_;  // per gear: its stuck split came from split_stuck_gears (events with the allowance)
  void numeric_jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J);
  /// Adds the elements' torques to f; returns the source work rate Σ (M v + heat) and adds their heat
  /// power (Element::heat_power) to *loss.
  double drive_forces(double t, const double* y, double* f, double* loss) const;
  /// The drives' state rates into dydt.
  void drive_rates(double t, const double* y, double* dydt) const;
  /// Elements holding a body (Element::held_port): their force there from the free forces f on it
  /// (f before the inertias divide it and before the stuck set's loads), into f.
  void hold_forces(double t, const double* y, double* f);
  /// drive_motion() with the accelerations of the last evaluate() (f_) and on every port on one body
  /// the other forces on it with the stuck set's loads, I a − M_p (ElementMotion::load).
  [[nodiscard]] ElementMotion evaluated_motion(int d, double t, const double* y) const;
  /// Mode md of element d as decided, or where it starts holding a body and its own event function
  /// is negative in it, the mode its settle() takes from there.
  int confirm_hold(int d, double t, const double* y, int md);

  /// Prescribed motions: from the forces f (before the inertias divide them) each source's force R
  /// (motion_f_) and its work rate into *src; then acc = a(t) on their bodies (after the division).
  void motion_forces(double t, const double* v, const double* f, double* src);
  void enforce_motions(double t, double* acc) const;
  std::vector<PrescribedMotionLaw> motions_;
  std::vector<double> motion_f_;

  // Within one mode, with constant loads and friction levels, no brake ramp, no moving surface and no
  // dampers, the whole right-hand side (work and losses included) is affine in y: dy = J y + c. Each
  // mode is compiled once, by probing rhs_general at 0 and at the unit vectors (exact for an affine
  // map up to rounding), and cached by its modes.
  // A few rows of an affine map, out = A y + c, stored densely over the columns of y they read
  // (column by column, `rows` values each) and applied by a kernel of that fixed row count: for
  // small systems this beats compressed rows (no index per entry, the rows' sums in registers).
  // Each row sums c, then the entries in ascending column order: the order of the compressed rows.
  // With copy = m > 0 the kernel first writes out[i] = y[m + i] for i < m (q̇ = v), then the rows
  // from out[m] on: the whole right-hand side in one call.
  struct AffineRows {
    int rows = 0, copy = 0;
    std::vector<int> cols;  // the columns with a nonzero entry in some row, ascending
    std::vector<double> A, c;
    using Kernel = void (*)(const int* cols, int ncols, const double* A, const double* c, const double* y,
                            double* out);
    Kernel kernel = nullptr;  // null: not used (too many rows or columns)
    /// From rows [r0, r1) of M and c, if their count and columns are small enough for the kernels
    /// (and a kernel copies `copy` states first: 0, rows or rows − 3).
    void build(const Eigen::MatrixXd& M, const Eigen::VectorXd& c0, int r0, int r1, int copy);
    void apply(const double* y, double* out) const {
      kernel(cols.data(), static_cast<int>(cols.size()), A.data(), c.data(), y, out);
    }
  };
  struct AffineMode {
    Eigen::VectorXd c;
    std::vector<int> row_start, col;  // J in compressed rows: a handful of nonzeros per row
    std::vector<double> val;
    int first_row = 0;  // rows before it are q̇_i = v_i (copied, not multiplied)
    AffineRows dense;   // rows [first_row, N) of J, when small (else the compressed rows)
    // The contact forces F_k (stuck: λ) are affine in y in the mode too: their rows, for the event
    // functions of stuck contacts (|λ| ≤ F_s) without solving the equations of motion again.
    Eigen::VectorXd force_c;
    std::vector<int> force_start, force_col;
    std::vector<double> force_val;
    AffineRows force_dense;
  };
  bool affine_eligible_ = false;
  const AffineMode* affine_ = nullptr;  // the current mode's, or null until compiled
  const AffineRows* fast_ = nullptr;     // rows n… of the whole right-hand side, when small and current
  const AffineRows* force_fast_ = nullptr;  // the contact forces' rows, when small and current
  void rhs_other(double t, const double* y, double* dydt);
  void contact_forces_other(double t, const double* y, double* fc);
  /// affine_ = the current mode's map (compiled or found), and its small contact-force rows.
  void use_affine() {
    affine_ = &compile_affine();
    if (affine_->force_dense.kernel) force_fast_ = &affine_->force_dense;
  }
  /// A mode changed: its affine map is compiled (or found) at the next evaluation.
  void mode_changed() {
    affine_ = nullptr;
    fast_ = dense_ && varying_.empty() ? &chain_ : nullptr;
    force_fast_ = nullptr;
  }
  std::unordered_map<std::string, AffineMode> affine_cache_;
  const AffineMode& compile_affine();
  void enforce_stuck(double t, double* acc) const;
  void enforce_stuck_weighted(double t, double* acc, const double* im) const;

  /// chain_ (the small chain's dense map) from the links' terms and the current masses.
  void form_dense();

  const Model& m_;
  int n_, nl_, nc_;
  std::vector<double> inertia_;          // current inertias (releases applied)
  int nd_ = 0, nx_ = 0;                  // elements with states of their own, and those states in y
  std::vector<const Element*> drives_;   // Model::drives' laws (the model owns them)
  std::vector<int> drive_body_;          // the body each acts on
  std::vector<int> drive_off_;           // index of each one's first state in y
  std::vector<int> drive_mode_;
  bool energy_;
  std::vector<double> inv_mass_;
  std::vector<const Machine*> machine_;  // per body, null for constant inertia
  std::vector<int> machine_bodies_;      // indices of the bodies with a machine
  bool has_machines_ = false;
  bool general_ = false;                 // machines or drives: the kMach = true instantiations
  bool stuck_machine_ = false;           // a stuck contact touches a machine: P_ per evaluation
  bool timed_share_ = false;  // a redundant stuck set with a limit varying in t (a brake, a clutch): P_ per evaluation
  std::vector<double> im_;               // I(q)⁻¹ of the last evaluation (machines)
  std::vector<double> q_lo_, q_hi_;      // evaluation windows of the machines (±inf: none)
  bool windows_ = false;                 // some window is set
  mutable std::vector<double> qw_;       // positions clamped into the windows
  std::vector<LinkLaw> links_;
  bool all_plain_ = true;  // every link plain (c δ + d δ̇): link_loads_and_rates() keeps the chain's own loop
  int ng_ = 0;                              // lossy gears
  std::vector<LossyGearLaw> gears_;
  std::vector<GearMode> gear_mode_;
  /// Per gear with a prescribed side (elements/lossy_gear.hpp "Prescribed side"): the index of its motion
  /// in motions_ (−1: none) and whether it is on body b.
  std::vector<int> gear_motion_;
  std::vector<char> gear_b_given_;
  std::vector<GearMode> gear_now_;  // a prescribed gear's mode at the last evaluation (gear_mode_: the run's)
  std::vector<LossyGearLaw::Torques> gear_t_;  // the last evaluation's torques
  std::vector<double> gear_fa_, gear_fb_;       // the last evaluation's F_a, F_b (without the gear)
  std::vector<ContactLaw> contacts_;
  std::vector<double> f_const_;        // sum of the constant loads per body
  std::vector<const Load*> varying_;   // loads that depend on t or v
  std::vector<double> stuck_share_;    // m_a/(m_a + m_b) per contact, for enforce_stuck
  std::vector<GapMode> gap_;
  std::vector<ContactMode> mode_;
  std::vector<int> stuck_;    // indices of stuck contacts
  // Pseudo-inverses per set of stuck contacts (bit k = contact k stuck), computed once: the same
  // few mode combinations recur at every stick–slip cycle.
  struct Projectors {
    Eigen::MatrixXd P, Pproj;
    bool timed = false;  // timed_share_ of this stuck set
  };
  std::unordered_map<uint64_t, Projectors> projector_cache_;
  Eigen::MatrixXd P_;         // λ = P_ r (weighted least norm)
  std::vector<Eigen::Index> one_sided_;  // positions in stuck_ of freewheels and end stops (≥ 2 stuck)
  std::unordered_map<uint64_t, Eigen::MatrixXd> masked_;  // λ = P r with those of mask at share 0, this stuck set
  Eigen::MatrixXd Pproj_;     // plain pseudo-inverse of G M⁻¹ Gᵀ (velocity projection)
  std::vector<double> f_, fc_;
  Eigen::VectorXd r_, lam_;
  // solve_coupled's split λ = P r, P = D (S D)⁺, kept while S and the weights D stay bit for bit the
  // same (they change with a gear's mode or direction of power flow, or a timed weight), and its scratch.
  struct CoupledSplit {
    Eigen::MatrixXd S, P, S_now;
    Eigen::VectorXd w, w_now;
    std::vector<double> ka, kb, df;
  } coupled_split_;
  // Small chains without events (n ≤ 8): a = −M⁻¹K q − M⁻¹D v + M⁻¹ f_const by a fixed-size dense
  // kernel in the AffineRows slot (A = [−M⁻¹K, −M⁻¹D], c = M⁻¹ f_const), which beats the link loop.
  bool dense_ = false;
  AffineRows chain_;
};

}  // namespace machdyn
