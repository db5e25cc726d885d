#pragma once
/// @file
/// 1-DOF machines whose reduced inertia depends on their own coordinate q (papers 000 and 004).
///
/// A machine is a body of the chain (Body::machine) with kinetic energy T = ½ I(q) q'². Lagrange's
/// equation for such a body, d/dt(∂T/∂q') − ∂T/∂q = Q, gives
///   d/dt(I q') − ½ I′ q'² = I q'' + I′ q'² − ½ I′ q'² = I q'' + ½ I′ q'² = Q      (paper 004 eq. 4)
/// with I′ = dI/dq. In a chain every body's inertia depends on its own coordinate only, so
/// T = ½ Σ I_i(q_i) q_i'² and the mass matrix stays diagonal: the velocity term is ½ I_i′ q_i'² in
/// row i and nothing couples rows (no Coriolis terms between bodies).
///
/// The inertia is split into parts I = Σ I_k (crank, rod, piston; wheel, block); each part gives
/// the d'Alembert inertia moment M_k = −I_k ε − ½ I_k′ ω² (paper 004 eq. 5), ΣM_k + Q = 0.
///
/// A machine may have an output point p(q) (the piston's displacement from top dead centre, the
/// wheel centre's travel, m) that a link can attach to (`between: [crank.piston, load]`).

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "machdyn/common/expression.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

class Machine {
 public:
  virtual ~Machine() = default;
  /// The element type as written in model files, e.g. "crank-slider".
  [[nodiscard]] virtual std::string type() const = 0;
  /// Number of inertia parts (>= 1) and their names (used in column names).
  [[nodiscard]] virtual int parts() const = 0;
  [[nodiscard]] virtual std::string part_name(int k) const = 0;
  /// I_k(q) in kg·m² and dI_k/dq in kg·m²/rad.
  virtual void part_inertia(int k, double q, double* I, double* dI) const = 0;
  /// I(q) = Σ I_k and I′(q).
  virtual void inertia(double q, double* I, double* dI) const;
  /// The machine's own generalized force Q(q), N·m (gas force on the piston, the thread's pull).
  /// Depends on position only, so it enters the energy integral.
  [[nodiscard]] virtual double force(double /*q*/) const { return 0.0; }
  /// I, I′ and Q at once — what the equation of motion needs per evaluation. A machine whose parts
  /// share expensive kinematics (the crank-slider's rod angle) computes them once here.
  virtual void dynamics(double q, double* I, double* dI, double* Q) const {
    inertia(q, I, dI);
    *Q = force(q);
  }
  /// Name of the output point ("piston", "x") or empty if none.
  [[nodiscard]] virtual std::string point_name() const { return {}; }
  /// p(q) in m with p′ (m/rad) and p″ (m/rad²).
  virtual void point(double /*q*/, double* p, double* dp, double* ddp) const { *p = *dp = *ddp = 0.0; }
  /// Extra output series of the state (the wheel's thread angle β): names (with unit suffix) and values.
  [[nodiscard]] virtual std::vector<std::string> extra_names() const { return {}; }
  virtual void extras(double /*q*/, double* /*out*/) const {}
  /// Positions in (q_a, q_b) where Q(q) has a kink (points of a piecewise-linear force table), so
  /// that quadrature can split there. Empty by default.
  [[nodiscard]] virtual std::vector<double> kinks(double /*q_a*/, double /*q_b*/) const { return {}; }
  /// Period of I and Q in q (2π for a crank), 0 if not periodic.
  [[nodiscard]] virtual double period() const { return 0.0; }
  /// Whether the output point's velocity p′(q) q' gets its own output column `NAME.POINT_speed_m_s`
  /// and a uniformity report over the last period (the gear drive's travel speed).
  [[nodiscard]] virtual bool reports_point_speed() const { return false; }

  /// Velocity jumps. A machine whose internal velocity ratio jumps at fixed positions (a stepwise
  /// gear: one circular arc per tooth) has I(q) discontinuous there, and passing such a position is
  /// an impact: the speed jumps from w− to w+ = velocity_after_jump(). has_jumps() says whether the
  /// machine has any; next_jump(q, dir) is the first jump position strictly beyond q in the
  /// direction dir = ±1 (±infinity if none).
  [[nodiscard]] virtual bool has_jumps() const { return false; }
  [[nodiscard]] virtual double next_jump(double /*q*/, int dir) const {
    return dir > 0 ? HUGE_VAL : -HUGE_VAL;
  }
  /// The speed just after passing the jump position qj in direction dir with speed w (sign of w =
  /// dir); *loss receives the kinetic energy lost in the impact, J (≥ 0).
  [[nodiscard]] virtual double velocity_after_jump(double /*qj*/, int /*dir*/, double w, double* loss) const {
    *loss = 0.0;
    return w;
  }

  /// For the energy analysis: a parameter s that describes the range of motion better than q (the
  /// wheel's thread angle β ∈ (β0, π) while φ → ∞). q(s) and dq/ds; the identity by default.
  [[nodiscard]] virtual double q_of_s(double s, double* dq_ds) const {
    *dq_ds = 1.0;
    return s;
  }
  [[nodiscard]] virtual double s_of_q(double q) const { return q; }
  /// The end of the natural range of s in the positive direction (β → π for the wheel), if any.
  [[nodiscard]] virtual std::optional<double> s_end() const { return std::nullopt; }
  [[nodiscard]] virtual std::string s_name() const { return "q"; }
  /// Q and I as functions of s (the wheel computes them from β directly, also at β → π).
  [[nodiscard]] virtual double force_of_s(double s) const {
    double d;
    return force(q_of_s(s, &d));
  }
  [[nodiscard]] virtual double inertia_of_s(double s) const {
    double d, I, dI;
    inertia(q_of_s(s, &d), &I, &dI);
    return I;
  }
};

/// Piecewise-linear table y(x), optionally periodic with period `period` (> 0), else held constant
/// beyond its ends.
struct LinearTable {
  std::vector<double> x, y;
  double period = 0.0;
  [[nodiscard]] double operator()(double xq) const;
};

/// A cubic spline through (x_j, y_j): periodic (y_0 = y_n, continuous y, y′, y″ across the period)
/// or clamped with zero end slopes and held constant beyond the ends (C¹ everywhere).
class CubicSpline {
 public:
  CubicSpline() = default;
  CubicSpline(std::vector<double> x, std::vector<double> y, bool periodic);
  void evaluate(double xq, double* y, double* dy) const;
  [[nodiscard]] bool periodic() const { return periodic_; }
  [[nodiscard]] double period() const { return periodic_ ? x_.back() - x_.front() : 0.0; }

 private:
  std::vector<double> x_, y_, m_;  ///< m_: second derivatives at the knots
  bool periodic_ = false;
};

/// Crank-slider (paper 004). φ is the crank angle from top dead centre (piston farthest from the
/// crank axis); the piston moves along the line through the crank axis (no offset).
///   crank pin A = (r cos φ, r sin φ); rod angle ψ with l sin ψ = r sin φ, λ = r/l < 1
///   piston B = (r cos φ + l cos ψ, 0); piston displacement from TDC s = r + l − x_B
///   rod centre of mass G at distance a from A along AB
///   I(φ) = J_c + m_rod |dG/dφ|² + J_rod (dψ/dφ)² + m_p (dx_B/dφ)²                (exact)
///   I(φ) = I1 + m_B r² (sin φ + (λ/2) sin 2φ)²                                   (approximate, paper)
///        with m_B = m_p + m_rod a/l, I1 = J_c + m_rod (1 − a/l) r² (the rod as two point masses)
/// Gas/resistance force F on the piston: positive pushes the piston away from the cylinder head
/// (towards the crank, +s); Q = F ds/dφ.
class CrankSlider final : public Machine {
 public:
  struct Params {
    double r = 0.05;        ///< crank radius, m
    double l = 0.2;         ///< rod length, m (> r)
    double m_rod = 0.0;     ///< rod mass, kg
    double a = 0.0;         ///< rod centre of mass from the crank pin, m
    double J_rod = 0.0;     ///< rod moment of inertia about its centre of mass, kg·m²
    double m_p = 0.0;       ///< piston mass, kg
    double J_c = 0.0;       ///< crank, shaft and flywheel, kg·m²
    bool approximate = false;
  };
  enum class ForceAgainst { none, angle, position };

  CrankSlider(Params p, ForceAgainst against = ForceAgainst::none, LinearTable force = {});
  [[nodiscard]] std::string type() const override { return "crank-slider"; }
  [[nodiscard]] int parts() const override { return 3; }
  [[nodiscard]] std::string part_name(int k) const override;
  void part_inertia(int k, double q, double* I, double* dI) const override;
  void inertia(double q, double* I, double* dI) const override;
  [[nodiscard]] double force(double q) const override;
  void dynamics(double q, double* I, double* dI, double* Q) const override;
  [[nodiscard]] std::string point_name() const override { return "piston"; }
  void point(double q, double* p, double* dp, double* ddp) const override;
  [[nodiscard]] double period() const override;
  [[nodiscard]] std::vector<double> kinks(double q_a, double q_b) const override;
  [[nodiscard]] const Params& params() const { return p_; }
  /// The piston force F (N) at crank angle φ.
  [[nodiscard]] double piston_force(double phi) const;

  /// Everything the parts and the piston need at one crank angle: sin φ, cos φ once.
  struct Kinematics {
    double I[3], dI[3];  // per part
    double x, dx, ddx;   // piston travel from the outer dead centre and its derivatives
  };
  [[nodiscard]] Kinematics kinematics(double q) const;

 private:
  [[nodiscard]] double piston_force(double phi, double x) const;
  Params p_;
  ForceAgainst against_;
  LinearTable force_;
};

/// The wheel rolled by a thread (paper 000), three schemes. φ is the wheel's rotation from the
/// start (φ = 0 at β = β0); the thread angle β(φ) follows from the centre travel
///   x(β) = H (cot β0 − cot β) + (Rt − r2)(1/sin β0 − 1/sin β) = Rr φ,
///   dβ/dφ = Rr sin²β / (H + (Rt − r2) cos β)
///   I(β) = m1 (ρ² + Rr²) + (m2/2)(Rt + Rr cos β)²   (eq. 17),  Q(β) = F (Rt + Rr cos β)   (eq. 15)
/// Scheme 1: Rt = Rr = R1; scheme 2: Rt = r1, Rr = R1; scheme 3: Rt = R1, Rr = r1.
class RollingWheel final : public Machine {
 public:
  struct Params {
    int scheme = 1;
    double R1 = 0.5, r1 = 0.0, r2 = 0.5, H = 1.0;
    double m1 = 50.0, m2 = 10.0, rho = 0.0, F = 200.0;
    double beta0 = 0.5235987755982988, omega0 = 0.0;
  };
  explicit RollingWheel(Params p);
  [[nodiscard]] std::string type() const override { return "rolling-wheel"; }
  [[nodiscard]] int parts() const override { return 2; }
  [[nodiscard]] std::string part_name(int k) const override { return k == 0 ? "wheel" : "block"; }
  void part_inertia(int k, double q, double* I, double* dI) const override;
  [[nodiscard]] double force(double q) const override;
  [[nodiscard]] std::string point_name() const override { return "x"; }
  void point(double q, double* p, double* dp, double* ddp) const override;
  [[nodiscard]] std::vector<std::string> extra_names() const override { return {"beta_rad"}; }
  void extras(double q, double* out) const override { out[0] = beta(q); }
  [[nodiscard]] double q_of_s(double s, double* dq_ds) const override;
  [[nodiscard]] double s_of_q(double q) const override { return beta(q); }
  [[nodiscard]] std::optional<double> s_end() const override;
  [[nodiscard]] std::string s_name() const override { return "beta"; }
  [[nodiscard]] double force_of_s(double s) const override { return p_.F * g(s); }
  [[nodiscard]] double inertia_of_s(double s) const override {
    double I, dI;
    inertia_beta(s, &I, &dI);
    return I;
  }

  [[nodiscard]] const Params& params() const { return p_; }
  [[nodiscard]] double Rt() const { return Rt_; }
  [[nodiscard]] double Rr() const { return Rr_; }
  /// x(β), the centre's travel from the start, m.
  [[nodiscard]] double x_of_beta(double beta) const;
  /// β(φ), by safeguarded Newton on x(β) = Rr φ.
  [[nodiscard]] double beta(double phi) const;
  /// I, dI/dβ, Q as functions of β.
  void inertia_beta(double beta, double* I, double* dI_dbeta) const;
  /// Rt + Rr cos β, written (Rt − Rr) + 2 Rr cos²(β/2) so that it keeps full relative accuracy
  /// near β = π in scheme 1 (Rt = Rr), where the force and the block's inertia vanish.
  [[nodiscard]] double g(double beta) const {
    const double c = std::cos(0.5 * beta);
    return (Rt_ - Rr_) + 2.0 * Rr_ * c * c;
  }

 private:
  Params p_;
  double Rt_, Rr_;
};

/// A table of I(q), interpolated by a cubic spline (periodic or clamped), optionally with a
/// generalized force given as an expression in q.
class InertiaTable final : public Machine {
 public:
  InertiaTable(CubicSpline spline, std::optional<Expression> torque);
  [[nodiscard]] std::string type() const override { return "inertia-table"; }
  [[nodiscard]] int parts() const override { return 1; }
  [[nodiscard]] std::string part_name(int) const override { return "inertia"; }
  void part_inertia(int k, double q, double* I, double* dI) const override;
  [[nodiscard]] double force(double q) const override { return torque_ ? (*torque_)(q) : 0.0; }
  [[nodiscard]] double period() const override { return spline_.period(); }

 private:
  CubicSpline spline_;
  std::optional<Expression> torque_;
};

/// I(q) given as an expression in q (SI), with its exact derivative; optional torque expression.
class InertiaExpression final : public Machine {
 public:
  InertiaExpression(Expression inertia, std::optional<Expression> torque, double period);
  [[nodiscard]] std::string type() const override { return "inertia-expression"; }
  [[nodiscard]] int parts() const override { return 1; }
  [[nodiscard]] std::string part_name(int) const override { return "inertia"; }
  void part_inertia(int k, double q, double* I, double* dI) const override;
  [[nodiscard]] double force(double q) const override { return torque_ ? (*torque_)(q) : 0.0; }
  [[nodiscard]] double period() const override { return period_; }

 private:
  Expression inertia_;
  std::optional<Expression> torque_;
  double period_;
};

/// Deflection of a link whose ends may be machine output points p(q) (Link::a_point, b_point):
///   δ = p_a(q_a)/i − p_b(q_b),  δ̇ = ja v_a − jb v_b,  ja = p_a′(q_a)/i, jb = p_b′(q_b)
/// (a plain end has p(q) = q, so ja = 1/i, jb = 1). An end with index < 0 is the ground.
struct LinkDeflection {
  double delta, rate, ja, jb;
};
LinkDeflection link_deflection(int a, int b, double inv_ratio, const Machine* pa, const Machine* pb, double qa,
                               double qb, double va, double vb);

/// Whether a body of `m` is a machine with velocity jumps (a stepwise gear drive).
bool has_velocity_jumps(const Model& m);

}  // namespace machdyn
