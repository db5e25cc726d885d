// The crane standards' factors (analysis/crane_standard.hpp) against every value printed on the
// table of docs/crane-factors.md, "Where the standard's values come from" (public sources named there;
// cited in each claim as "crane-standards.md, <section>", the facts page the table was built from).
#include <stdexcept>
#include <gtest/gtest.h>

#include "machdyn/analysis/crane_standard.hpp"

namespace machdyn::crane {
namespace MACHDYN_UNITY_ID {

constexpr HoistingClass kHC[4] = {HoistingClass::HC1, HoistingClass::HC2, HoistingClass::HC3, HoistingClass::HC4};
constexpr HoistDriveClass kHD[5] = {HoistDriveClass::HD1, HoistDriveClass::HD2, HoistDriveClass::HD3,
                                    HoistDriveClass::HD4, HoistDriveClass::HD5};

// Claim (crane-standards.md, EN 13001-2 φ2 table): β2 = 0.17, 0.34, 0.51, 0.68 s/m and φ2,min for
// HD1, HD2, HD4 = 1.05, 1.10, 1.15, 1.20 by HC1 … HC4; HD3 and HD5 have φ2,min = 1.05 in every class.
TEST(CraneStandard, Phi2TableValues) {
  const double beta[4] = {0.17, 0.34, 0.51, 0.68}, pmin[4] = {1.05, 1.10, 1.15, 1.20};
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(beta2(kHC[c]), beta[c]) << c;
    for (HoistDriveClass hd : {HoistDriveClass::HD1, HoistDriveClass::HD2, HoistDriveClass::HD4})
      EXPECT_EQ(phi2_min(kHC[c], hd), pmin[c]) << c;
    for (HoistDriveClass hd : {HoistDriveClass::HD3, HoistDriveClass::HD5}) EXPECT_EQ(phi2_min(kHC[c], hd), 1.05) << c;
  }
}

// Claim (crane-standards.md, EN 13001-2, characteristic vh): HD1 vh,max; HD2 and HD3 the creep
// speed; HD4 0.5 vh,max; HD5 0. And φ2 = φ2,min + β2 vh: HC2/HD1 at 1 m/s is 1.10 + 0.34 = 1.44;
// HC4/HD4 at vh,max = 0.5 m/s: vh = 0.25, 1.20 + 0.68 · 0.25 = 1.37; HC3/HD5: 1.05 whatever vh,max.
TEST(CraneStandard, CharacteristicSpeedAndPhi2) {
  const double vmax = 0.5, vcs = 0.08;
  const double want[5] = {0.5, 0.08, 0.08, 0.25, 0.0};
  for (int d = 0; d < 5; ++d) EXPECT_EQ(characteristic_hoisting_speed(kHD[d], vmax, vcs), want[d]) << d;
  EXPECT_DOUBLE_EQ(phi2(HoistingClass::HC2, HoistDriveClass::HD1, 1.0), 1.44);
  EXPECT_DOUBLE_EQ(phi2(HoistingClass::HC4, HoistDriveClass::HD4,
                        characteristic_hoisting_speed(HoistDriveClass::HD4, vmax, vcs)), 1.37);
  EXPECT_EQ(phi2(HoistingClass::HC3, HoistDriveClass::HD5, characteristic_hoisting_speed(HoistDriveClass::HD5, 2, 0)),
            1.05);
  EXPECT_THROW(phi2(HoistingClass::HC1, HoistDriveClass::HD1, -1.0), std::invalid_argument);
  EXPECT_EQ(parse_hoisting_class("HC3"), HoistingClass::HC3);
  EXPECT_EQ(to_string(parse_hoist_drive_class("HD5")), "HD5");
  EXPECT_THROW(parse_hoisting_class("HC5"), std::invalid_argument);
}

// Claim (crane-standards.md, EN 13001-2 φ3): φ3 = 1 − (Δm/m)(1 + β3), β3 = 0.5 slow / 1.0 rapid:
// releasing half the load rapidly gives 1 − 0.5 · 2 = 0; a quarter slowly 1 − 0.25 · 1.5 = 0.625.
TEST(CraneStandard, Phi3Formula) {
  EXPECT_EQ(beta3(ReleaseKind::slow), 0.5);
  EXPECT_EQ(beta3(ReleaseKind::rapid), 1.0);
  EXPECT_EQ(phi3(500, 1000, ReleaseKind::rapid), 0.0);
  EXPECT_EQ(phi3(250, 1000, ReleaseKind::slow), 0.625);
  EXPECT_EQ(phi3(0, 1000, ReleaseKind::rapid), 1.0);
  EXPECT_THROW(phi3(1100, 1000, ReleaseKind::slow), std::invalid_argument);
  EXPECT_THROW(phi3(1, 0, ReleaseKind::slow), std::invalid_argument);
}

// Claim (crane-standards.md, EN 13001-2 φ5, φ6): φ5 is 1.0 centrifugal, 1.0–1.5 smooth, 1.5–2.0
// sudden, 3.0 with considerable backlash; φ6,dyn = 0.5 (1 + φ2).
TEST(CraneStandard, Phi5RangesAndPhi6) {
  EXPECT_EQ(phi5_range(DriveForceChange::centrifugal).lo, 1.0);
  EXPECT_EQ(phi5_range(DriveForceChange::centrifugal).hi, 1.0);
  EXPECT_EQ(phi5_range(DriveForceChange::smooth).lo, 1.0);
  EXPECT_EQ(phi5_range(DriveForceChange::smooth).hi, 1.5);
  EXPECT_EQ(phi5_range(DriveForceChange::sudden).lo, 1.5);
  EXPECT_EQ(phi5_range(DriveForceChange::sudden).hi, 2.0);
  EXPECT_EQ(phi5_range(DriveForceChange::backlash).lo, 3.0);
  EXPECT_EQ(phi5_range(DriveForceChange::backlash).hi, 3.0);
  EXPECT_DOUBLE_EQ(phi6_dynamic(1.44), 1.22);
}

// Claim (crane-standards.md, EN 13001-2 φ7): φ7 = 1.25 for 0 ≤ ξb ≤ 0.5 (not 1.6, the suspected
// calculator bug) and 1.25 + 0.7 (ξb − 0.5) above: 1.25 at 0, 0.5; 1.6 at 1.0; 1.46 at 0.8.
TEST(CraneStandard, Phi7Formula) {
  EXPECT_EQ(phi7(0.0), 1.25);
  EXPECT_EQ(phi7(0.3), 1.25);
  EXPECT_EQ(phi7(0.5), 1.25);
  EXPECT_DOUBLE_EQ(phi7(0.8), 1.46);
  EXPECT_DOUBLE_EQ(phi7(1.0), 1.6);
  EXPECT_THROW(phi7(1.01), std::invalid_argument);
  EXPECT_THROW(phi7(-0.1), std::invalid_argument);
}

// Claim: ξb = ∫F dx / (F_max x_max), the trapezoids exact for a piecewise linear table: a linear
// characteristic gives 1/2; a constant force after a linear rise over 10 % of the stroke
// (hydraulic-like) gives (0.05 + 0.9)/1 = 0.95; F = c x² sampled finely tends to 1/3 (error of the
// trapezoid rule c h²/6 · x_max over c x_max³: 1/(6 N²)).
TEST(CraneStandard, BufferEnergyRatio) {
  EXPECT_EQ(buffer_energy_ratio({0, 0.1}, {0, 5e4}), 0.5);
  EXPECT_DOUBLE_EQ(buffer_energy_ratio({0, 0.01, 0.1}, {0, 1e5, 1e5}), 0.95);
  const int N = 1000;
  std::vector<double> x, F;
  for (int k = 0; k <= N; ++k) x.push_back(0.2 * k / N), F.push_back(x.back() * x.back());
  EXPECT_NEAR(buffer_energy_ratio(x, F), 1.0 / 3.0 + 1.0 / (6.0 * N * N), 1e-12);
  EXPECT_THROW(buffer_energy_ratio({0.1, 0.2}, {0, 1}), std::invalid_argument);
  EXPECT_THROW(buffer_energy_ratio({0, 0.2, 0.1}, {0, 1, 2}), std::invalid_argument);
  EXPECT_THROW(buffer_energy_ratio({0, 0.2}, {0, 0}), std::invalid_argument);
}

// Claim (crane-standards.md, FEM 1.001 and DIN 15018): ψ = 1 + ξ vL with ξ = 0.6 (overhead, gantry)
// or 0.3 (jib), never below 1.15, taken at 1 m/s above it; DIN H1…H4 ψ = 1.1 + 0.0022 v … 1.4 +
// 0.0088 v with v in m/min: H2 at 0.5 m/s = 30 m/min gives 1.2 + 0.132 = 1.332.
TEST(CraneStandard, FemAndDinPsi) {
  EXPECT_DOUBLE_EQ(fem_psi(CraneType::overhead_or_gantry, 0.5), 1.3);
  EXPECT_DOUBLE_EQ(fem_psi(CraneType::jib, 0.3), 1.15);   // 1.09 raised to the floor
  EXPECT_DOUBLE_EQ(fem_psi(CraneType::jib, 0.8), 1.24);
  EXPECT_DOUBLE_EQ(fem_psi(CraneType::overhead_or_gantry, 2.0), 1.6);
  EXPECT_DOUBLE_EQ(din_psi(1, 0.0), 1.1);
  EXPECT_DOUBLE_EQ(din_psi(2, 0.5), 1.332);
  EXPECT_DOUBLE_EQ(din_psi(3, 1.0), 1.3 + 0.0066 * 60);
  EXPECT_DOUBLE_EQ(din_psi(4, 1.0), 1.4 + 0.0088 * 60);
  EXPECT_THROW(din_psi(5, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace machdyn::crane
