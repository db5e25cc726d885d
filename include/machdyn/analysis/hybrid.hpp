#pragma once
/// @file
/// Exact event-driven simulation of drives with gaps (backlash), friction contacts and brakes.
///
/// State y = [q; v; W_src; E_fric; E_damp] (n positions, n velocities, three energy quadratures).
/// Every element is in a definite mode and the equations of a mode hold until an event:
///   gap link     open (F = 0), closed+ on the positive flank, closed- on the negative one
///   contact      stuck (u ≡ 0, a bilateral velocity constraint) or sliding in direction ±1
/// In a mode:  M v' = f(t, v) − Bᵀ F_links − Gᵀ λ − Σ_sliding ĝ_k F_k,
/// where row k of G is the sliding velocity u_k = v_a − v_b of stuck contact k and λ solves
///   (G M⁻¹ Gᵀ) λ = G M⁻¹ f̃ − ẇ     (f̃: all forces but λ; ẇ: the prescribed surface acceleration).
/// G M⁻¹ Gᵀ is singular when two stuck contacts lock one motion; λ is then the weighted least-norm
/// solution (minimum Σ λ_k² / F_s0,k): the locked load is shared in proportion to the static limits,
/// so the motion stays locked exactly while it is within their sum. The pseudo-inverse is formed once
/// per mode (complete orthogonal decomposition, rank threshold 1e-12).
///
/// Events are sign changes of one function per element boundary (EventSlots), located on the
/// stepper's dense output by the Illinois method to a bracket of 1e-13·max(1, t) s; the run restarts
/// just after the event with the new modes. The new modes are decided together (decide_contacts):
/// all contacts with zero sliding speed start stuck; while some stuck contact needs more than its
/// static limit, the one with the largest |λ|/F_s is released in the direction of its λ; a released
/// contact whose sliding would immediately reverse is not consistent, and then every combination is
/// tried (fewest sliding first). Deterministic; no smoothing, no velocity threshold.
///
/// Bodies with position-dependent inertia (Body::machine, model/machine.hpp) are exact here too:
/// M(q) = diag(I_i(q_i)), the velocity terms −½ I_i′ q_i'² and the machines' forces Q_i(q_i) join f̃,
/// and links may attach to a machine's output point p(q) (δ = p_a/i − p_b, forces −F p_a′/i, +F p_b′).
/// G M(q)⁻¹ Gᵀ then depends on q: when a stuck contact touches a machine its solution is formed at
/// every evaluation (constant-inertia stuck sets keep their cached pseudo-inverses), and the
/// momentum-weighted means of enforce_stuck/project_velocities use I(q). The work of Q counts as
/// source work; the kinetic energy is ½ Σ I_i(q_i) v_i². No affine fast path with machines.

#include <string>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/modes.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/solve/ode_system.hpp"

namespace machdyn {

class Machine;

class HybridSystem final : public OdeSystem {
 public:
  /// Keeps a reference: `model` must outlive the system.
  explicit HybridSystem(const Model& model);

  [[nodiscard]] int size() const override { return 2 * n_ + 3; }
  void rhs(double t, const double* y, double* dydt) override;
  [[nodiscard]] std::string state_name(int i) const override;

  [[nodiscard]] int dof() const { return n_; }
  /// Index of the energy states in y: source work, friction loss, damping loss.
  [[nodiscard]] int energy_index() const { return 2 * n_; }
  /// y0 from the bodies' initial positions and velocities, zero energies.
  void initial_state(double* y) const;

  // Modes.
  [[nodiscard]] GapMode gap_mode(int l) const { return gap_[static_cast<size_t>(l)]; }
  [[nodiscard]] ContactMode contact_mode(int k) const { return mode_[static_cast<size_t>(k)]; }
  void set_gap_mode(int l, GapMode g) {
    gap_[static_cast<size_t>(l)] = g;
    affine_ = nullptr;
  }
  /// Sets all contact modes and forms the constraint solution of the stuck set.
  void set_contact_modes(const std::vector<ContactMode>& modes);
  [[nodiscard]] const std::vector<ContactMode>& contact_modes() const { return mode_; }
  /// The gap mode a state implies on its own (initial state): closed on a flank it presses.
  [[nodiscard]] GapMode natural_gap_mode(int l, const double* y) const;

  // Quantities in the current modes.
  [[nodiscard]] double deflection(int l, const double* y) const;       ///< δ
  [[nodiscard]] double deflection_rate(int l, const double* y) const;  ///< δ̇
  [[nodiscard]] double link_load(int l, const double* y) const;        ///< F of link l
  /// The rate dF/dt of link l from the state y and its derivative dy (a closed or gap-free link; 0 if
  /// open). y is read only for a link to a machine's output point (link_uses_point).
  [[nodiscard]] double link_load_rate(int l, const double* y, const double* dy) const;
  [[nodiscard]] bool link_uses_point(int l) const {
    return links_[static_cast<size_t>(l)].point;
  }
  /// Whether some body has a position-dependent inertia.
  [[nodiscard]] bool has_machines() const { return has_machines_; }
  [[nodiscard]] double sliding_velocity(int k, double t, const double* y) const;  ///< u = v_a − v_b
  /// Accelerations (n) and contact forces F_k (stuck: λ; sliding: ±F_k; size = contacts).
  void evaluate(double t, const double* y, double* acc, double* contact_force);
  /// Generalized external forces f (n): loads plus friction forces (for quasi-static link loads).
  void external_forces(double t, const double* y, double* f);
  /// Kinetic and elastic energy, J.
  [[nodiscard]] double kinetic_energy(const double* y) const;
  [[nodiscard]] double elastic_energy(const double* y) const;

  // Events.
  /// Two slots per link, then two per contact. A slot is ≥ 0 while the mode holds.
  [[nodiscard]] int event_slots() const { return 2 * (nl_ + nc_); }
  void event_functions(double t, const double* y, double* g);
  /// The element of a slot: link index (slot < 2·links) or contact index.
  [[nodiscard]] bool slot_is_link(int slot) const { return slot < 2 * nl_; }
  [[nodiscard]] int slot_element(int slot) const { return slot < 2 * nl_ ? slot / 2 : (slot - 2 * nl_) / 2; }

  /// Sets the sliding velocity of contact k to exactly 0 by the M-orthogonal (momentum-keeping)
  /// velocity change Δv_a = −u/(m_a (1/m_a + 1/m_b)), Δv_b = +u/(m_b (…)): a contact decided at zero
  /// speed (stick, or slide/reverse from rest) starts its new mode at u = 0, not at the ~1e-13 s
  /// location error beyond it — else a sliding mode would start already past its own event.
  void zero_sliding_velocity(int k, double t, double* y) const;
  /// Projects the velocities onto the stuck constraints (M-orthogonally): u_k = 0 exactly.
  void project_velocities(double t, double* y) const;

  [[nodiscard]] const Model& model() const { return m_; }

 private:
  struct FlatLink {
    int a, b;
    double inv_ratio, c, d;
    bool gap;
    bool point;     // an end is a machine's output point (link_point_); fits the padding after `gap`
    double lo, hi;  // flanks δ₋, δ₊
  };
  // δ, δ̇ and the weights ∂δ/∂q_a (ja), −∂δ/∂q_b (jb) of a link to a machine's output point.
  struct PointState {
    double delta, rate, ja, jb;
  };
  [[nodiscard]] PointState point_state(int l, const double* y) const;
  // What the hot path needs of a contact, decided once: most contacts have a constant kinetic
  // level, no surface motion and no brake ramp.
  struct FlatContact {
    int a, b;
    bool kinetic_table, moving_surface, brake;
    double kinetic0, surface0;  // the constant kinetic level and ground velocity when not tabulated
  };
  // kMach: the model has machines (position-dependent inertia, point links). The constant-inertia
  // instantiation is the plain code of the linear chain, untouched by the machine terms.
  template <bool kMach>
  void forces(double t, const double* y, double* f, double* fc, double* p_src, double* p_fric, double* p_damp);
  template <bool kMach>
  /// Accelerations and contact forces; the rates of source work, friction and damping losses.
  void evaluate_impl(double t, const double* y, double* acc, double* contact_force, double* src, double* fric,
                     double* damp);
  template <bool kMach>
  void rhs_general(double t, const double* y, double* dydt);
  /// I_i(q_i)⁻¹ of every body into `im` (constant bodies: 1/I).
  void inverse_inertias(const double* y, double* im) const;
  /// G M⁻¹ Gᵀ of the stuck set for the inverse inertias `im`.
  [[nodiscard]] Eigen::MatrixXd stuck_matrix(const double* im) const;
  /// P_ for the inverse inertias `im` (machines in the stuck set: at every evaluation).
  void form_stuck_solution(const double* im);

  // Within one mode, with constant loads and friction levels, no brake ramp, no moving surface and no
  // dampers, the whole right-hand side (work and losses included) is affine in y: dy = J y + c. Each
  // mode is compiled once, by probing rhs_general at 0 and at the unit vectors (exact for an affine
  // map up to rounding), and cached by its modes.
  struct AffineMode {
    Eigen::VectorXd c;
    std::vector<int> row_start, col;  // J in compressed rows: a handful of nonzeros per row
    std::vector<double> val;
  };
  bool affine_eligible_ = false;
  const AffineMode* affine_ = nullptr;  // the current mode's, or null until compiled
  std::unordered_map<std::string, AffineMode> affine_cache_;
  const AffineMode& compile_affine();
  void enforce_stuck(double t, double* acc) const;
  void enforce_stuck_weighted(double t, double* acc, const double* im) const;

  const Model& m_;
  int n_, nl_, nc_;
  std::vector<double> inv_mass_;
  std::vector<const Machine*> machine_;  // per body, null for constant inertia
  std::vector<int> machine_bodies_;      // indices of the bodies with a machine
  bool has_machines_ = false;
  bool stuck_machine_ = false;           // a stuck contact touches a machine: P_ per evaluation
  std::vector<double> im_;               // I(q)⁻¹ of the last evaluation (machines)
  std::vector<FlatLink> links_;
  // Per link: the machines whose output points p(q) replace q_a and q_b (a_point, b_point), or null.
  std::vector<std::pair<const Machine*, const Machine*>> link_point_;
  std::vector<FlatContact> contacts_;
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
  };
  std::unordered_map<uint64_t, Projectors> projector_cache_;
  Eigen::MatrixXd P_;         // λ = P_ r (weighted least norm)
  Eigen::MatrixXd Pproj_;     // plain pseudo-inverse of G M⁻¹ Gᵀ (velocity projection)
  std::vector<double> f_, fc_;
  Eigen::VectorXd r_, lam_;
};

/// Hybrid settings beyond the model's simulation settings.
struct HybridOptions {
  long max_events = 1'000'000;  ///< SolverError when exceeded
  int chatter_count = 50;       ///< switches of one element ...
  double chatter_window = 1e-6; ///< ... within this fraction of t_end (or of 1 s) mean chattering
  /// Progress observer (SimulationProgress::events counts the mode events so far); called at most
  /// every progress_interval_s of wall time and once at the end.
  ProgressCallback progress;
  double progress_interval_s = 0.1;
  /// false: no time series on the output grid (SimulationResult::columns stay empty, the names are
  /// set); the peaks, events, slip phases and energies are the same bytes. For callers that need
  /// only the summaries (sweeps): a third less CPU for the travel start-up (4001 output rows).
  bool record_series = true;
};

/// Event-driven simulation (see above). Fills SimulationResult like simulate() and its `hybrid`
/// report. Throws SolverError on numerical failure, on chattering (naming the element, the time and
/// the number of switches) and when no consistent contact mode exists.
SimulationResult simulate_hybrid(const Model& m, const HybridOptions& options = {});

}  // namespace machdyn
