// The invariant audit (analysis/audit.hpp): every check fed a deliberately wrong state reports the
// element, the time, the values and the invariant (so no check is dead) and passes the same state
// made right; a driver that never decides its modes is caught on both integrators; a run with the
// audit on gives the same numbers as without it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/audit.hpp"
#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/solve/driver.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "audit.yaml"), "audit.yaml"); }

const FrictionContact& contact(const Model& m, const std::string& name) {
  for (const auto& c : m.contacts)
    if (c.name == name) return c;
  throw std::runtime_error("no contact " + name);
}
const Link& link(const Model& m, const std::string& name) {
  for (const auto& l : m.links)
    if (l.name == name) return l;
  throw std::runtime_error("no link " + name);
}

/// Runs `f`, expects an AuditError of `invariant` naming `element` at time `t` with `value` in its
/// message.
template <class F>
void expect_violation(F&& f, const std::string& invariant, const std::string& element, double t,
                      const std::string& value) {
  try {
    f();
    ADD_FAILURE() << "no violation of " << invariant;
  } catch (const AuditError& e) {
    EXPECT_EQ(e.invariant(), invariant) << e.what();
    EXPECT_EQ(e.element(), element) << e.what();
    EXPECT_EQ(e.time(), t) << e.what();
    const std::string what = e.what();
    EXPECT_NE(what.find(invariant), std::string::npos) << what;
    EXPECT_NE(what.find("'" + element + "'"), std::string::npos) << what;
    EXPECT_NE(what.find(value), std::string::npos) << what;
    const SolverError& base = e;  // exit 3 from the CLI, SolverError in Python
    EXPECT_EQ(base.element(), element);
  }
}

// One model with every element family the audit checks.
const char* kElements = R"(
bodies:
  a: {type: translational, mass: 1 kg}
  b: {type: translational, mass: 2 kg}
  c: {type: translational, mass: 1 kg}
  d: {type: translational, mass: 1 kg}
  e: {type: translational, mass: 1 kg}
links:
  g: {type: spring-damper, between: [a, b], stiffness: 1000 N/m, damping: 10 N*s/m, gap: 4 mm, gap_start: 1 mm}
  r: {type: rope, between: [b, c], stiffness: 1e5 N/m, slack: 2 mm}
contacts:
  k: {between: [a, ground], static: 10 N, kinetic: 6 N}
brakes:
  B: {body: b, holding: 100 N, braking: 80 N, time: 1 s, ramp: 1 s}
freewheels:
  fw: {between: [c, d]}
stops:
  s: {body: e, min: 0 m}
)";

// Claim: a stuck contact holds at most F_s (F_s0 = 10 N) plus the stick rule's rounding allowance
// 1e-12 F_s0 — exactly at the limit holds, 2e-12 F_s0 beyond it is reported with |λ| and F_s.
TEST(AuditChecks, StuckContactBeyondItsStaticLimit) {
  const Model m = model_of(kElements);
  const ContactLaw law = ContactLaw::of(contact(m, "k"));
  audit::ContactValues x;
  x.mode = ContactMode::stuck;
  x.F = -10.0;
  EXPECT_NO_THROW(audit::check_contact(law, "k", 0.25, x));
  x.F = -10.0 * (1 + 2e-12);
  expect_violation([&] { audit::check_contact(law, "k", 0.25, x); }, "contact.static_limit", "k", 0.25,
                   "F_s = 10");
  // The travel start-up's defect: stuck at 1.09 F_s.
  x.F = 10.9;
  expect_violation([&] { audit::check_contact(law, "k", 0.5, x); }, "contact.static_limit", "k", 0.5, "1.09 F_s");
}

// Claim: a contact labelled sliding at u = 0 whose motion the stuck contacts beside it lock is
// reported: two clutches between bodies 0 and 1 (rows e0 − e1 and e1 − e0), one stuck, the other
// "sliding" (the campaign's parallel clutches, released by a share of the full limits, slid at u ≡ 0
// with their kinetic force). Free of the stuck set (row e1 − e2, or u ≠ 0) it is no violation.
TEST(AuditChecks, ASlideTheStuckContactsLockIsStuck) {
  const std::vector<std::vector<double>> stuck = {{1.0, -1.0, 0.0}};
  expect_violation([&] { audit::check_locked_slide("K1", 0.3, ContactMode::slip_neg, 0.0, stuck, {-1.0, 1.0, 0.0}); },
                   "contact.locked_slide", "K1", 0.3, "slip-");
  // A loop: b0–ground and b0–b1 stuck lock b1–ground too.
  expect_violation([&] {
    audit::check_locked_slide("B", 0.1, ContactMode::slip_pos, 0.0, {{1.0, 0.0, 0.0}, {1.0, -1.0, 0.0}}, {0.0, 1.0, 0.0});
  }, "contact.locked_slide", "B", 0.1, "slip+");
  EXPECT_NO_THROW(audit::check_locked_slide("K2", 0.3, ContactMode::slip_neg, 0.0, stuck, {0.0, 1.0, -1.0}));
  EXPECT_NO_THROW(audit::check_locked_slide("K1", 0.3, ContactMode::slip_neg, -1e-3, stuck, {-1.0, 1.0, 0.0}));
  EXPECT_NO_THROW(audit::check_locked_slide("K1", 0.3, ContactMode::stuck, 0.0, stuck, {-1.0, 1.0, 0.0}));
}

// Claim: a brake's limit is its application r(t) F_s0: before its time (r = 0, released) it carries
// nothing, halfway up its ramp (t = 1.5 s: r = 0.5) at most 50 N.
TEST(AuditChecks, BrakeLimitFollowsItsApplication) {
  const Model m = model_of(kElements);
  const ContactLaw law = ContactLaw::of(contact(m, "B"));
  audit::ContactValues x;
  x.mode = ContactMode::stuck;
  x.F = 0.0;
  EXPECT_NO_THROW(audit::check_contact(law, "B", 0.5, x));
  x.F = 2000.0;  // the campaign's released brake holding its body with 2 kN
  expect_violation([&] { audit::check_contact(law, "B", 0.5, x); }, "contact.static_limit", "B", 0.5, "released");
  x.F = 50.0;
  EXPECT_NO_THROW(audit::check_contact(law, "B", 1.5, x));
  x.F = 50.001;
  expect_violation([&] { audit::check_contact(law, "B", 1.5, x); }, "contact.static_limit", "B", 1.5, "F_s = 50");
}

// Claim: a sliding contact's force is its kinetic law s F_k (6 N) and has the sign of its sliding
// velocity (its load on body a, −F, opposes a's motion relative to the ground).
TEST(AuditChecks, SlidingContactKineticLawAndDirection) {
  const Model m = model_of(kElements);
  const ContactLaw law = ContactLaw::of(contact(m, "k"));
  audit::ContactValues x;
  x.mode = ContactMode::slip_pos;
  x.u = 0.3, x.speed_scale = 0.3, x.F = 6.0;
  EXPECT_NO_THROW(audit::check_contact(law, "k", 1.0, x));
  x.F = 7.0;
  expect_violation([&] { audit::check_contact(law, "k", 1.0, x); }, "contact.kinetic_law", "k", 1.0,
                   "s r F_k(|u|) = 6");
  x.F = 6.0, x.u = -0.3;  // labelled slip+ while sliding backwards: friction drives the motion
  expect_violation([&] { audit::check_contact(law, "k", 1.0, x); }, "contact.sliding_direction", "k", 1.0,
                   "u = -0.29999999999999999");
  x.mode = ContactMode::slip_neg, x.F = -6.0;
  EXPECT_NO_THROW(audit::check_contact(law, "k", 1.0, x));
  // Within the integrator's velocity resolution (atol 1e-10 m/s) the direction is only a label; a
  // body sliding back at 1e-9 m/s is not.
  x.mode = ContactMode::slip_pos, x.F = 6.0, x.resolution = 1e-10, x.speed_scale = 2e-20, x.u = -2e-20;
  EXPECT_NO_THROW(audit::check_contact(law, "k", 1.0, x));
  x.u = -1e-9, x.speed_scale = 1e-9;
  expect_violation([&] { audit::check_contact(law, "k", 1.0, x); }, "contact.sliding_direction", "k", 1.0, "u = -1");
}

// Claim: a freewheel (lock +1) holds only while λ ≥ 0 (allowance ε_h, 1e-9 N without a model) and slides only in its
// free direction −lock.
TEST(AuditChecks, FreewheelNeverHoldsAgainstItsFreeDirection) {
  const Model m = model_of(kElements);
  const ContactLaw law = ContactLaw::of(contact(m, "fw"));
  ASSERT_EQ(law.lock, 1);
  audit::ContactValues x;
  x.mode = ContactMode::stuck;
  x.F = -0.5e-9;
  EXPECT_NO_THROW(audit::check_contact(law, "fw", 2.0, x));
  x.F = -3.0;
  expect_violation([&] { audit::check_contact(law, "fw", 2.0, x); }, "freewheel.hold", "fw", 2.0, "lock·λ = -3");
  x.mode = ContactMode::slip_pos, x.F = 0.0, x.u = 1.0, x.speed_scale = 1.0;
  expect_violation([&] { audit::check_contact(law, "fw", 2.0, x); }, "freewheel.direction", "fw", 2.0,
                   "locked direction");
}

// Claim: a body stays within its end stop (min 0 m): off the stop at q ≥ 0; at q = −1e-6 m it has
// passed through it. Resting on it, the stop only pushes (lock·λ ≥ 0).
TEST(AuditChecks, BodyStaysWithinItsEndStop) {
  const Model m = model_of(kElements);
  const ContactLaw law = ContactLaw::of(contact(m, "s"));
  audit::ContactValues x;
  x.mode = static_cast<ContactMode>(-law.lock);  // free
  x.q = 0.0;
  EXPECT_NO_THROW(audit::check_contact(law, "s", 0.7, x));
  x.q = -1e-6;
  expect_violation([&] { audit::check_contact(law, "s", 0.7, x); }, "stop.position", "s", 0.7, "q = -9.99");
  x.mode = ContactMode::stuck, x.q = 0.0, x.F = -law.lock * 5.0;  // the stop pulling the body on
  expect_violation([&] { audit::check_contact(law, "s", 0.7, x); }, "stop.hold", "s", 0.7, "lock·λ = -5");
}

// Claim: a closed flank's force has the flank's sign (positive flank δ₊ = 3 mm: F ≥ 0), and an open
// gap beyond its flank does not press into it (F₊ = c (δ − δ₊) + d δ̇ ≤ 0).
TEST(AuditChecks, GapFlankSignAndInside) {
  const Model m = model_of(kElements);
  const LinkLaw law = LinkLaw::of(m, link(m, "g"));
  ASSERT_DOUBLE_EQ(law.hi, 0.003);
  audit::LinkValues x;
  x.mode = GapMode::closed_pos, x.delta = 0.004, x.rate = 0.0, x.F = 1.0;
  EXPECT_NO_THROW(audit::check_link(law, "g", 0.1, x));
  x.F = -2.5;  // a closed flank pulling
  expect_violation([&] { audit::check_link(law, "g", 0.1, x); }, "gap.flank_sign", "g", 0.1, "F = -2.5");
  x.mode = GapMode::closed_neg, x.delta = -0.002, x.F = 3.0;  // the negative flank pushing
  expect_violation([&] { audit::check_link(law, "g", 0.1, x); }, "gap.flank_sign", "g", 0.1, "F = 3");
  // Open: inside the gap anything goes; 0.85 m past the flank and moving on: passed without closing.
  x.mode = GapMode::open, x.F = 0.0, x.delta = 0.001, x.rate = 1.0;
  EXPECT_NO_THROW(audit::check_link(law, "g", 0.1, x));
  x.delta = 0.853, x.rate = 0.1;
  expect_violation([&] { audit::check_link(law, "g", 0.1, x); }, "gap.inside", "g", 0.1, "positive flank 0.003");
  // Off the flank after opening at F = 0 (damped: it opens before δ is back at the flank) is no
  // violation: c e + d δ̇ = 1000·0.0001 + 10·(−0.02) < 0.
  x.delta = 0.0031, x.rate = -0.02;
  EXPECT_NO_THROW(audit::check_link(law, "g", 0.1, x));
  x.delta = -0.5, x.rate = -1.0;
  expect_violation([&] { audit::check_link(law, "g", 0.1, x); }, "gap.inside", "g", 0.1, "negative flank -0.001");
}

// Claim: a rope never pushes (taut: F ≥ 0); the campaign's −64 kN after the hook lands is reported.
TEST(AuditChecks, RopeNeverPushes) {
  const Model m = model_of(kElements);
  const LinkLaw law = LinkLaw::of(m, link(m, "r"));
  audit::LinkValues x;
  x.mode = GapMode::closed_pos, x.delta = 0.003, x.F = 100.0;
  EXPECT_NO_THROW(audit::check_link(law, "r", 3.0, x));
  x.F = -64000.0;
  expect_violation([&] { audit::check_link(law, "r", 3.0, x); }, "rope.never_pushes", "r", 3.0, "F = -64000");
}

// Claim: a lossy gear's loss power (X − Y) v_a is never negative: X = 10, Y = 9 at v_a = 2 loses 2 W;
// Y = 11 would deliver 2 W.
TEST(AuditChecks, LossyGearLossNeverNegative) {
  EXPECT_NO_THROW(audit::check_gear_loss("G", 0.4, 10.0, 9.0, 2.0));
  EXPECT_NO_THROW(audit::check_gear_loss("G", 0.4, 10.0, 11.0, 0.0));
  expect_violation([] { audit::check_gear_loss("G", 0.4, 10.0, 11.0, 2.0); }, "lossy_gear.loss", "G", 0.4,
                   "= -2 W");
}

// Claim: the books balance to tol · E_max + 1e-9 J: W = 100 J into ΔT = 60, ΔV = 30, friction 10
// closes; a lost 1 J (an impact not booked) is reported with the residual.
TEST(AuditChecks, EnergyBooksBalance) {
  audit::EnergyValues e;
  e.work = 100.0, e.kinetic = 60.0, e.elastic = 30.0, e.friction = 10.0;
  double E_max = 0.0;
  EXPECT_NO_THROW(audit::check_energy(0.9, e, 1e-6, E_max));
  EXPECT_EQ(E_max, 100.0);
  e.friction = 9.0;
  expect_violation([&] { audit::check_energy(0.9, e, 1e-6, E_max); }, "energy.balance", "energy books", 0.9,
                   "= 1 J");
  e.friction = 10.0 - 0.5e-4;  // within 1e-6 · 100 J
  EXPECT_NO_THROW(audit::check_energy(0.9, e, 1e-6, E_max));
}

// Claim: the mode columns agree with the event list: a row shows the last event's mode before it
// (a row at an event's time the mode before the event); a column that says otherwise is reported.
TEST(AuditChecks, EventListAgreesWithModeColumns) {
  const Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1 kg}}
contacts: {k: {between: [a, ground], static: 10 N, kinetic: 6 N}}
)");
  SimulationResult r;
  r.column_names = {"t_s", "k.mode"};
  r.columns = {{0.0, 0.1, 0.2, 0.3}, {0.0, 0.0, 1.0, 0.0}};
  r.hybrid.events = {{0.0, "initial", "k", "", "stuck"}, {0.1, "slip", "k", "stuck", "slip+"},
                     {0.25, "stick", "k", "slip+", "stuck"}};
  EXPECT_NO_THROW(audit::check_event_list(m, r));
  r.columns[1][3] = 1.0;  // still sliding by its column after the stick event
  expect_violation([&] { audit::check_event_list(m, r); }, "events.mode_columns", "k", 0.3, "stick at t = 0.25");
  r.columns[1] = {0.0, 0.0, 0.0, 0.0};  // a slip event the columns never show
  expect_violation([&] { audit::check_event_list(m, r); }, "events.mode_columns", "k", 0.2, "slip at t = 0.1");
}

// ---- end to end: the audit as the observer of the one driver ----

/// A broken event system for the test: the drive system's equations in their initial modes, with
/// no event functions (a missed event, for good). The audit must catch what it lets through.
class NeverDecides final : public EventSystem {
 public:
  explicit NeverDecides(DriveSystem& s) : s_(s) {}
  [[nodiscard]] int size() const override { return s_.size(); }
  void rhs(double t, const double* y, double* dydt) override { s_.rhs(t, y, dydt); }
  [[nodiscard]] std::string state_name(int i) const override { return s_.state_name(i); }

 private:
  DriveSystem& s_;
};

class AuditObserver final : public StepObserver {
 public:
  explicit AuditObserver(Audit& a) : a_(a) {}
  void on_step(const Stepper&) override { a_.settle(); }
  void on_segment(const Stepper& st, double, double tb) override { a_.piece_end(tb, tb == st.t(), st.y()); }
  void on_output(double t, const double* y) override { a_.row(t, y); }
  void on_event(double t, const double* y, const std::vector<int>& fired) override {
    a_.after_event(t, y, !fired.empty());
  }

 private:
  Audit& a_;
};

// Claim: a freewheel's drag D is the static limit of its free direction (elements/contact.hpp): a
// backstop with drag 10 N stuck holds a push in its free direction up to lock·λ = −10 N (the run of
// Impact.BackstopWithDragStaysAtRestUntilThePushReachesTheDrag: λ = P = 20 t N until 0.5 s), and not
// beyond; without drag the limit is 0.
TEST(AuditChecks, FreewheelDragIsTheLimitOfItsFreeDirection) {
  const Model m = model_of(R"(
bodies: {b: {type: translational, mass: 1}, c: {type: translational, mass: 1}}
freewheels: {F: {between: [ground, b], drag: 10}, G: {between: [ground, c]}}
)");
  for (const char* name : {"F", "G"}) {
    const ContactLaw law = ContactLaw::of(contact(m, name));
    const double D = std::string(name) == "F" ? 10.0 : 0.0;
    audit::ContactValues x;
    x.mode = ContactMode::stuck;
    x.F = -law.lock * D;  // at its drag: holds
    EXPECT_NO_THROW(audit::check_contact(law, name, 0.5, x)) << name;
    x.F = -law.lock * (D + 0.5);  // beyond it
    expect_violation([&] { audit::check_contact(law, name, 0.5, x); }, "freewheel.hold", name, 0.5, "lock·λ = -");
  }
}

class AuditRun : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, AuditRun, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: a block (1 kg, F_s = 10 N) on the ground pushed by P = 20 t N stays stuck until
// t* = F_s/20 = 0.5 s. A driver that never decides keeps it stuck beyond: the audit reports the
// contact at the first row or step end past t* (rows every 0.01 s: t ≤ 0.51 s) with |λ| = P(t) > F_s.
TEST_P(AuditRun, ADriverThatMissesTheBreakawayIsCaught) {
  Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1 kg}}
contacts: {k: {between: [a, ground], static: 10 N, kinetic: 6 N}}
loads: {P: {type: ramp, body: a, value: 20 N, end: 1 s}}
simulation: {t_end: 1 s, dt_out: 0.01 s}
)");
  DriveSystem sys(m, true);
  sys.set_contact_modes({ContactMode::stuck});
  NeverDecides broken(sys);
  std::vector<double> y(static_cast<size_t>(sys.size()), 0.0);
  sys.initial_state(y.data());
  EnergyBalance E;
  const double release = 0.0;
  Audit audit(m, sys, E, release);
  AuditObserver obs(audit);
  StepperOptions so;
  auto st = make_stepper(GetParam() == IntegratorChoice::bdf ? Method::bdf : Method::dopri5, broken, so);
  DriveOptions opt;
  opt.dt_out = m.simulation.dt_out;
  try {
    integrate(*st, broken, 0.0, y.data(), 1.0, opt, obs);
    audit.settle();
    FAIL() << "the missed breakaway was not caught";
  } catch (const AuditError& e) {
    EXPECT_EQ(e.invariant(), "contact.static_limit") << e.what();
    EXPECT_EQ(e.element(), "k");
    EXPECT_GT(e.time(), 0.5);
    EXPECT_LE(e.time(), 0.51 + 1e-12);
    EXPECT_NE(std::string(e.what()).find("F_s = 10"), std::string::npos) << e.what();
  }
}

// Claim: the same block run by simulate() with the audit on breaks away at t* = 0.5 s and passes
// every check; the audit changes no number (every column and event bit for bit as without it).
TEST_P(AuditRun, OnChangesNoNumber) {
  Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1 kg}, b: {type: translational, mass: 2 kg}}
links: {g: {type: spring-damper, between: [a, b], stiffness: 1000 N/m, damping: 5 N*s/m, gap: 4 mm}}
contacts: {k: {between: [b, ground], static: 10 N, kinetic: 6 N}}
brakes: {B: {body: a, holding: 3 N, braking: 2 N, time: 0.2 s, ramp: 0.1 s}}
loads: {P: {type: ramp, body: a, value: 40 N, end: 1 s}}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  // Off means off here, whatever the suite's MACHDYN_CHECK says.
  const char* env = std::getenv("MACHDYN_CHECK");
  const std::string saved = env ? env : "";
  unsetenv("MACHDYN_CHECK");
  SimulateOptions off, on;
  off.check = false;
  on.check = true;
  const SimulationResult a = simulate(m, off), b = simulate(m, on);
  if (env) setenv("MACHDYN_CHECK", saved.c_str(), 1);
  ASSERT_EQ(a.columns.size(), b.columns.size());
  for (size_t c = 0; c < a.columns.size(); ++c) EXPECT_EQ(a.columns[c], b.columns[c]) << a.column_names[c];
  ASSERT_EQ(a.hybrid.events.size(), b.hybrid.events.size());
  for (size_t k = 0; k < a.hybrid.events.size(); ++k) EXPECT_EQ(a.hybrid.events[k].t, b.hybrid.events[k].t);
  bool slipped = false;
  for (const auto& e : b.hybrid.events) slipped = slipped || (e.element == "k" && e.kind == "slip");
  EXPECT_TRUE(slipped);
}

// Claim: the audit resolves a speed to its integrator's global error, not to one step's tolerance.
// examples/msl/one-way-clutch.yaml (rtol 1e-10, atol 1e-12): after the freewheel releases at 7/6 s
// with the clutch open until 1.6 s, inertiaIn is driven by M = 10 sin 6πt and inertiaOut coasts, so
// u = ω_out − ω_in = −(10/(6π)) (1 + cos 6πt) ≤ 0 (closed form: ω_in = ω_out at 7/6 s, the integral of
// M/J since), touching 0 with u̇ = 0 at t = 1.5 s — a tangency, no event. Each integrator's u keeps
// within the audit's resolution 1e3 (atol + rtol S) of that closed form on every row of (1.17, 1.59) s
// (BDF is 7.7e-10 = 14 rtol S off, beyond one step's atol + rtol S: that tolerance called the tangency
// a freewheel sliding against its direction), the run with the audit on passes, and a wrong sign the
// size of a real missed lock (u = +1e-6 in slip−, 1e4 times the resolution) is still reported.
TEST_P(AuditRun, SpeedsAreResolvedToTheirGlobalError) {
  Model m = load_model(test::example("msl/one-way-clutch.yaml"));
  m.simulation.integrator = GetParam();
  SimulateOptions on;
  on.check = true;
  const SimulationResult r = simulate(m, on);
  const auto& t = test::series(r, "t_s");
  const auto& u = test::series(r, "freewheel.sliding_velocity_rad_s");
  const auto& wa = test::series(r, "inertiaIn.velocity_rad_s");
  const auto& wb = test::series(r, "inertiaOut.velocity_rad_s");
  double worst = 0.0, res_min = 1.0;
  int rows = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= 1.17 || t[k] >= 1.59) continue;
    ++rows;
    const double exact = -(10.0 / (6.0 * std::numbers::pi)) * (1.0 + std::cos(6.0 * std::numbers::pi * t[k]));
    const double res = 1e3 * (m.simulation.atol + m.simulation.rtol * (std::abs(wa[k]) + std::abs(wb[k])));
    worst = std::max(worst, std::abs(u[k] - exact) / res);
    res_min = std::min(res_min, res);
  }
  EXPECT_GT(rows, 400);
  EXPECT_LT(worst, 1.0);
  std::printf("OneWayClutch %s: |u − closed form| ≤ %.3g × the audit's resolution\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", worst);
  const ContactLaw law = ContactLaw::of(contact(m, "freewheel"));
  audit::ContactValues x;
  x.mode = static_cast<ContactMode>(-law.lock);
  x.speed_scale = 0.56;
  x.resolution = res_min;
  x.u = 0.1 * res_min * -static_cast<double>(law.lock);  // on its side: fine
  EXPECT_NO_THROW(audit::check_contact(law, "freewheel", 1.5, x));
  x.u = 1e4 * res_min * static_cast<double>(law.lock);  // against it: a missed lock
  expect_violation([&] { audit::check_contact(law, "freewheel", 1.5, x); }, "contact.sliding_direction", "freewheel",
                   1.5, "u = ");
}

// Claim: a lossy gear on a prescribed speed is audited on the speed the engine decides its mode on.
// examples/worm-hoist-s-curve.yaml stops its motor with 150 (1 − c)² (1 + 2c), c = t − 4 (a double
// root at 5 s); the integrated state may cross 0 up to its error, 1e-6 of the scale 150 rad/s, before
// the signal reaches it (dopri5: −3.2e-5 rad/s at 4.99955 s, where the signal is +9.1e-5). Both
// integrators pass the audit and the gear stops at the signal's rest, 5 s (within 1e-8 s).
TEST_P(AuditRun, LossyGearOnAPrescribedSpeedStopsWithItsSignal) {
  Model m = load_model(test::example("worm-hoist-s-curve.yaml"));
  m.simulation.integrator = GetParam();
  SimulateOptions on;
  on.check = true;
  const SimulationResult r = simulate(m, on);
  std::vector<double> stops;
  for (const auto& e : r.hybrid.events)
    if (e.element == "worm" && e.to == "stuck" && e.kind != "initial") stops.push_back(e.t);
  ASSERT_EQ(stops.size(), 1u);
  EXPECT_NEAR(stops[0], 5.0, 1e-8);
  // The motor's state at the rows before the stop is within 1e-6 × 150 rad/s of its signal.
  const auto& t = test::series(r, "t_s");
  const auto& w = test::series(r, "motor.velocity_rad_s");
  for (size_t k = 0; k < t.size(); ++k) {
    const double c2 = std::clamp(t[k] - 4.0, 0.0, 1.0), c1 = std::clamp(t[k] - 0.5, 0.0, 1.0);
    const double v = 150.0 * c1 * c1 * (3.0 - 2.0 * c1) * (1.0 - c2) * (1.0 - c2) * (1.0 + 2.0 * c2);
    EXPECT_NEAR(w[k], v, 1e-6 * 150.0) << t[k];
  }
}

}  // namespace
}  // namespace machdyn
