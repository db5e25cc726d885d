// Modal analysis per topology (analysis/modal.hpp) against closed forms: paper 001's ω2, ω3, ω4,
// paper 002's eq. 16 and its braked variants for each of the eleven operating modes, the damped
// two-mass chain and the decay a time simulation shows.
#include <cmath>
#include <numeric>
#include <Eigen/Dense>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modal.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/topology.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"
#include "support/three_mass_hoist.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Topology topology(const Model& m, const std::string& text) { return parse_topology(m, text, Location{"test", 1, 0}); }

// Claim: the constraint elimination reproduces paper 001's frequencies of each topology of the
// travel drive to 1e-10, with the rigid-body modes counted: gap closed + both contacts stuck fixes
// mk and m2 (only m1 moves, ω2 = √(c/m1), no rigid mode); rolling (W slides) leaves m1 and mk + m2
// (ω3 = √(c/m1 + c/(mk + m2)), one rigid mode); slipping frees all three (ω4 = √(c/m1 + c/mk), m2
// alone and the pair as two rigid modes).
TEST(LinearModal, TravelDriveTopologiesGivePaper001Frequencies) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const double c = 2.0e6, m1 = 3000, mk = 300, m2 = 10000;
  struct Case {
    const char* text;
    double omega;
    int dof, rigid;
  };
  for (const Case& k : {Case{"c=closed, adhesion=stuck, W=stuck", std::sqrt(c / m1), 1, 0},
                        Case{"c=closed, adhesion=stuck, W=slip+", std::sqrt(c / m1 + c / (mk + m2)), 2, 1},
                        Case{"c=closed, adhesion=slip+, W=slip+", std::sqrt(c / m1 + c / mk), 3, 2}}) {
    const UndampedModes md = undamped_modes(linearize(m, topology(m, k.text)));
    ASSERT_EQ(md.omega.size(), 1) << k.text;
    EXPECT_NEAR(md.omega(0), k.omega, 1e-10 * k.omega) << k.text;
    EXPECT_EQ(md.dof, k.dof) << k.text;
    EXPECT_EQ(md.rigid_body_modes, k.rigid) << k.text;
  }
}

/// ω² of two bodies on springs: K = [[k11, −k12], [−k12, k22]], M = diag(ma, mb):
/// ma mb ω⁴ − (ma k22 + mb k11) ω² + (k11 k22 − k12²) = 0; the lower root as P/(upper) (no cancellation).
std::array<double, 2> two_body_frequencies(double ma, double mb, double k11, double k22, double k12) {
  const double s = k11 / ma + k22 / mb, P = (k11 * k22 - k12 * k12) / (ma * mb);
  const double hi = 0.5 * (s + std::sqrt(s * s - 4 * P));
  return {std::sqrt(P / hi), std::sqrt(hi)};
}

// Claim: paper 002's hoist in each of its eleven operating modes, the brake applied (holding) where
// the mode has one: without a brake eq. 16 with one rigid mode; a brake on I1 leaves I2, I3 on c1 to
// the ground and c2 (k11 = c1 + c2, k22 = c2, k12 = c2); on I3 leaves I1, I2 (k11 = c1, k22 =
// c1 + c2, k12 = c1); on I2 splits the chain into I1 on c1 and I3 on c2: √(c1/I1), √(c2/I3).
TEST(LinearModal, HoistOperatingModesWithBrakesApplied) {
  const std::string path = test::example("hoist-modes.yaml");
  int cases = 0;
  for (const std::string name : {"accel_up", "brake_I1_lifting", "brake_I2_lifting", "brake_I3_lifting", "coast_up",
                                 "accel_down", "brake_I1_lowering", "brake_I2_lowering", "brake_I3_lowering",
                                 "coast_down", "braked_lowering"}) {
    const Model m = load_model_case(path, {}, name);
    const double I1 = m.bodies[0].inertia, I2 = m.bodies[1].inertia, I3 = m.bodies[2].inertia;
    const double c1 = m.links[0].c, c2 = m.links[1].c;
    std::array<double, 2> w{};
    int rigid = 0;
    if (m.contacts.empty()) {
      w = paper002::natural_frequencies({I1, I2, I3, c1, c2, 0, 0});
      rigid = 1;
    } else {
      const std::string on = m.bodies[static_cast<size_t>(m.contacts[0].a)].name;
      if (on == "I1") w = two_body_frequencies(I2, I3, c1 + c2, c2, c2);
      if (on == "I3") w = two_body_frequencies(I1, I2, c1, c1 + c2, c1);
      if (on == "I2") w = {std::sqrt(c1 / I1), std::sqrt(c2 / I3)}, std::sort(w.begin(), w.end());
    }
    const UndampedModes md = undamped_modes(linearize(m, topology(m, m.contacts.empty() ? "" : "T=applied")));
    ASSERT_EQ(md.omega.size(), 2) << name;
    EXPECT_EQ(md.rigid_body_modes, rigid) << name;
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(md.omega(k), w[static_cast<size_t>(k)], 1e-10 * w[static_cast<size_t>(k)]) << name;
    ++cases;
  }
  EXPECT_EQ(cases, 11);
}

// Claim: the shapes of a constrained topology are mass-normalized eigenvectors of the full
// (unreduced) K and M that satisfy the constraints: φᵀ M φ = 1, G φ = 0 and the residual of
// K φ − ω² M φ lies in the span of Gᵀ (the constraint forces).
TEST(LinearModal, ConstrainedShapesSatisfyTheFullProblem) {
  const Model m = load_model_case(test::example("hoist-modes.yaml"), {}, "brake_I1_lifting");
  const LinearModel lin = linearize(m, topology(m, "T=applied"));
  const UndampedModes md = undamped_modes(lin);
  const Eigen::MatrixXd K(lin.stiffness()), M = lin.M.asDiagonal(), G(lin.constraints());
  for (Eigen::Index k = 0; k < md.omega.size(); ++k) {
    const Eigen::VectorXd phi = md.shapes.col(k);
    EXPECT_NEAR(phi.dot(M * phi), 1.0, 1e-12);
    EXPECT_LT((G * phi).norm(), 1e-14);
    const Eigen::VectorXd res = K * phi - md.omega(k) * md.omega(k) * M * phi;
    // Remove the component along the constraint rows (the brake's reaction), then nothing remains.
    const Eigen::VectorXd free = res - G.transpose() * (G * G.transpose()).ldlt().solve(G * res);
    EXPECT_LT(free.norm(), 1e-9 * (K * phi).norm());
  }
}

const char* kTwoMass = R"(name: two masses
bodies:
  m1: {type: translational, mass: 2 kg, velocity: 1 m/s}
  m2: {type: translational, mass: 3 kg}
links:
  k: {type: spring-damper, between: [m1, m2], stiffness: 5000 N/m, damping: 12 N*s/m}
simulation: {t_end: 1 s, dt_out: 0.02 ms, rtol: 1e-12, atol: 1e-14, integrator: dopri5}
)";

// Claim: two free masses on a spring–damper have one rigid mode and one damped mode of the relative
// motion μ ẍ + d ẋ + c x = 0, μ = m1 m2/(m1 + m2): ω_n = √(c/μ), ζ = d/(2√(c μ)) (to 1e-9), and the
// complex shape of a free pair is real with the masses moving opposite, amplitudes in ratio m2/m1.
TEST(LinearModal, DampedTwoMassChainEqualsClosedForm) {
  const Model m = load_model(test::write_temp("two.yaml", kTwoMass));
  const DampedModes dm = damped_modes(linearize(m, initial_topology(m)));
  const double m1 = 2, m2 = 3, c = 5000, d = 12, mu = m1 * m2 / (m1 + m2);
  ASSERT_EQ(dm.modes.size(), 1u);
  EXPECT_EQ(dm.zero_eigenvalues, 2);
  const DampedMode& md = dm.modes[0];
  EXPECT_TRUE(md.oscillatory);
  EXPECT_NEAR(md.omega_n, std::sqrt(c / mu), 1e-10 * std::sqrt(c / mu));
  const double zeta = d / (2 * std::sqrt(c * mu));
  EXPECT_NEAR(md.zeta, zeta, 1e-9 * zeta);
  EXPECT_NEAR(md.omega_d, std::sqrt(c / mu) * std::sqrt(1 - zeta * zeta), 1e-10 * md.omega_d);
  EXPECT_NEAR(std::abs(md.shape(1) / md.shape(0) + m1 / m2), 0.0, 1e-10);
}

// Claim: with non-proportional damping (one damper on one link of three) every complex mode solves
// the quadratic eigenproblem (λ² M + λ D + K) φ = 0 — an independent check of the state-space
// eigenvectors — and the damping ratios differ between the modes.
TEST(LinearModal, NonProportionalDampingSolvesQuadraticEigenproblem) {
  const Model m = load_model(test::write_temp("three.yaml", R"(name: three
bodies:
  a: {type: rotational, inertia: 1 kg*m^2}
  b: {type: rotational, inertia: 0.5 kg*m^2}
  c: {type: rotational, inertia: 0.2 kg*m^2}
links:
  ab: {type: spring-damper, between: [a, b], stiffness: 1e4 N*m/rad, damping: 8 N*m*s/rad}
  bc: {type: spring, between: [b, c], stiffness: 3e3 N*m/rad}
  ag: {type: spring, between: [a, ground], stiffness: 2e3 N*m/rad}
)"));
  const LinearModel lin = linearize(m, initial_topology(m));
  const DampedModes dm = damped_modes(lin);
  ASSERT_EQ(dm.modes.size(), 3u);
  const Eigen::MatrixXcd K = Eigen::MatrixXd(lin.stiffness()).cast<std::complex<double>>();
  const Eigen::MatrixXcd D = Eigen::MatrixXd(lin.damping()).cast<std::complex<double>>();
  const Eigen::MatrixXcd M = Eigen::MatrixXd(lin.M.asDiagonal()).cast<std::complex<double>>();
  for (const DampedMode& md : dm.modes) {
    const auto l = md.lambda;
    const Eigen::VectorXcd res = (l * l * M + l * D + K) * md.shape;
    EXPECT_LT(res.norm(), 1e-10 * (K * md.shape).norm());
  }
  EXPECT_GT(std::abs(dm.modes[0].zeta - dm.modes[1].zeta), 1e-3);
}

// Claim: the decay rate σ = ζ ω_n of the damped mode is what a time simulation shows: successive
// maxima of the link load of the freely vibrating pair (started by m1's initial speed) are T_d
// apart and in ratio e^{−σ T_d}, so ln(peak_0/peak_k)/(t_k − t_0) = σ. Peaks located by a
// parabola through the three grid points around each maximum (dt_out = T_d/1000). Within 1e-4.
TEST(LinearModal, DecayRateEqualsTimeSimulation) {
  const Model m = load_model(test::write_temp("two.yaml", kTwoMass));
  const DampedModes dm = damped_modes(linearize(m, initial_topology(m)));
  const SimulationResult r = simulate(m);
  const auto& t = r.columns[test::column(r, "t_s")];
  const auto& F = r.columns[test::column(r, "k.load_N")];
  std::vector<std::pair<double, double>> peaks;
  for (size_t i = 1; i + 1 < F.size(); ++i)
    if (F[i] > F[i - 1] && F[i] >= F[i + 1]) {
      const double a = F[i - 1], b = F[i], c = F[i + 1], h = t[i + 1] - t[i];
      const double s = 0.5 * (a - c) / (a - 2 * b + c);
      peaks.emplace_back(t[i] + s * h, b - 0.25 * (a - c) * s);
    }
  ASSERT_GE(peaks.size(), 6u);
  const auto& p0 = peaks[0];
  const auto& p5 = peaks[5];
  const double sigma = std::log(p0.second / p5.second) / (p5.first - p0.first);
  EXPECT_NEAR(sigma, dm.modes[0].decay_rate, 1e-4 * dm.modes[0].decay_rate);
}

/// A chain of n bodies with links i–(i+1), bodies written in the file in `order`.
Model chain(int n, const std::vector<int>& order, const std::string& file) {
  std::string text = "name: chain\nbodies:\n", links = "links:\n";
  for (int i = 0; i < n; ++i)
    text += fmt::format("  b{}: {{type: rotational, inertia: {} kg*m^2}}\n", order[static_cast<size_t>(i)],
                        1.0 + 0.5 * std::sin(order[static_cast<size_t>(i)]));
  for (int i = 0; i + 1 < n; ++i)
    links += fmt::format("  l{}: {{type: spring, between: [b{}, b{}], stiffness: {} N*m/rad}}\n", i, i, i + 1,
                         1e3 * (1 + 0.3 * std::cos(i)));
  return load_model(test::write_temp(file, text + links));
}

// Claim: a chain numbered along its length takes the tridiagonal path (QR with rotations for 12
// bodies, inverse iteration for 300); numbered out of order it takes the dense path. Both give the
// same frequencies (two algorithms) to 1e-10, and the inverse-iteration shapes are M-orthonormal
// eigenvectors (residual of K φ − ω² M φ at rounding level).
TEST(LinearModal, TridiagonalAndDensePathsAgree) {
  for (int n : {12, 300}) {
    std::vector<int> ordered(static_cast<size_t>(n)), shuffled;
    std::iota(ordered.begin(), ordered.end(), 0);
    for (int i = 0; i < n; ++i) shuffled.push_back((i * 7 + 3) % n);  // 7 and n coprime
    const Model a = chain(n, ordered, "a.yaml"), b = chain(n, shuffled, "b.yaml");
    const LinearModel la = linearize(a, initial_topology(a));
    const UndampedModes ma = undamped_modes(la);
    const UndampedModes mb = undamped_modes(linearize(b, initial_topology(b)));
    ASSERT_EQ(ma.omega.size(), n - 1);
    ASSERT_EQ(mb.omega.size(), n - 1);
    EXPECT_EQ(ma.rigid_body_modes, 1);
    for (int k = 0; k < n - 1; ++k) EXPECT_NEAR(ma.omega(k), mb.omega(k), 1e-10 * ma.omega(k)) << n << " " << k;
    const Eigen::MatrixXd K(la.stiffness()), M = la.M.asDiagonal();
    const Eigen::MatrixXd G = ma.shapes.transpose() * M * ma.shapes;
    EXPECT_LT((G - Eigen::MatrixXd::Identity(n - 1, n - 1)).cwiseAbs().maxCoeff(), 1e-10) << n;
    for (int k = 0; k < n - 1; ++k) {
      const Eigen::VectorXd phi = ma.shapes.col(k);
      EXPECT_LT((K * phi - ma.omega(k) * ma.omega(k) * M * phi).norm(), 1e-10 * K.norm() * phi.norm()) << n << " " << k;
    }
  }
}

// Claim: a general constraint row (not a stuck contact's ±1 pair; none of today's elements adds one)
// takes the QR basis of ker G and gives the frequencies of a second algorithm — an LU kernel basis
// N and the pair (Nᵀ K N, Nᵀ M N) — to 1e-10, with shapes on the constraint (G φ = 0).
TEST(LinearModal, GeneralConstraintRowUsesQrBasis) {
  LinearModel lin(4);
  lin.M << 1.0, 2.0, 0.5, 1.5;
  const int idx[4] = {0, 1, 2, 3};
  const double j1[2] = {1.0, -1.0};
  for (int k = 0; k < 3; ++k) LinearModel::add_outer(lin.K, idx + k, j1, 2, 1000.0 * (k + 1));
  LinearModel::add_outer(lin.K, idx, j1 + 0, 1, 500.0);  // body 0 to the ground
  lin.G.push_back({{0, 1.0}, {1, 1.0}, {3, -2.0}});
  const UndampedModes md = undamped_modes(lin);
  const Eigen::MatrixXd K(lin.stiffness()), M = lin.M.asDiagonal(), G(lin.constraints());
  const Eigen::MatrixXd N = Eigen::FullPivLU<Eigen::MatrixXd>(G).kernel();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(N.transpose() * K * N, N.transpose() * M * N);
  ASSERT_EQ(md.dof, 3);
  ASSERT_EQ(md.omega.size(), 3);
  for (int k = 0; k < 3; ++k) {
    const double w = std::sqrt(es.eigenvalues()(k));
    EXPECT_NEAR(md.omega(k), w, 1e-10 * w);
    EXPECT_LT((G * md.shapes.col(k)).norm(), 1e-12);
    EXPECT_NEAR(md.shapes.col(k).dot(M * md.shapes.col(k)), 1.0, 1e-12);
  }
}

// Claim: a sliding contact whose kinetic force rises with the sliding speed (dF_k/du = 4 N·s/m
// between 1 and 2 m/s) is a damper of that slope in the linear model: a 2 kg mass on an 800 N/m
// spring sliding at 1.5 m/s has ω_n = √(c/m) = 20 rad/s and ζ = (dF_k/du)/(2√(c m)) = 0.05 (to
// 1e-9); stuck, the contact fixes the mass (no elastic mode); sliding at a constant level, none.
TEST(LinearModal, KineticSlopeOfASlidingContactDamps) {
  const Model m = load_model(test::write_temp("slide.yaml", R"(name: slide
bodies:
  x: {type: translational, mass: 2 kg, velocity: 1.5 m/s}
links:
  k: {type: spring, between: [x, ground], stiffness: 800 N/m}
contacts:
  f: {between: [x, ground], static: 20 N, kinetic: [[0 m/s, 10 N], [1 m/s, 14 N], [2 m/s, 18 N]]}
)"));
  const TopologyModes t = analyse_topology(m, topology(m, "f=slip+"));
  ASSERT_TRUE(t.damped);
  ASSERT_EQ(t.damped_modes.modes.size(), 1u);
  EXPECT_NEAR(t.damped_modes.modes[0].omega_n, 20.0, 1e-10 * 20.0);
  EXPECT_NEAR(t.damped_modes.modes[0].zeta, 0.05, 1e-9 * 0.05);
  EXPECT_EQ(analyse_topology(m, topology(m, "f=stuck")).modes.omega.size(), 0);
  EXPECT_FALSE(analyse_topology(m, topology(m, "f=released")).damped);
}

}  // namespace
}  // namespace machdyn
