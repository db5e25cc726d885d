#pragma once
/// @file
/// Paper 001: the staged solution of the travel-drive start-up with a gap and wheel slip
/// (docs/hybrid.md). Everything is reduced to the wheel rim: forces in N, masses in kg, x in m.
///   m1 rotating drive parts, mk driving wheels, m2 the translating crane; link c with total gap Δ
///   between m1 and mk; adhesion mk–m2 holds up to F_sc = ΔG μ_s and slides at F_d = ΔG μ_d;
///   W the resistance of m2 (static limit = kinetic level); P the drive force on m1.
/// Stages 1–3 are exact closed forms. Stages 4–5 follow the paper's approximations and say so.

namespace machdyn::paper001 {

struct TravelDrive {
  double m1 = 0, mk = 0, m2 = 0;  ///< kg
  double c = 0;                   ///< N/m
  double Delta = 0;               ///< m
  double P = 0, W = 0;            ///< N
  double F_sc = 0, F_d = 0;       ///< N: ΔG μ_s, ΔG μ_d
};

/// Stage 1 (gap taken up, only m1 moves, exact): t1 = sqrt(2 m1 Δ / P), v1 = sqrt(2 P Δ / m1).
/// Stage 2 (link force rises while mk, m2 stand, exact): with τ from the end of stage 1,
///   F(τ) = P − P cos ω2 τ + sqrt(2 c Δ P) sin ω2 τ,  ω2 = sqrt(c/m1),
///   t2 = [arctan sqrt(P/(2cΔ)) − arcsin((P − W)/sqrt(P (2cΔ + P)))] / ω2   (F(t2) = W),
///   v1(t2) = sqrt((2P(Δc + W) − W²)/(c m1)).
/// Stage 3 (mk and m2 move together against W, exact): F(τ) = A3 cos ω3 τ + B3 sin ω3 τ + D3,
///   ω3 = sqrt(c/m1 + c/(mk + m2)), D3 = [P (mk + m2) + W m1]/(m1 + mk + m2), A3 = W − D3,
///   B3 = c v1(t2)/ω3, until the adhesion force (m2 F + mk W)/(mk + m2) reaches F_sc, i.e. the link
///   force reaches F_slip = [F_sc (mk + m2) − mk W]/m2 (the paper takes F_sc there).
struct ExactStages {
  double t1 = 0, v1_stage1 = 0;             ///< s, m/s
  double omega2 = 0, t2 = 0, v1_stage2 = 0; ///< rad/s, s, m/s
  double omega3 = 0, A3 = 0, B3 = 0, D3 = 0;
  double F_slip = 0;  ///< N, link force at which the wheels start to slip
  double t3 = 0;      ///< s, duration of stage 3 (NaN if F never reaches F_slip)
  [[nodiscard]] double slip_time() const { return t1 + t2 + t3; }
};
ExactStages exact_stages(const TravelDrive& d);

/// The stage-2 link force at τ after the gap closed.
double stage2_force(const TravelDrive& d, double tau);

/// APPROXIMATION (paper 001, stage 4): the wheels slip; m1 x1'' = P − F, mk xk'' = F − F_d, so
/// F(τ) = A4 cos ω4 τ + B4 sin ω4 τ + D4, ω4 = sqrt(c/m1 + c/mk), D4 = (P mk + F_d m1)/(m1 + mk),
/// A4 = F_sc − D4 (the paper starts the stage at F = F_sc), B4 = F'(start)/ω4 with the link-force
/// rate at the end of the exact stage 3. Peak F4max = sqrt(A4² + B4²) + D4; the stage ends where
/// F = 0 (t4, NaN if F stays positive: the gap does not reopen).
/// APPROXIMATION (stage 5, W neglected): t5 = m2 mk (vk − v2)/(F_d (m2 + mk)).
struct ApproxStages {
  double omega4 = 0, A4 = 0, B4 = 0, D4 = 0;
  double F4_max = 0;  ///< N
  double t4 = 0;      ///< s
};
ApproxStages approximate_stage4(const TravelDrive& d, const ExactStages& e);
double approximate_t5(const TravelDrive& d, double vk_minus_v2);

}  // namespace machdyn::paper001
