#pragma once
/// @file
/// Closed forms of paper 002 (three-mass hoisting mechanism, two elastic links), independent of the
/// numerical path; the tests hold `modes` and `simulate` to them.
///
///   I1 φ1'' = M_sp − c1 (φ1 − φ2)
///   I2 φ2'' = c1 (φ1 − φ2) − c2 (φ2 − φ3) − M_B
///   I3 φ3'' = c2 (φ2 − φ3)
/// With x1 = φ1 − φ2, x2 = φ2 − φ3 (link torques M12 = c1 x1, M23 = c2 x2):
///   x1'' = −a11 x1 + a12 x2 + b1,   x2'' = a21 x1 − a22 x2 + b2
///   a11 = c1 (1/I1 + 1/I2), a12 = c2/I2, a21 = c1/I2, a22 = c2 (1/I2 + 1/I3),
///   b1 = M_sp/I1 + M_B/I2, b2 = −M_B/I2.
/// M_B is the paper's load torque: positive when it opposes lifting (it enters I2's equation with −).
/// Units: kg·m², N·m/rad, N·m; valid for I_i > 0, c_i > 0.

#include <array>

namespace machdyn::paper002 {

struct ThreeMassHoist {
  double I1, I2, I3;  ///< kg·m²
  double c1, c2;      ///< N·m/rad
  double M_sp;        ///< mean starting torque of the motor on I1, N·m
  double M_B;         ///< load torque on I2 (opposing lifting), N·m
};

/// Eq. 16: ω²₁,₂ = ½ [s ∓ sqrt(s² − 4 c1 c2 (I1+I2+I3)/(I1 I2 I3))], s = c1/I1 + c1/I2 + c2/I2 + c2/I3.
/// The lower root is evaluated as 2P/(s + sqrt(s² − 4P)) to avoid cancellation. Returns {ω1, ω2}, rad/s.
std::array<double, 2> natural_frequencies(const ThreeMassHoist& h);

/// Eq. 22: M12* = M_B + (I2 + I3)(M_sp − M_B)/(I1 + I2 + I3), M23* = I3 (M_sp − M_B)/(I1 + I2 + I3).
std::array<double, 2> particular_loads(const ThreeMassHoist& h);

/// The general solution x(t) = x* + Σ_k u_k (C_k cos ω_k t + S_k sin ω_k t) (eqs. 17–21), with
/// mode vectors u_k = (a12, a11 − ω_k²) of the 2×2 system and C, S from the initial deflections
/// and their rates. The paper's own start is x1(0) = M_sp/c1 (M12 = M_sp), x2(0) = 0, at rest.
class ThreeMassSolution {
 public:
  ThreeMassSolution(const ThreeMassHoist& h, double x1_0, double x2_0, double x1dot_0, double x2dot_0);
  [[nodiscard]] double M12(double t) const;  ///< link torque c1 x1(t), N·m
  [[nodiscard]] double M23(double t) const;  ///< link torque c2 x2(t), N·m

 private:
  [[nodiscard]] std::array<double, 2> x(double t) const;
  ThreeMassHoist h_;
  std::array<double, 2> w_{}, xs_{}, C_{}, S_{};
  std::array<std::array<double, 2>, 2> u_{};  // u_[k] = mode vector k
};

}  // namespace machdyn::paper002
