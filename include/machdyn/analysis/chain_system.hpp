#pragma once
/// @file
/// The equations of motion of an elastic drive chain (model/model.hpp) as a first-order system for
/// the integrators:
///   y = [q; v],   q' = v,   M v' = f(t, v) − Bᵀ (C B q + D B v)
/// M = diag(I or m), row l of B gives the deflection δ_l = q_a/i − q_b of link l, C = diag(c),
/// D = diag(d), f the loads (model/model.hpp). Link loads F = C B q + D B v are linear in y.
///
/// Bodies with variable inertia (Body::machine, model/machine.hpp) make it the Lagrangian system
///   M(q) v' + ½ diag(I_i′(q_i)) v² = f(t, q, v) − Jᵀ(q) F,   M(q) = diag(I_i(q_i))
/// (derivation in model/machine.hpp), where a link attached to a machine's output point p(q) has
/// δ = p_a(q_a)/i − p_b(q_b) and row J = ∂δ/∂q; such links are nonlinear in y. The machines' own
/// forces Q(q) are part of f. With machines the Jacobian is by finite differences.

#include <algorithm>
#include <string>
#include <vector>

#include "machdyn/model/model.hpp"
#include "machdyn/analysis/peak_tracker.hpp"
#include "machdyn/solve/event_system.hpp"

namespace machdyn {

class ChainSystem final : public EventSystem {  // no events of its own
 public:
  /// Keeps a reference: `model` must outlive the system.
  explicit ChainSystem(const Model& model);

  [[nodiscard]] int size() const override { return 2 * n_; }
  void rhs(double t, const double* y, double* dydt) override;
  [[nodiscard]] bool has_jacobian() const override { return true; }
  void jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) override;
  /// The linear chain's J sparsely (O(n) nonzeros); machines have none (finite differences, dense).
  [[nodiscard]] bool has_sparse_jacobian() const override { return !nonlinear_; }
  void sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) override;
  [[nodiscard]] std::string state_name(int i) const override;
  /// The model's breakpoints (Model::breakpoints): steps of loads, pulse edges, table kinks.
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t_end) const override;

  /// y0 from the bodies' initial positions and velocities.
  void initial_state(double* y) const;
  /// The load F of link l for state y.
  [[nodiscard]] double link_load(int l, const double* y) const;
  /// Weights w with F_l = wᵀ y (over the 2n states): F_l is linear in the state. For a link to a machine's
  /// output point (nonlinear) these are the weights of the ratio alone; simulate() takes that
  /// link's extremes from the output grid instead.
  /// Sparse: the nonzero entries only (at most four), so n links cost O(n), not O(n²).
  [[nodiscard]] SparseWeights link_load_weights(int l) const;
  /// The external loads as generalized forces f(t, v) (size n).
  void generalized_loads(double t, const double* y, double* f) const;
  /// Evaluates body i's machine (inertia, force, point) at q clamped to [lo, hi]. For machines with
  /// velocity jumps (stepwise gears) analysis/machine_run.cpp keeps this window inside the current
  /// piece, so that a step ending a hair beyond a jump position (the re-integration up to the
  /// located event) does not see the next piece's inertia. Default: no clamp.
  void set_evaluation_window(int body, double lo, double hi);

 private:
  struct FlatLink {
    int a, b;
    double inv_ratio, c, d;
    const Machine* pa = nullptr;  ///< a's output point is used (a_point), else q_a
    const Machine* pb = nullptr;
  };
  /// δ, δ' and the weights ∂δ/∂q_a (ja), −∂δ/∂q_b (jb) of a link.
  struct LinkState {
    double delta, rate, ja, jb;
  };
  [[nodiscard]] LinkState link_state(const FlatLink& k, const double* y) const;
  void numeric_jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J);
  void rhs_nonlinear(double t, const double* y, double* dydt);

  const Model& m_;
  int n_;
  std::vector<double> inv_mass_;
  std::vector<FlatLink> links_;
  std::vector<const Machine*> machine_;  ///< per body, null for constant inertia
  std::vector<double> q_lo_, q_hi_;      ///< evaluation windows of the machines (±inf: none)
  /// The position at which body i's machine is evaluated.
  [[nodiscard]] double mq(int i, const double* y) const {
    return std::clamp(y[i], q_lo_[static_cast<size_t>(i)], q_hi_[static_cast<size_t>(i)]);
  }
  bool nonlinear_ = false;               ///< machines or point links present
  // Fast paths of the linear chain (no machines, no point links):
  std::vector<FlatLink> between_;     // links with two bodies (hot path without ground branches)
  std::vector<FlatLink> grounded_;    // links to the ground, body index in `a`, inv_ratio = ±1
  std::vector<double> f_const_;       // sum of the constant loads per body
  std::vector<const Load*> varying_;  // loads that depend on t or v
  // Small chains (n <= 8): a = Aq q + Av v + M⁻¹ f_const as fixed-size dense products, which beat
  // the link loop there. Aq = −M⁻¹K, Av = −M⁻¹D, column-major n × n.
  using DenseRhs = void (*)(const double* y, double* dydt, const double* Aq, const double* Av, const double* b);
  DenseRhs dense_ = nullptr;
  std::vector<double> Aq_, Av_, b_;
};

}  // namespace machdyn
