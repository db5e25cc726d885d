// The conformance of every registered element type (model/element_types.hpp) to the one interface
// (model/element.hpp). The test iterates the registry: a new type is checked without an edit here,
// and a type registered without an example instance fails. For each type, a small instance built
// through its compile function from its registered example (on rotational bodies A, B of 1 kg·m²):
// its Jacobian against central differences, its power balance, its stored power against the
// difference of its energy, its event functions continuous along a short motion and ≥ 0 in the mode
// its state implies, its linear terms equal to the difference Hessian of its energy where it has one,
// and every output column described (a name with its unit) and present in a run's time series.
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/linearize.hpp"
#include "model/element_types.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// The model of one instance `e` of `type` from its example, on A (and B), or on the bodies its
/// example names (a type whose fields name its bodies: ElementType::place).
Model instance_of(const detail::ElementType& type) {
  std::string yaml = type.place ? std::string("bodies: {") + type.example_bodies + "}\n"
                                : "bodies:\n  A: {inertia: 1 kg*m^2, velocity: 3 rad/s}\n  B: {inertia: 1 kg*m^2, velocity: -0.5 rad/s}\n";
  const std::string entry = std::string("{type: ") + type.name + ", " +
                            (type.place ? "" : type.bodies == 2 ? "between: [A, B], " : "body: A, ") + type.example + "}";
  yaml += std::string(type.section) + ":\n  e: " + entry + "\nsimulation: {t_end: 0.05 s, dt_out: 1 ms}\n";
  return test::model_text(yaml, std::string(type.name) + ".yaml");
}

/// The states the checks run at: positions and velocities of A and B (the element's own states
/// stay at their initial values); on more bodies, body i at its initial position + q[i % 2] with
/// velocity v[i % 2].
struct Sample {
  double q[2], v[2];
};
const Sample kSamples[] = {{{0.2, 0.05}, {3.0, -0.5}}, {{-0.1, 0.02}, {-2.0, 0.4}}, {{0.0, 0.0}, {0.7, 0.1}},
                           {{0.2, 0.05}, {3.0, 0.5}},   {{0.2, 0.05}, {-3.0, -0.5}}};

/// The unit suffixes an output column may end in (model/model.hpp unit_suffix of the units the
/// outputs use), and "mode" (a number without unit).
bool described(const std::string& name) {
  static const std::set<std::string> kUnits = {"A",   "V",   "W",     "J",     "K",    "degC", "rad", "m",   "s",
                                               "N",   "N_m", "rad_s", "m_s",   "rpm",  "Hz",   "kg",  "kg_m2"};
  if (name == "mode") return true;
  if (name.empty() || !std::islower(static_cast<unsigned char>(name[0]))) return false;
  for (size_t k = name.find('_'); k != std::string::npos; k = name.find('_', k + 1))
    if (kUnits.count(name.substr(k + 1))) return true;
  return false;
}

class Conformance : public ::testing::TestWithParam<const detail::ElementType*> {};

std::string type_name(const ::testing::TestParamInfo<const detail::ElementType*>& p) {
  std::string s = p.param->name;
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

INSTANTIATE_TEST_SUITE_P(Registry, Conformance, ::testing::ValuesIn(detail::element_types()), type_name);

// Claim: the type comes with an example instance that compiles through its own compile function
// on the section and number of bodies it registered, and names its registered type.
TEST_P(Conformance, HasAnExampleThatCompiles) {
  const detail::ElementType& type = *GetParam();
  ASSERT_NE(type.example, nullptr);
  ASSERT_STRNE(type.example, "") << "a registered type needs an example instance (MACHDYN_ELEMENT_TYPE's last argument)";
  const Model m = instance_of(type);
  ASSERT_EQ(m.drives.size(), 1u);
  EXPECT_STREQ(m.drives[0].law->type(), type.name);
  if (type.bodies > 0) {
    EXPECT_EQ(m.drives[0].law->bodies(), type.bodies);
  }
  EXPECT_EQ(m.drives[0].ports(), m.drives[0].law->bodies());
  EXPECT_LE(m.drives[0].ports(), ElementMotion::kMax);
  EXPECT_LE(m.drives[0].law->states(), ElementJacobian::kMax);
}

/// The model's state at sample s (bodies' q and v; the element's own states initial) in the mode the
/// element's law implies there at t.
void place(DriveSystem& sys, const Sample& s, double t, std::vector<double>& y) {
  sys.initial_state(y.data());
  const int n = sys.dof();
  for (int i = 0; i < n; ++i) y[static_cast<size_t>(i)] += s.q[i % 2], y[static_cast<size_t>(n + i)] = s.v[i % 2];
  sys.set_drive_mode(0, sys.natural_drive_mode(0, t, y.data()));
}

// Claim: at each sample, in the mode its state implies, the element's Jacobian terms ∂M/∂(q, v, x)
// and ∂x'/∂(q, v, x) equal central differences of its forces and rates (step 1e-6 (1 + |value|),
// within 1e-6 of the largest term); and that mode's event functions are ≥ 0 there.
TEST_P(Conformance, JacobianMatchesCentralDifferences) {
  const Model m = instance_of(*GetParam());
  DriveSystem sys(m, false);
  const Element& e = sys.drive(0);
  const int nb = e.bodies(), nx = e.states();
  std::vector<double> y(static_cast<size_t>(sys.size()));
  for (const Sample& s : kSamples) {
    const double t = 0.01;
    place(sys, s, t, y);
    const int mode = sys.drive_mode(0);
    ElementMotion b = sys.drive_motion(0, y.data());
    const double* x0 = y.data() + sys.drive_offset(0);
    std::vector<double> x(x0, x0 + nx);
    if (e.has_events() && !e.reads_acceleration(mode)) {
      double g[2];
      e.events(t, b, x.data(), mode, g);
      EXPECT_GE(g[0], 0.0) << "mode " << e.mode_name(mode);
      EXPECT_GE(g[1], 0.0) << "mode " << e.mode_name(mode);
    }
    const ElementJacobian J = e.jacobian(t, b, x.data(), mode);
    // f = [M_0 .. M_nb-1, x'_0 .. x'_nx-1] as a function of z = [q, v, x].
    auto eval = [&](const ElementMotion& bb, const std::vector<double>& xx) {
      std::vector<double> f(static_cast<size_t>(nb + nx), 0.0);
      e.forces(t, bb, xx.data(), mode, f.data());
      if (nx > 0) e.rates(t, bb, xx.data(), mode, f.data() + nb);
      return f;
    };
    auto analytic = [&](int row, int col) {  // col: q_r (r < nb), v_r (nb + r), x_k (2 nb + k)
      if (row < nb) {
        if (col < nb) return J.dM_dq[row][col];
        if (col < 2 * nb) return J.dM_dv[row][col - nb];
        return J.dM_dx[row][col - 2 * nb];
      }
      const int k = row - nb;
      if (col < nb) return J.dx_dq[k][col];
      if (col < 2 * nb) return J.dx_dv[k][col - nb];
      return J.dx_dx[k][col - 2 * nb];
    };
    double worst = 0.0, scale = 1.0;
    for (int col = 0; col < 2 * nb + nx; ++col) {
      ElementMotion bp = b, bm = b;
      std::vector<double> xp = x, xm = x;
      double* zp = col < nb ? &bp.q[col] : col < 2 * nb ? &bp.v[col - nb] : &xp[static_cast<size_t>(col - 2 * nb)];
      double* zm = col < nb ? &bm.q[col] : col < 2 * nb ? &bm.v[col - nb] : &xm[static_cast<size_t>(col - 2 * nb)];
      const double h = 1e-6 * (1.0 + std::abs(*zp));
      *zp += h, *zm -= h;
      const std::vector<double> fp = eval(bp, xp), fm = eval(bm, xm);
      for (int row = 0; row < nb + nx; ++row) {
        const double D = (fp[static_cast<size_t>(row)] - fm[static_cast<size_t>(row)]) / (2.0 * h);
        const double A = analytic(row, col);
        scale = std::max(scale, std::abs(A));
        worst = std::max(worst, std::abs(A - D));
        if (col < nb && !e.reads_positions()) {
          EXPECT_EQ(A, 0.0) << "a q term of an element that reads no positions";
        }
      }
    }
    EXPECT_LT(worst, 1e-6 * scale) << "mode " << e.mode_name(mode) << " at q = (" << s.q[0] << ", " << s.q[1] << ")";
  }
}

// Claim: the power it puts into its bodies is its supply's power less the rate of its stored energy
// and its heat, Σ M_p v_p = P_source − dV/dt − P_heat (within 1e-9 of the largest term); P_heat ≥ 0;
// dV/dt is the central difference of its energy along the motion (q + s v, x + s x'), within 1e-6.
TEST_P(Conformance, PowerBalances) {
  const Model m = instance_of(*GetParam());
  DriveSystem sys(m, false);
  const Element& e = sys.drive(0);
  const int nb = e.bodies(), nx = e.states();
  std::vector<double> y(static_cast<size_t>(sys.size()));
  for (const Sample& s : kSamples) {
    const double t = 0.01;
    place(sys, s, t, y);
    const int mode = sys.drive_mode(0);
    const ElementMotion b = sys.drive_motion(0, y.data());
    const double* x = y.data() + sys.drive_offset(0);
    double M[ElementMotion::kMax] = {};
    e.forces(t, b, x, mode, M);
    double P = 0.0;
    for (int p = 0; p < nb; ++p) P += M[p] * b.v[p];
    const double src = e.source_power(t, b, x, mode), heat = e.heat_power(t, b, x, mode);
    const double stored = e.stored_power(t, b, x, mode);
    const double scale = std::max({1.0, std::abs(P), std::abs(src), std::abs(heat), std::abs(stored)});
    EXPECT_NEAR(P, src - stored - heat, 1e-9 * scale) << "mode " << e.mode_name(mode);
    EXPECT_GE(heat, 0.0);
    if (!e.dissipates()) {
      EXPECT_EQ(heat, 0.0) << "heat from an element that does not dissipate";
    }
    // dV/dt along the motion.
    std::vector<double> dx(static_cast<size_t>(nx), 0.0);
    if (nx > 0) e.rates(t, b, x, mode, dx.data());
    const double h = 1e-6;
    auto V_at = [&](double sgn) {
      ElementMotion bb = b;
      std::vector<double> xx(x, x + nx);
      for (int p = 0; p < nb; ++p) bb.q[p] += sgn * h * b.v[p];
      for (int k = 0; k < nx; ++k) xx[static_cast<size_t>(k)] += sgn * h * dx[static_cast<size_t>(k)];
      return e.energy(bb, xx.data(), mode);
    };
    const double dV = (V_at(1.0) - V_at(-1.0)) / (2.0 * h);
    EXPECT_NEAR(stored, dV, 1e-6 * scale) << "stored power against the energy's difference";
    if (!e.has_energy()) {
      EXPECT_EQ(e.energy(b, x, mode), 0.0);
    }
  }
}

// Claim: in a fixed mode its event functions are continuous along a short motion of the drive
// system: along y(s) = y + s y'(y), |g(s) − g(0)| falls at least fivefold per decade of s from
// s = 1e-4 to 1e-7 s (or stays below 1e-12 of |g|'s scale).
TEST_P(Conformance, EventFunctionsAreContinuous) {
  const Model m = instance_of(*GetParam());
  DriveSystem sys(m, false);
  const int N = sys.size(), slot = sys.event_slots() - 2;  // the element's two slots (its model's last)
  ASSERT_TRUE(sys.slot_is_drive(slot));
  std::vector<double> y(static_cast<size_t>(N)), dy(y), ys(y), g0(static_cast<size_t>(sys.event_slots())), gs(g0);
  for (const Sample& s : kSamples) {
    const double t = 0.01;
    place(sys, s, t, y);
    sys.rhs(t, y.data(), dy.data());
    sys.event_functions(t, y.data(), g0.data());
    for (int k = 0; k < 2; ++k) {
      const double g = g0[static_cast<size_t>(slot + k)], tiny = 1e-12 * std::max(1.0, std::abs(g));
      double last = HUGE_VAL;
      for (double h : {1e-4, 1e-5, 1e-6, 1e-7}) {
        for (int j = 0; j < N; ++j) ys[static_cast<size_t>(j)] = y[static_cast<size_t>(j)] + h * dy[static_cast<size_t>(j)];
        sys.event_functions(t + h, ys.data(), gs.data());
        const double jump = std::abs(gs[static_cast<size_t>(slot + k)] - g);
        if (last > tiny) {
          EXPECT_LT(jump, std::max(0.2 * last, tiny)) << "slot " << k << " at s = " << h;
        }
        last = jump;
      }
    }
  }
}

// Claim: where it stores energy, its linear terms in a mode are the Hessian of that energy over its
// bodies' positions (central second differences, step 1e-4, within 1e-5 of the largest entry).
TEST_P(Conformance, LinearTermsAreTheHessianOfTheEnergy) {
  const Model m = instance_of(*GetParam());
  DriveSystem sys(m, false);
  const Element& e = sys.drive(0);
  if (!e.has_energy()) GTEST_SKIP() << e.type() << " stores no energy";
  const int nb = e.bodies();
  std::vector<double> y(static_cast<size_t>(sys.size()));
  for (const Sample& s : kSamples) {
    place(sys, s, 0.0, y);
    const int mode = sys.drive_mode(0);
    const ElementMotion b = sys.drive_motion(0, y.data());
    const double* x = y.data() + sys.drive_offset(0);
    LinearModel lin(m.dof());
    add_drive_linear(m.drives[0], mode, lin, y.data(), x);
    const Eigen::MatrixXd K(lin.stiffness());
    const double h = 1e-4;
    double worst = 0.0, scale = 1e-12;
    for (int r = 0; r < nb; ++r)
      for (int c = 0; c < nb; ++c) {
        auto V = [&](double dr, double dc) {
          ElementMotion bb = b;
          bb.q[r] += dr, bb.q[c] += dc;
          return e.energy(bb, x, mode);
        };
        const double H = (V(h, h) - V(h, -h) - V(-h, h) + V(-h, -h)) / (4.0 * h * h);
        auto body_of = [&](int p) { return p == 0 ? m.drives[0].body : m.drives[0].others[static_cast<size_t>(p - 1)]; };
        const int br = body_of(r), bc = body_of(c);
        scale = std::max(scale, std::abs(H));
        worst = std::max(worst, std::abs(K(br, bc) - H));
      }
    EXPECT_LT(worst, 1e-5 * scale) << "mode " << e.mode_name(mode) << "\nK\n" << K;
  }
}

// Claim: every output column is described — a lower-case name ending in its unit ("_A", "_N_m",
// "_degC", …) or "mode" — with a finite value; every state has a name and a unit; the element
// describes itself; and a run's time series has the element's torque column and each of its own.
TEST_P(Conformance, OutputColumnsAreDescribed) {
  const Model m = instance_of(*GetParam());
  const Element& e = *m.drives[0].law;
  const BodyKind kind = m.bodies[static_cast<size_t>(m.drives[0].body)].kind;
  const std::vector<std::string> names = e.output_names(kind);
  for (const std::string& n : names) EXPECT_TRUE(described(n)) << "column '" << n << "'";
  for (int j = 0; j < e.states(); ++j) {
    EXPECT_STRNE(e.state_name(j), "");
    EXPECT_NE(e.state_unit(j, kind), "");
  }
  EXPECT_NE(e.describe(kind), "");
  EXPECT_STRNE(e.mode_name(0), "");
  const SimulationResult r = simulate(m);
  EXPECT_NO_THROW(test::column(r, "e.torque_" + unit_suffix(load_unit(kind))));
  for (const std::string& n : names) {
    const auto& col = test::series(r, "e." + n);
    for (double v : col) ASSERT_TRUE(std::isfinite(v)) << n;
  }
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
