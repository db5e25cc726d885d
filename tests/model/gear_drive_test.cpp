// The wheel-walking propulsor drive as a machine (model/gear_drive.hpp): kinematics of the continuous
// and stepwise gear pair, reduced inertia and its derivative, the velocity jump at a tooth boundary.
#include "machdyn/model/gear_drive.hpp"

#include <cmath>
#include <numbers>
#include <gtest/gtest.h>

#include "machdyn/gears/synthesis.hpp"
#include "machdyn/io/yaml_reader.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;

gears::GearModel paper_gears() {
  return gears::compile_gears(read_yaml_file(std::string(MACHDYN_SOURCE_DIR) + "/examples/walking-drive-gears.yaml"));
}

GearDrive drive(GearDrive::Ratio ratio, double I_p = 0.5, double I_H = 2.0, double m = 300.0, double F_r = 0.0) {
  const auto gm = paper_gears();
  GearDrive::Params p;
  p.I_p = I_p, p.I_H = I_H, p.m = m, p.F_r = F_r, p.ratio = ratio;
  return GearDrive(p, gm, gears::synthesize(gm));
}

/// Angles spread over two pinion turns, away from the big-sector ends (θ = ±π/2 + kπ, where the
/// walking law has its corner) and, for the stepwise ratio, from sector boundaries.
std::vector<double> sample_angles(const GearDrive& d) {
  std::vector<double> out;
  for (int j = 0; j < 200; ++j) {
    const double q = -2 * kPi + 4 * kPi * (j + 0.37) / 200;
    const double rel = std::remainder(q - kPi / 2, kPi);
    if (std::abs(rel) < 1e-3) continue;
    if (d.has_jumps()) {
      const double up = d.next_jump(q, +1), down = d.next_jump(q, -1);
      if (up - q < 1e-3 || q - down < 1e-3) continue;
    }
    out.push_back(q);
  }
  return out;
}

// Claim: dI/dθ of every part and the travel derivatives X_θ, X_θθ equal central finite differences
// (h = 1e-6 rad, truncation ~1e-12 relative) for both ratios.
TEST(GearDrive, InertiaAndTravelDerivativesMatchFiniteDifferences) {
  for (auto ratio : {GearDrive::Ratio::continuous, GearDrive::Ratio::stepwise}) {
    const GearDrive d = drive(ratio);
    const double h = 1e-6;
    for (double q : sample_angles(d)) {
      for (int k = 0; k < d.parts(); ++k) {
        double Ip, Im, I, dI, dummy;
        d.part_inertia(k, q + h, &Ip, &dummy);
        d.part_inertia(k, q - h, &Im, &dummy);
        d.part_inertia(k, q, &I, &dI);
        EXPECT_NEAR(dI, (Ip - Im) / (2 * h), 1e-7 * (1 + std::abs(I))) << "part " << k << " at " << q;
      }
      double p, dp, ddp, pp, dpp, ddpp, pm, dpm, ddpm;
      d.point(q, &p, &dp, &ddp);
      d.point(q + h, &pp, &dpp, &ddpp);
      d.point(q - h, &pm, &dpm, &ddpm);
      EXPECT_NEAR(dp, (pp - pm) / (2 * h), 1e-8) << q;
      EXPECT_NEAR(ddp, (dpp - dpm) / (2 * h), 1e-7) << q;
    }
  }
}

// Claim: with the continuous ratio the travel per pinion angle is the constant (a − b + c)/u
// (paper eqs. 2 and 10: i ∝ dX/dφ), so the vehicle's part of I is the constant m ((a − b + c)/u)²,
// and the total is I_p + I_H/i(φ)² + that constant.
TEST(GearDrive, ContinuousTravelPerPinionAngleIsConstant) {
  const GearDrive d = drive(GearDrive::Ratio::continuous);
  const double u = (kPi / 2) / (kPi / 4 + 0.9375 / 2), Xt = 0.320 / u;
  for (double q : sample_angles(d)) {
    double p, dp, ddp;
    d.point(q, &p, &dp, &ddp);
    EXPECT_NEAR(dp, Xt, 1e-12) << q;
    EXPECT_NEAR(ddp, 0.0, 1e-9) << q;
    double I, dI;
    d.inertia(q, &I, &dI);
    const auto kin = d.kinematics(q);
    const double i = u * (1 + 0.9375 * std::cos(2 * std::remainder(kin.phi, kPi / 2)));  // the law repeats per big sector
    EXPECT_NEAR(I, 0.5 + 2.0 / (i * i) + 300.0 * Xt * Xt, 1e-10 * I) << q;
  }
}

// Claim: the stepwise φ(θ) passes through every corner (θ_j, φ_j) of Table 1, is continuous at the
// boundaries, and repeats with (Θ, T) = (π, π/2) per big sector; X repeats with X_T = A T + B sin T.
TEST(GearDrive, StepwiseKinematicsFollowTheSectorTable) {
  const auto gm = paper_gears();
  const auto syn = gears::synthesize(gm);
  const GearDrive d = drive(GearDrive::Ratio::stepwise);
  for (int big = -2; big <= 2; ++big)
    for (size_t j = 1; j < syn.sectors.size(); ++j) {  // sector 1's start is closed onto the next big sector
      const auto& s = syn.sectors[j];
      const double q = s.theta + big * kPi;
      EXPECT_NEAR(d.kinematics(q).phi, s.phi + big * kPi / 2, 1e-12) << big << " " << j;
      EXPECT_NEAR(d.kinematics(q - 1e-12).phi, d.kinematics(q).phi, 1e-11);
      // The ratio below the boundary θ_j is sector j's (1-based j+1) Δθ/Δφ, above it sector j−1's.
      // (The last sector is closed onto the next big sector: its ratio moves by the synthesis
      // defects, 1.3e-5 relative for the paper's data.)
      EXPECT_NEAR(d.ratio_beside(q, -1), s.dtheta / s.dphi, j + 1 == syn.sectors.size() ? 3e-5 : 1e-12);
      EXPECT_NEAR(d.ratio_beside(q, +1), syn.sectors[j - 1].dtheta / syn.sectors[j - 1].dphi, 1e-12);
    }
  double p0, p1, dp, ddp;
  d.point(0.3, &p0, &dp, &ddp);
  d.point(0.3 + kPi, &p1, &dp, &ddp);
  const double A = 0.32, B = 0.3;
  EXPECT_NEAR(p1 - p0, A * kPi / 2 + B * std::sin(kPi / 2), 1e-12);
}

// Claim: the jump positions are the 24 sector boundaries per big sector, 48 per pinion turn, and
// next_jump walks them in both directions.
TEST(GearDrive, JumpPositionsAreTheSectorBoundaries) {
  const GearDrive d = drive(GearDrive::Ratio::stepwise);
  double q = 0.01;  // inside the sector around θ = 0
  int count = 0;
  while (true) {
    const double nq = d.next_jump(q, +1);
    if (nq > 0.01 + 2 * kPi) break;
    EXPECT_GT(nq, q);
    if (count > 0) {
      EXPECT_NEAR(d.next_jump(nq, -1), q, 1e-14);
    }
    q = nq;
    ++count;
  }
  EXPECT_EQ(count, 48);
  EXPECT_FALSE(drive(GearDrive::Ratio::continuous).has_jumps());
}

// Claim: the jump of the stepwise ratio is a perfectly plastic impact of the new tooth pair. Checked
// against independent statements: (1) afterwards the new rolling constraint holds with the carrier
// speed φ'+ = θ'+/i+; (2) the energy lost equals Carnot's ½ I_p (Δθ')² + ½ J_H (Δφ')² (the kinetic
// energy of the lost velocities, true only for a plastic impact with the impulse normal to the new
// constraint); (3) it equals ½ I(θ_b−) θ'−² − ½ I(θ_b+) θ'+² with I evaluated just beside the
// boundary; (4) the impulses on pinion and wheel, Λ r+ and Λ r_H+, are in the ratio 1 : i+.
TEST(GearDrive, JumpIsAPlasticImpactOfTheNewToothPair) {
  const GearDrive d = drive(GearDrive::Ratio::stepwise);
  double q = 0.05;
  for (int j = 0; j < 30; ++j) {
    q = d.next_jump(q, +1);
    const double w = 4.0;
    double loss;
    const double wp = d.velocity_after_jump(q, +1, w, &loss);
    const double im = d.ratio_beside(q, -1), ip = d.ratio_beside(q, +1);
    double X, dX, ddX;
    d.travel(d.kinematics(q).phi, &X, &dX, &ddX);
    const double J_H = 2.0 + 300.0 * dX * dX;
    const double dth = wp - w, dph = wp / ip - w / im;
    EXPECT_NEAR(loss, 0.5 * 0.5 * dth * dth + 0.5 * J_H * dph * dph, 1e-12 * (1 + loss)) << j;
    EXPECT_GE(loss, 0.0);
    double Im, Ip, dI;
    d.inertia(q - 1e-10, &Im, &dI);
    d.inertia(q + 1e-10, &Ip, &dI);
    EXPECT_NEAR(loss, 0.5 * Im * w * w - 0.5 * Ip * wp * wp, 1e-7) << j;
    // Angular impulses: pinion −Λ r+ = I_p Δθ', wheel +Λ r_H+ = J_H Δφ'; r_H+/r+ = i+.
    EXPECT_NEAR(J_H * dph, -ip * 0.5 * dth, 1e-9 * (1 + std::abs(J_H * dph))) << j;
    // Going back over the same boundary with the reversed motion is the mirror impact.
    double loss_back;
    const double wb = d.velocity_after_jump(q, -1, -w, &loss_back);
    EXPECT_NEAR(loss_back, 0.5 * 0.5 * (wb + w) * (wb + w) + 0.5 * J_H * std::pow(wb / im + w / ip, 2), 1e-10);
  }
}

}  // namespace
}  // namespace machdyn
