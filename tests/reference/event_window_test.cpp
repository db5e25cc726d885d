// The campaign's comparison of event instants (tests/reference/campaign.hpp): an instant is compared
// as well as the model fixes it — within the reference event's resolution window where that is wider
// than kEventTol — and a real shift of 1e-3 s is still caught.
#include <cmath>
#include <string>
#include <gtest/gtest.h>

#include "reference/campaign.hpp"
#include "reference/reference.hpp"

namespace machdyn::reference {
namespace MACHDYN_UNITY_ID {

class EventWindow : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Integrators, EventWindow, ::testing::Values("dopri5", "bdf"),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

/// The first event of `kind` in r (nullptr: none).
RefEvent* first(RefResult& r, const std::string& kind) {
  for (auto& e : r.events)
    if (e.kind == kind) return &e;
  return nullptr;
}

// Claim: a double root. A block A (m = 1 kg) pulled by a step P = 100 N at t₀ = 0.1 s drives B
// (1 kg) through a spring c = 100 N/m; B rests on a backstop without drag, which P pushes in its
// free direction. With B held, x_A = (P/c)(1 − cos ω(t − t₀)), ω = √(c/m) = 10 rad/s, so the
// backstop carries λ = c x_A = P (1 − cos ωτ) ≈ c₂ τ², c₂ = P ω²/2 = 5000 N/s², τ = t − t₀: a root of
// multiplicity 2 at τ = 0, passed by the hold rule's allowance of 1e-9 N (the reference fires where
// its function passes −1e-13 of the force scale P, so at λ = 1e-9 + 1e-11 N) at τ* = √(1.01e-9/c₂) =
// 4.49e-7 s. Its function is known to δ = kLoadResolution · 100 N = 1e-5 N (the model's force scale is
// P), so the instant is fixed only to w = √((δ + 1.01e-9)/c₂) − τ* = 4.43e-5 s — the time after τ* over
// which λ stays within δ of its value there (the side before is shorter: it ends at t₀). The window
// found by doubling lies in (w/2, w]; the engine's instant is compared within it; the reference's
// instant moved by 0.9 of the window still agrees, moved by 2.5 w it does not.
TEST_P(EventWindow, ADoubleRootIsComparedWithinItsResolutionWindow) {
  RefModel m;
  m.bodies = {{"A", 1.0, 0.0, 0.0}, {"B", 1.0, 0.0, 0.0}};
  Link k;
  k.name = "k", k.a = 0, k.b = 1, k.c = 100.0;
  m.links = {k};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::step, P.s.value = 100.0, P.s.before = 0.0, P.s.t0 = 0.1;
  m.loads = {P};
  Friction f;
  f.kind = Friction::Kind::freewheel, f.name = "backstop", f.a = kGround, f.b = 1, f.drag = 0.0;
  m.frictions = {f};
  m.t_end = 0.2, m.dt_out = 0.002;
  RefResult ref = simulate_reference(m);
  ASSERT_TRUE(ref.error.empty()) << ref.error;
  RefEvent* slip = first(ref, "slip");
  ASSERT_NE(slip, nullptr);
  const double c2 = 100.0 * 100.0 / 2, level = 1e-9 + 1e-13 * 100.0, tau_s = std::sqrt(level / c2);
  const double delta = kLoadResolution * 100.0, w = std::sqrt((delta + level) / c2) - tau_s;
  EXPECT_NEAR(slip->t, 0.1 + tau_s, 1e-12);
  EXPECT_GT(slip->window, w / 2);
  EXPECT_LE(slip->window, w * (1 + 1e-6));
  const Outcome o = compare(m, GetParam(), ref);
  EXPECT_EQ(o.kind, Outcome::Kind::pass) << o.detail;
  const double t = slip->t, window = slip->window;
  slip->t = t + 0.9 * window;
  EXPECT_EQ(compare(m, GetParam(), ref).kind, Outcome::Kind::pass);
  slip->t = t + 2.5 * w;
  EXPECT_EQ(compare(m, GetParam(), ref).kind, Outcome::Kind::event_mismatch);
}

// Claim: a simple root keeps kEventTol. A block (1 kg) under P = 200 t N against a contact of
// F_s = 10 N, F_k = 8 N breaks away at t* = F_s/200 = 0.05 s; its function F_s − |λ| falls at
// 200 N/s and is known to δ = kLoadResolution · 20 N (the load's largest value at t_end = 0.1 s):
// δ/200 = 1e-8 s, below the window's first probe (1e-7 s) — no window. The reference's instant
// moved by 1e-3 s is an event mismatch on both integrators (the states agree: the event list is
// wrong, which the comparison must see), unmoved it agrees.
TEST_P(EventWindow, ASimpleRootStillCatchesAShiftOf1ms) {
  RefModel m;
  m.bodies = {{"block", 1.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.value = 20.0, P.s.before = 0.0, P.s.t0 = 0.0, P.s.t1 = 0.1;
  m.loads = {P};
  Friction f;
  f.kind = Friction::Kind::contact, f.name = "f", f.a = 0, f.b = kGround, f.Fs = 10.0, f.Fk = 8.0;
  m.frictions = {f};
  m.t_end = 0.1, m.dt_out = 0.001;
  RefResult ref = simulate_reference(m);
  ASSERT_TRUE(ref.error.empty()) << ref.error;
  RefEvent* slip = first(ref, "slip");
  ASSERT_NE(slip, nullptr);
  EXPECT_NEAR(slip->t, 0.05, 1e-11);
  EXPECT_EQ(slip->window, 0.0);
  const Outcome o = compare(m, GetParam(), ref);
  EXPECT_EQ(o.kind, Outcome::Kind::pass) << o.detail;
  slip->t += 1e-3;
  const Outcome shifted = compare(m, GetParam(), ref);
  EXPECT_EQ(shifted.kind, Outcome::Kind::event_mismatch) << shifted.detail;
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn::reference
