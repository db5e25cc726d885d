// Random small models (generator.hpp) and their model files.
#include "reference/generator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace machdyn::reference {

const std::vector<std::string>& all_families() {
  static const std::vector<std::string> f = {"chain", "gap",   "one-sided", "ground-friction", "body-friction",
                                             "brake", "clutch", "freewheel", "stop",            "mixed", "signals", "gear", "planetary", "motion", "release", "kinetic", "buffer", "dc-motor", "drum",
                                             "gear-mesh", "sway"};
  return f;
}

namespace {

/// splitmix64: a small, portable generator (the same models on every platform and library).
struct Rng {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double u() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  ///< [0, 1)
  double u(double a, double b) { return a + (b - a) * u(); }
  double log_u(double a, double b) { return a * std::pow(b / a, u()); }
  int i(int a, int b) { return a + static_cast<int>(next() % static_cast<std::uint64_t>(b - a + 1)); }  ///< [a, b]
  bool p(double prob) { return u() < prob; }
};

/// x rounded to `d` significant digits (readable files; the reference reads the same double).
double sig(double x, int d = 3) {
  if (x == 0.0) return 0.0;
  const double e = std::pow(10.0, d - 1 - static_cast<int>(std::floor(std::log10(std::abs(x)))));
  return std::round(x * e) / e;
}

/// A random table: 3–5 points over the run (the first sometimes after 0, sometimes a jump: two
/// points at one time), values from `value(r)`; outside held or extrapolated.
template <class V>
Signal random_table(Rng& r, double t_end, V value, bool may_extrapolate) {
  Signal s;
  s.kind = Signal::Kind::table;
  const int n = r.i(3, 5);
  double t = r.p(0.5) ? 0.0 : sig(r.u(0.0, 0.3) * t_end);
  for (int k = 0; k < n; ++k) {
    s.points.emplace_back(t, value(r));
    // A jump: never at the ends (an extrapolated table needs end segments of positive length).
    if (k + 2 < n && r.p(0.2) && k >= 1) s.points.emplace_back(t, value(r)), ++k;
    t = sig(t + r.u(0.05, 0.35) * t_end);
  }
  s.extrapolate = may_extrapolate && r.p(0.4);
  return s;
}

/// A random pulse train from `start` with `count` pulses (or no end).
Signal random_pulse(Rng& r, double t_end, double low, double high) {
  Signal s;
  s.kind = Signal::Kind::pulse, s.before = low, s.value = high;
  s.period = sig(r.u(0.1, 0.5) * t_end);
  s.width = sig(s.period * r.u(0.2, 0.7));
  s.t0 = r.p(0.5) ? 0.0 : sig(r.u(0.0, 0.4) * t_end);
  s.count = r.p(0.5) ? -1 : r.i(1, 4);
  return s;
}

/// A random expression c0 + c1 t + A sin(2π f t + phase) + B exp(−t/τ) of magnitude about `scale`.
Signal random_expression(Rng& r, double t_end, double scale) {
  Signal s;
  s.kind = Signal::Kind::expression;
  s.offset = r.p(0.5) ? 0.0 : sig(r.u(-0.5, 0.5) * scale);
  s.slope = r.p(0.5) ? 0.0 : sig(r.u(-1, 1) * scale / t_end);
  if (r.p(0.7)) s.amplitude = sig(r.u(0.2, 1) * scale), s.frequency_hz = sig(r.u(0.5, 6.0), 2), s.phase = sig(r.u(0, 3));
  if (r.p(0.5)) s.decay = sig(r.u(-1, 1) * scale), s.tau = sig(r.u(0.05, 0.5) * t_end);
  return s;
}

/// A load signal of every kind of docs/model-files.md (but sum and file), magnitude about `scale`.
Signal random_signal(Rng& r, double t_end, double scale, bool every_kind) {
  Signal s;
  switch (every_kind ? r.i(0, 6) : r.i(0, 3)) {
    case 0: s.kind = Signal::Kind::constant, s.value = sig(r.u(-1, 1) * scale); break;
    case 1:
      s.kind = Signal::Kind::step, s.value = sig(r.u(-1, 1) * scale), s.before = r.p(0.5) ? 0.0 : sig(r.u(-1, 1) * scale);
      s.t0 = sig(r.u(0.05, 0.7) * t_end);
      break;
    case 2:
      s.kind = Signal::Kind::ramp, s.value = sig(r.u(-1, 1) * scale), s.before = r.p(0.6) ? 0.0 : sig(r.u(-1, 1) * scale);
      s.t0 = r.p(0.5) ? 0.0 : sig(r.u(0.0, 0.4) * t_end), s.t1 = sig(s.t0 + r.u(0.05, 0.5) * t_end);
      break;
    case 3:
      s.kind = Signal::Kind::sine, s.amplitude = sig(r.u(0.2, 1) * scale), s.frequency_hz = sig(r.u(0.5, 6.0), 2);
      s.phase = r.p(0.5) ? 0.0 : sig(r.u(0, 3)), s.offset = r.p(0.5) ? 0.0 : sig(r.u(-0.5, 0.5) * scale);
      s.t0 = r.p(0.6) ? 0.0 : sig(r.u(0.05, 0.5) * t_end);
      break;
    case 4: s = random_table(r, t_end, [&](Rng& g) { return sig(g.u(-1, 1) * scale); }, true); break;
    case 5: {  // the draws in sequence (a function's arguments are evaluated in an unspecified order:
               // GCC's right to left, clang's left to right gave two compilers two models)
      const double high = sig(r.u(-1, 1) * scale);
      const double low = r.p(0.5) ? 0.0 : sig(r.u(-0.5, 0.5) * scale);
      s = random_pulse(r, t_end, low, high);
      break;
    }
    default: s = random_expression(r, t_end, scale); break;
  }
  return s;
}

/// A brake's application r(t) ∈ [0, 1] of every kind that stays there: a step or ramp up (or a ramp
/// down: released), a table applying and releasing, a pulse, a sine about ½, 1 − e^(−t/τ).
Signal random_application(Rng& r, double t_end) {
  Signal s;
  switch (r.i(0, 5)) {
    case 0: s.kind = Signal::Kind::step, s.value = r.p(0.7) ? 1.0 : sig(r.u(0.3, 1.0)), s.t0 = sig(r.u(0.0, 0.6) * t_end); break;
    case 1:
      s.kind = Signal::Kind::ramp, s.t0 = sig(r.u(0.0, 0.4) * t_end), s.t1 = sig(s.t0 + r.u(0.05, 0.4) * t_end);
      s.value = 1.0;
      if (r.p(0.3)) std::swap(s.value, s.before);  // released over the ramp
      break;
    case 2: s = random_table(r, t_end, [](Rng& g) { return g.p(0.3) ? 0.0 : g.p(0.5) ? 1.0 : sig(g.u(0.0, 1.0)); }, false); break;
    case 3: s = random_pulse(r, t_end, 0.0, r.p(0.6) ? 1.0 : sig(r.u(0.3, 1.0))); break;
    case 4:
      s.kind = Signal::Kind::sine, s.offset = 0.55, s.amplitude = sig(r.u(0.1, 0.45)), s.frequency_hz = sig(r.u(0.5, 4.0), 2);
      s.phase = r.p(0.5) ? 0.0 : sig(r.u(0, 3)), s.t0 = r.p(0.6) ? 0.0 : sig(r.u(0.05, 0.5) * t_end);
      break;
    default: s.kind = Signal::Kind::expression, s.offset = 1.0, s.decay = -1.0, s.tau = sig(r.u(0.02, 0.3) * t_end); break;
  }
  return s;
}

/// A normal force of about `fN` N of every kind; with `may_open` it may fall to zero or below (a
/// clutch opening: a sine through zero, a table or pulse to 0, a ramp down), else it stays ≥ fN/5.
Signal random_normal(Rng& r, double t_end, double fN, bool may_open) {
  Signal s;
  const double lo = may_open && r.p(0.5) ? 0.0 : sig(0.2 * fN);
  switch (r.i(0, 6)) {
    case 0: s.kind = Signal::Kind::constant, s.value = fN; break;
    case 1: s.kind = Signal::Kind::step, s.value = fN, s.before = lo, s.t0 = sig(r.u(0.0, 0.5) * t_end); break;
    case 2:
      s.kind = Signal::Kind::ramp, s.value = fN, s.before = lo, s.t0 = sig(r.u(0.0, 0.4) * t_end), s.t1 = sig(s.t0 + r.u(0.05, 0.4) * t_end);
      if (may_open && r.p(0.25)) std::swap(s.value, s.before);
      break;
    case 3:
      s.kind = Signal::Kind::sine, s.amplitude = sig(r.u(0.2, 1.0) * fN), s.frequency_hz = sig(r.u(0.5, 4.0), 2);
      s.offset = may_open ? sig(r.u(-0.3, 1.0) * fN) : sig(s.amplitude + r.u(0.2, 1.0) * fN);
      s.phase = r.p(0.5) ? 0.0 : sig(r.u(0, 3)), s.t0 = r.p(0.6) ? 0.0 : sig(r.u(0.05, 0.5) * t_end);
      break;
    case 4: s = random_table(r, t_end, [&](Rng& g) { return g.p(0.3) ? lo : sig(g.u(0.2, 1.0) * fN); }, false); break;
    case 5: s = random_pulse(r, t_end, lo, fN); break;
    default:
      s.kind = Signal::Kind::expression, s.offset = fN, s.decay = -sig(r.u(0.0, 0.8) * fN), s.tau = sig(r.u(0.02, 0.3) * t_end);
      if (r.p(0.5)) s.amplitude = sig(r.u(0.0, 0.15) * fN), s.frequency_hz = sig(r.u(0.5, 4.0), 2);
      break;
  }
  return s;
}

/// FNV-1a of a family's name (std::hash differs between libraries).
std::uint64_t fnv(const std::string& s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

/// PREFIX + i (appended: GCC 12's -Wrestrict misfires on "b" + std::to_string(i)).
std::string named(const char* prefix, int i) {
  std::string s(prefix);
  s.append(std::to_string(i));
  return s;
}

}  // namespace

RefModel random_model(const std::string& family, std::uint64_t seed, std::uint64_t index) {
  Rng r{seed * 0x2545F4914F6CDD1Dull + index * 0x9E3779B97F4A7C15ull + fnv(family)};
  for (int k = 0; k < 4; ++k) r.next();
  RefModel m;
  const bool mixed = family == "mixed", signals = family == "signals";
  // Every signal kind (tables, pulses, expressions besides constants, steps, ramps and sines; brake
  // applications and normal forces as signals) in the families that were added with them; the
  // first families keep their random streams (and models) as they were.
  const bool every_kind = !(family == "chain" || family == "gap" || family == "one-sided" || family == "ground-friction" ||
                            family == "body-friction" || family == "freewheel" || family == "stop");
  auto has = [&](const char* f) {
    const std::string fs = f;
    return family == fs || (mixed && r.p(0.35)) ||
           (signals && (fs == "ground-friction" || fs == "brake" || fs == "clutch") && r.p(0.4));
  };
  const int n = family == "planetary" ? r.i(3, 6) : r.i(2, 6);
  m.rotational = family == "planetary" || family == "drum" || family == "gear-mesh";
  m.t_end = sig(r.u(0.4, 1.2), 2);
  m.dt_out = m.t_end / 200;
  for (int i = 0; i < n; ++i) m.bodies.push_back({named("b", i), sig(r.log_u(1.0, 20.0)), 0.0, 0.0});
  // A common initial speed (a drive line running) in some models.
  if (r.p(0.25)) {
    const double v = sig(r.u(-0.5, 0.5));
    for (auto& b : m.bodies) b.v0 = v;
  }
  // The chain: b(i−1) — b(i), sometimes one end to the ground.
  const double force = sig(r.log_u(20.0, 300.0));
  for (int i = 1; i < n; ++i) {
    Link L;
    L.name = named("k", i);
    L.a = i - 1, L.b = i;
    L.c = sig(r.log_u(2e3, 1e5));
    const double mm = std::min(m.bodies[static_cast<size_t>(i - 1)].m, m.bodies[static_cast<size_t>(i)].m);
    L.d = r.p(0.35) ? 0.0 : sig(r.u(0.0, 0.15) * 2 * std::sqrt(L.c * mm));
    m.links.push_back(L);
  }
  if (r.p(0.35)) {
    Link L;
    L.name = "k0";
    L.a = r.p(0.5) ? 0 : n - 1, L.b = kGround;
    if (r.p(0.5)) std::swap(L.a, L.b);
    L.c = sig(r.log_u(2e3, 5e4));
    L.d = r.p(0.5) ? 0.0 : sig(r.u(0.0, 0.1) * 2 * std::sqrt(L.c * m.bodies[0].m));
    m.links.push_back(L);
  }
  // Loads.
  const int nl = signals ? r.i(1, 3) : r.i(1, 2);
  for (int k = 0; k < nl; ++k) m.loads.push_back({named("P", k), r.i(0, n - 1), random_signal(r, m.t_end, force, every_kind)});

  // Gaps and one-sided links replace chain links.
  auto pick_link = [&]() -> Link* {
    std::vector<Link*> plain;
    for (auto& L : m.links)
      if (L.kind == Link::Kind::plain) plain.push_back(&L);
    return plain.empty() ? nullptr : plain[static_cast<size_t>(r.i(0, static_cast<int>(plain.size()) - 1))];
  };
  if (has("gap"))
    for (int k = r.i(1, 2); k > 0; --k)
      if (Link* L = pick_link()) {
        L->kind = Link::Kind::gap;
        L->gap = sig(r.log_u(5e-4, 5e-3));
        L->gap_start = sig(r.u(0.2, 0.8) * L->gap);
        L->elasto = L->d > 0 && r.p(0.4);
      }
  if (has("one-sided"))
    for (int k = r.i(1, 2); k > 0; --k)
      if (Link* L = pick_link()) {
        if (r.p(0.5) && L->a != kGround) {
          L->kind = Link::Kind::rope;
          L->flank = sig(r.log_u(5e-4, 5e-3));
        } else {
          L->kind = Link::Kind::one_sided;
          const double side = r.p(0.5) ? 1.0 : -1.0;  // drawn first, in sequence (a product's operands are not)
          L->flank = sig(side * r.log_u(5e-4, 5e-3));
        }
        L->elasto = L->d > 0 && r.p(0.3);
      }

  // Friction elements. Which pairs are used (a freewheel is the only element on its pair; a stop only
  // on a body without friction to another body).
  std::set<std::pair<int, int>> pair_used;
  std::set<int> body_friction_on;
  auto add = [&](Friction f) { m.frictions.push_back(std::move(f)); };
  auto levels = [&](Friction& f) {
    const double Fs = sig(r.log_u(0.2, 2.0) * force);
    if (f.kind == Friction::Kind::contact && r.p(0.4)) {
      f.via_mu = true;
      f.normal = sig(r.log_u(200.0, 3000.0));
      f.mu_s = Fs / f.normal * (1 + 1e-3 * r.u());  // many digits: the last bits of F_s = N μ_s matter
      f.mu_k = f.mu_s * (r.p(0.2) ? 1.0 : r.u(0.5, 1.0));
      if (every_kind && r.p(0.4)) f.fN = random_normal(r, m.t_end, f.normal, false);  // a normal force that varies
    } else {
      f.Fs = Fs;
      f.Fk = r.p(0.2) ? Fs : sig(Fs * r.u(0.5, 1.0));
    }
  };
  int nf = 0;
  auto fname = [&](const char* p) { return named(p, nf++); };
  if (has("ground-friction"))
    for (int k = r.i(1, 3); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = r.i(0, n - 1), f.b = kGround;
      levels(f);
      add(f);
    }
  if (has("body-friction"))
    for (int k = r.i(1, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = r.i(0, n - 1);
      f.b = (f.a + r.i(1, n - 1)) % n;
      levels(f);
      pair_used.insert({std::min(f.a, f.b), std::max(f.a, f.b)});
      body_friction_on.insert(f.a), body_friction_on.insert(f.b);
      add(f);
    }
  if (has("brake"))
    for (int k = r.i(1, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::brake, f.name = fname("B"), f.a = r.i(0, n - 1), f.b = kGround;
      f.Fs = sig(r.log_u(0.3, 3.0) * force);
      f.Fk = r.p(0.3) ? f.Fs : sig(f.Fs * r.u(0.6, 1.0));
      f.time = r.p(0.3) ? 0.0 : sig(r.u(0.05, 0.6) * m.t_end);
      f.ramp = r.p(0.4) ? 0.0 : sig(r.u(0.02, 0.3) * m.t_end);
      if (every_kind && r.p(0.5)) f.with_application = true, f.application = random_application(r, m.t_end);
      add(f);
    }
  if (has("clutch"))
    for (int k = r.i(1, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::clutch, f.name = fname("K"), f.a = r.i(0, n - 1);
      f.b = (f.a + r.i(1, n - 1)) % n;
      const double fN = sig(r.log_u(200.0, 3000.0));
      f.mu_s = sig(r.log_u(0.2, 2.0) * force / fN);
      f.mu_k = r.p(0.2) ? f.mu_s : sig(f.mu_s * r.u(0.5, 1.0));
      if (!every_kind || r.p(0.5)) {  // the step or ramp that closes it
        f.fN.value = fN;
        if (r.p(0.5)) f.fN.kind = Signal::Kind::step, f.fN.t0 = sig(r.u(0.0, 0.5) * m.t_end);
        else f.fN.kind = Signal::Kind::ramp, f.fN.t0 = sig(r.u(0.0, 0.4) * m.t_end), f.fN.t1 = sig(f.fN.t0 + r.u(0.05, 0.4) * m.t_end);
        if (f.fN.kind == Signal::Kind::step && f.fN.t0 == 0.0) f.fN.kind = Signal::Kind::constant;
      } else {
        f.fN = random_normal(r, m.t_end, fN, true);
      }
      pair_used.insert({std::min(f.a, f.b), std::max(f.a, f.b)});
      body_friction_on.insert(f.a), body_friction_on.insert(f.b);
      // A clutch closing on a running pair: give one side a speed.
      if (r.p(0.4)) m.bodies[static_cast<size_t>(f.a)].v0 += sig(r.u(-1, 1));
      add(f);
    }
  if (has("freewheel"))
    for (int k = r.i(1, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::freewheel, f.name = fname("F");
      if (r.p(0.4)) {
        f.a = kGround, f.b = r.i(0, n - 1);  // a backstop: b may move forward only
      } else {
        f.a = r.i(0, n - 1), f.b = (f.a + r.i(1, n - 1)) % n;
        if (pair_used.count({std::min(f.a, f.b), std::max(f.a, f.b)}) != 0) continue;
        pair_used.insert({std::min(f.a, f.b), std::max(f.a, f.b)});
        body_friction_on.insert(f.a), body_friction_on.insert(f.b);
      }
      f.drag = r.p(0.5) ? 0.0 : sig(r.log_u(0.01, 0.2) * force);
      add(f);
    }
  if (has("stop"))
    for (int k = r.i(1, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::stop, f.name = fname("S"), f.a = r.i(0, n - 1), f.b = kGround;
      if (body_friction_on.count(f.a) != 0) continue;
      f.stop_max = r.p(0.5);
      const double off = sig(r.log_u(5e-4, 1e-2));
      f.stop_pos = f.stop_max ? off : -off;
      f.e = r.p(0.4) ? 0.0 : sig(r.u(0.1, 0.8), 2);
      add(f);
    }
  // The initial speeds must not turn a freewheel in its locked direction (u = v_a − v_b > 0), nor
  // move a body into a stop it starts on (none starts on its stop here).
  for (const auto& f : m.frictions)
    if (f.kind == Friction::Kind::freewheel) {
      const double va = f.a >= 0 ? m.bodies[static_cast<size_t>(f.a)].v0 : 0.0;
      const double vb = f.b >= 0 ? m.bodies[static_cast<size_t>(f.b)].v0 : 0.0;
      if (va > vb) {
        for (auto& b : m.bodies) b.v0 = 0.0;
        break;
      }
    }
  // Ideal gears: 1–2 bodies slaved to chain bodies (q_master = i q_slave), with loads and links
  // from the slave (its first end) back into the chain or to the ground; friction on the masters.
  // The family `drum`: the same with a rotational chain and translational slaves (a rope drum and its
  // hook: q_drum = i x, i = 1/R in rad/m), links from the hook to the ground only.
  const bool drum = family == "drum";
  if (family == "gear" || drum) {
    for (int k = r.i(1, 2); k > 0; --k) {
      const int master = r.i(0, n - 1), slave = static_cast<int>(m.bodies.size());
      const double i = drum ? sig(1.0 / r.u(0.1, 0.5)) : sig((r.p(0.3) ? -1 : 1) * r.log_u(0.3, 3.0));
      m.bodies.push_back({named("g", slave - n), drum ? sig(r.log_u(10.0, 500.0)) : sig(r.log_u(0.5, 10.0)), 0.0, 0.0});
      m.bodies.back().linear = drum;
      m.gears.push_back({named("G", slave - n), master, slave, i});
      if (r.p(0.6)) m.loads.push_back({named("Pg", slave - n), slave, random_signal(r, m.t_end, drum ? sig(force * i) : force, true)});
      if (r.p(0.6)) {
        Link L;
        L.name = named("kg", slave - n);
        L.a = slave, L.b = drum || r.p(0.3) ? kGround : r.i(0, n - 1);
        L.c = drum ? sig(r.log_u(1e4, 1e6)) : sig(r.log_u(2e3, 5e4));
        L.d = r.p(0.5) ? 0.0 : sig(r.u(0.0, 0.1) * 2 * std::sqrt(L.c * m.bodies[static_cast<size_t>(slave)].m));
        if (L.b == master) L.b = kGround;  // a link inside the rigid group is an input error
        m.links.push_back(L);
      }
    }
    if (r.p(0.5)) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = m.gears[0].a, f.b = kGround;
      if (drum) f.Fs = sig(r.log_u(0.2, 2.0) * force), f.Fk = sig(f.Fs * r.u(0.5, 1.0));  // levels: no radius needed
      else levels(f);
      add(f);
    }
    if (r.p(0.3)) {
      Friction f;
      f.kind = Friction::Kind::brake, f.name = fname("B"), f.a = m.gears.back().a, f.b = kGround;
      f.Fs = sig(r.log_u(0.3, 3.0) * force), f.Fk = sig(f.Fs * r.u(0.6, 1.0)), f.time = sig(r.u(0.05, 0.6) * m.t_end);
      add(f);
    }
  }
  // A planetary gear among three chain members (rotational bodies: inertias, torques), with a contact
  // and a brake to the ground on two of them (at most two: three would lock the gear redundantly).
  if (family == "planetary") {
    std::vector<int> idx(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) idx[static_cast<size_t>(k)] = k;
    for (int k = 0; k < 3; ++k) std::swap(idx[static_cast<size_t>(k)], idx[static_cast<size_t>(r.i(k, n - 1))]);
    Gear g;
    g.name = "PG", g.planetary = true, g.a = idx[0], g.b = idx[1], g.c = idx[2], g.ratio = sig(r.u(1.5, 5.0));
    m.gears.push_back(g);
    if (r.p(0.5)) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = idx[static_cast<size_t>(r.i(0, 2))], f.b = kGround;
      f.Fs = sig(r.log_u(0.2, 2.0) * force), f.Fk = r.p(0.2) ? f.Fs : sig(f.Fs * r.u(0.5, 1.0));
      add(f);
    }
    if (r.p(0.4)) {
      Friction f;
      f.kind = Friction::Kind::brake, f.name = fname("B"), f.a = idx[static_cast<size_t>(r.i(0, 2))], f.b = kGround;
      f.Fs = sig(r.log_u(0.3, 3.0) * force), f.Fk = sig(f.Fs * r.u(0.6, 1.0));
      f.time = sig(r.u(0.05, 0.6) * m.t_end), f.ramp = r.p(0.5) ? 0.0 : sig(r.u(0.02, 0.3) * m.t_end);
      if (r.p(0.4)) f.with_application = true, f.application = random_application(r, m.t_end);
      add(f);
    }
  }
  // Elastic gear meshes: 1–2 links of the rotational chain become meshes (ratio 0.3–3, stiffness,
  // damping up to 0.15 of critical over the mesh's J_eff = 1/(1/J_a + i²/J_b), backlash 0 or
  // 0.5–5 mrad, efficiency 1 or 0.85–0.99), with a contact and a brake to the ground on chain bodies.
  if (family == "gear-mesh") {
    for (int k = r.i(1, 2); k > 0; --k) {
      std::vector<size_t> between;
      for (size_t j = 0; j < m.links.size(); ++j)
        if (m.links[j].kind == Link::Kind::plain && m.links[j].a >= 0 && m.links[j].b >= 0) between.push_back(j);
      if (between.empty()) break;
      const size_t j = between[static_cast<size_t>(r.i(0, static_cast<int>(between.size()) - 1))];
      Mesh G;
      G.name = named("M", k), G.a = m.links[j].a, G.b = m.links[j].b;
      m.links.erase(m.links.begin() + static_cast<long>(j));
      G.i = sig(r.log_u(0.3, 3.0));
      const double Jeff = 1.0 / (1.0 / m.bodies[static_cast<size_t>(G.a)].m + G.i * G.i / m.bodies[static_cast<size_t>(G.b)].m);
      G.c = sig(r.log_u(2e3, 1e5));
      G.d = r.p(0.35) ? 0.0 : sig(r.u(0.0, 0.15) * 2 * std::sqrt(G.c * Jeff));
      G.backlash = r.p(0.35) ? 0.0 : sig(r.log_u(5e-4, 5e-3));
      G.eta = r.p(0.3) ? 1.0 : sig(r.u(0.85, 0.99), 2);
      m.meshes.push_back(G);
    }
    if (r.p(0.4)) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = r.i(0, n - 1), f.b = kGround;
      f.Fs = sig(r.log_u(0.2, 2.0) * force), f.Fk = r.p(0.2) ? f.Fs : sig(f.Fs * r.u(0.5, 1.0));
      add(f);
    }
    if (r.p(0.3)) {
      Friction f;
      f.kind = Friction::Kind::brake, f.name = fname("B"), f.a = r.i(0, n - 1), f.b = kGround;
      f.Fs = sig(r.log_u(0.3, 3.0) * force), f.Fk = sig(f.Fs * r.u(0.6, 1.0));
      f.time = sig(r.u(0.05, 0.6) * m.t_end), f.ramp = r.p(0.5) ? 0.0 : sig(r.u(0.02, 0.3) * m.t_end);
      add(f);
    }
  }
  // A prescribed motion (speed or acceleration of every kind that keeps the speed continuous) on one
  // chain body, with friction contacts from it to free neighbours (a stuck one makes the neighbour
  // follow the motion).
  if (family == "motion") {
    const int p = r.i(0, n - 1);
    Body& b = m.bodies[static_cast<size_t>(p)];
    const double vs = sig(r.u(0.1, 1.0));
    if (r.p(0.6)) {
      b.motion = Body::Motion::speed;
      switch (r.i(0, 3)) {  // a speed without jumps: a ramp, a sine from its zero, a table, an expression
        case 0:
          b.prescribed.kind = Signal::Kind::ramp, b.prescribed.value = sig(r.u(-1, 1) * vs), b.prescribed.before = r.p(0.5) ? 0.0 : sig(r.u(-1, 1) * vs);
          b.prescribed.t0 = sig(r.u(0.0, 0.4) * m.t_end), b.prescribed.t1 = sig(b.prescribed.t0 + r.u(0.05, 0.5) * m.t_end);
          break;
        case 1:
          b.prescribed.kind = Signal::Kind::sine, b.prescribed.amplitude = vs, b.prescribed.frequency_hz = sig(r.u(0.5, 5.0), 2);
          b.prescribed.offset = r.p(0.5) ? 0.0 : sig(r.u(-0.5, 0.5) * vs), b.prescribed.t0 = r.p(0.5) ? 0.0 : sig(r.u(0.05, 0.5) * m.t_end);
          break;
        case 2: {
          b.prescribed = random_table(r, m.t_end, [&](Rng& g) { return sig(g.u(-1, 1) * vs); }, r.p(0.3));
          auto& pts = b.prescribed.points;  // no jumps in a speed
          pts.erase(std::unique(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.first == y.first; }), pts.end());
          break;
        }
        default: b.prescribed = random_expression(r, m.t_end, vs); break;
      }
    } else {
      b.motion = Body::Motion::acceleration;
      b.prescribed = random_signal(r, m.t_end, sig(r.u(1.0, 10.0)), true);
    }
    for (int k = r.i(0, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = p, f.b = (p + r.i(1, n - 1)) % n;
      levels(f);
      add(f);
    }
  }
  // Releases: 1–2 chain bodies lose 20–80 % of their mass at an instant of the run, with contacts to
  // the ground and between bodies (a stuck one is decided again with the new mass).
  if (family == "release") {
    for (int k = r.i(1, 2); k > 0; --k) {
      const int b = r.i(0, n - 1);
      double left = m.bodies[static_cast<size_t>(b)].m;
      for (const auto& x : m.releases)
        if (x.body == b) left -= x.dm;
      m.releases.push_back({named("R", static_cast<int>(m.releases.size())), b, sig(r.u(0.2, 0.6) * left), sig(r.u(0.05, 0.8) * m.t_end)});
    }
    for (int k = r.i(0, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = m.releases[0].body, f.b = r.p(0.6) ? kGround : (f.a + r.i(1, n - 1)) % n;
      levels(f);
      add(f);
    }
  }
  // Kinetic levels over the sliding speed: 1–3 contacts (to the ground and between bodies) with a
  // table from speed 0 (F_k(0) ≤ F_s, rising or falling) or the Stribeck law.
  if (family == "kinetic") {
    for (int k = r.i(1, 3); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = r.i(0, n - 1), f.b = r.p(0.6) ? kGround : (f.a + r.i(1, n - 1)) % n;
      f.Fs = sig(r.log_u(0.2, 2.0) * force);
      f.Fk = sig(f.Fs * r.u(0.3, 0.9));
      if (r.p(0.5)) {
        double sp = 0.0;
        f.kinetic_table.emplace_back(0.0, r.p(0.3) ? f.Fs : sig(f.Fs * r.u(0.5, 1.0)));
        for (int j = r.i(1, 3); j > 0; --j) sp = sig(sp + r.log_u(0.01, 0.3)), f.kinetic_table.emplace_back(sp, sig(f.Fs * r.u(0.3, 1.2)));
      } else {
        f.stribeck_speed = sig(r.log_u(0.01, 0.3));
        f.stribeck_exponent = r.p(0.5) ? 1.0 : sig(r.u(1.0, 2.5), 2);
      }
      add(f);
    }
  }
  // Linear buffers against the ground (one-sided springs with damping) on 1–2 chain bodies, placed
  // a little off the start so the loads drive the bodies onto them.
  if (family == "buffer") {
    for (int k = r.i(1, 2); k > 0; --k) {
      Link L;
      L.kind = Link::Kind::one_sided, L.buffer = true, L.name = named("U", k);
      const int b = r.i(0, n - 1);
      const double xb = sig(r.log_u(5e-4, 1e-2));
      if (r.p(0.5)) L.a = b, L.b = kGround, L.flank = xb;     // max: x_b above
      else L.a = kGround, L.b = b, L.flank = -(-xb);          // min at −x_b: δ = −x ≥ x_b
      L.c = sig(r.log_u(1e4, 2e5));
      L.d = r.p(0.4) ? 0.0 : sig(r.u(0.0, 0.3) * 2 * std::sqrt(L.c * m.bodies[static_cast<size_t>(b)].m));
      m.links.push_back(L);
    }
  }
  // A DC motor (a linear motor on a translational body) driving the chain, its voltage a signal of
  // every kind; with contacts to the ground.
  if (family == "dc-motor") {
    DcMotor M;
    M.name = "motor", M.body = r.i(0, n - 1);
    M.R = sig(r.log_u(0.5, 5.0)), M.L = sig(r.log_u(5e-3, 5e-2)), M.k = sig(r.log_u(5.0, 50.0));
    M.i0 = r.p(0.3) ? sig(r.u(-1, 1) * force / M.k) : 0.0;
    M.u = random_signal(r, m.t_end, sig(force * M.R / M.k), true);  // stall force k u/R about the force scale
    m.motors.push_back(M);
    for (int k = r.i(0, 2); k > 0; --k) {
      Friction f;
      f.kind = Friction::Kind::contact, f.name = fname("f"), f.a = r.i(0, n - 1), f.b = kGround;
      levels(f);
      add(f);
    }
  }
  // The swinging load (issue 31): a point-mass load L on a spatial rope from a chain body (the
  // trolley, x) — in space also from another (the bridge, y) — at a fixed height; in some models the
  // rope wound on a drum (a rotational body of J = (3–30) m s², its torque about the holding torque
  // m g R/n, a constant or a ramp). The load hangs swinging (its rope taut, or slack by up to 1 % of
  // its length: it falls first), or rests on a ground stop (plastic or with restitution) with its
  // rope slack or carrying part of its weight, lifted off by the drum or pulled off obliquely as the
  // trolley moves.
  if (family == "sway") {
    constexpr double g = 9.80665;
    SwayRope R;
    R.name = "rope", R.load = "L";
    const bool space = r.p(0.4);
    R.trolley = r.i(0, n - 1);
    if (space) {
      R.bridge = r.i(0, n - 2);
      if (R.bridge >= R.trolley) ++R.bridge;
    }
    const double ml = sig(r.log_u(0.5, 10.0));
    R.L0 = sig(r.u(0.8, 2.5));
    R.falls = r.i(1, 2);
    R.EA = sig(r.log_u(2e3, 5e4) * R.L0 / R.falls);
    const double c = R.falls * R.EA / R.L0;
    R.d = r.p(0.4) ? 0.0 : sig(r.u(0.0, 0.1) * 2 * std::sqrt(c * ml));
    const bool lift = r.p(0.4), with_drum = r.p(0.5);
    const double sx = sig(r.u(-0.3, 0.3)), sy = space ? sig(r.u(-0.3, 0.3)) : 0.0;
    double x0 = 0, y0 = 0, z0 = 0;
    if (lift) {  // on the stop at z = 0, e = ℓ₀ − L0 from −0.03 to 0.3 of the static stretch m g/c
      x0 = sig(0.5 * sx * R.L0), y0 = sig(0.5 * sy * R.L0);
      const double l0 = R.L0 + r.u(-0.03, 0.3) * ml * g / c;
      R.h = sig(std::sqrt(l0 * l0 - x0 * x0 - y0 * y0), 6);
    } else {  // hanging at sin θ = (sx, sy) from (0, 0, h), h = L0 + m g/c, ρ within 1 % of the static length
      R.h = sig(R.L0 + ml * g / c, 6);
      const double rho = (R.L0 + ml * g / c) * (1.0 + r.u(-0.01, 0.002));
      x0 = sig(rho * sx, 6), y0 = sig(rho * sy, 6), z0 = sig(R.h - rho * std::sqrt(1.0 - sx * sx - sy * sy), 6);
    }
    auto coordinate = [&](const char* axis, double q0, double v0) {
      m.bodies.push_back({std::string("L.") + axis, ml, q0, v0});
      m.bodies.back().load_coordinate = true;
      return static_cast<int>(m.bodies.size()) - 1;
    };
    const bool moving = !lift && r.p(0.5);
    R.x = coordinate("x", x0, moving ? sig(r.u(-0.3, 0.3)) : 0.0);
    if (space) R.y = coordinate("y", y0, moving ? sig(r.u(-0.3, 0.3)) : 0.0);
    R.z = coordinate("z", z0, 0.0);
    if (lift) {
      Friction f;
      f.kind = Friction::Kind::stop, f.name = "ground", f.a = R.z, f.b = kGround;
      f.stop_pos = 0.0, f.e = r.p(0.5) ? 0.0 : sig(r.u(0.1, 0.5));
      add(f);
    }
    if (with_drum) {
      R.R = sig(r.u(0.05, 0.2));
      const double s = R.R / R.falls, M0 = ml * g * s;
      R.drum = static_cast<int>(m.bodies.size());
      m.bodies.push_back({"drum", sig(ml * s * s * r.log_u(3.0, 30.0)), 0.0, 0.0});
      m.bodies.back().angular = true;
      Signal hoist;
      if (r.p(0.5)) {
        hoist.kind = Signal::Kind::constant, hoist.value = sig(M0 * r.u(0.9, 1.25));
      } else {
        hoist.kind = Signal::Kind::ramp, hoist.before = sig(M0 * r.u(0.9, 1.0)), hoist.value = sig(M0 * r.u(0.9, 1.25));
        hoist.t0 = sig(r.u(0.0, 0.3) * m.t_end), hoist.t1 = sig(hoist.t0 + r.u(0.1, 0.5) * m.t_end);
      }
      m.loads.push_back({"hoist", R.drum, hoist});
    }
    // A rigid load (type: rigid-load, planar) in some planar models, from a stream of its own so
    // that every other model of the family keeps its numbers: the point-mass load above becomes a
    // body of inertia J = m (0.05–2) m² with its angle ψ, hung either by one rope at a point
    // a = (a_h, a_z) of its own (a_z 0.05–0.5 m above the centre; a_h within ±0.3 m: a compound
    // pendulum, turning when a is off the vertical) where the point mass was, or as a spreader on
    // two ropes at a = (±a_h, a_z) from suspension points ±d along x (d within 10 % of a_h: a
    // parallelogram or nearly), each carrying half the weight, both on the drum if there is one.
    Rng rr{seed * 0x2545F4914F6CDD1Dull + index * 0x9E3779B97F4A7C15ull + fnv("sway: the rigid load")};
    for (int k = 0; k < 4; ++k) rr.next();
    if (!space && rr.p(0.4)) {
      const bool spreader = rr.p(0.5);
      const double J = sig(ml * rr.log_u(0.05, 2.0));
      const double az = sig(rr.u(0.05, 0.5)), ah = spreader ? sig(rr.u(0.3, 1.5)) : sig(rr.u(-0.3, 0.3));
      const double psi0 = rr.p(0.5) ? 0.0 : sig(rr.u(-0.05, 0.05)), w0 = moving && rr.p(0.5) ? sig(rr.u(-0.2, 0.2)) : 0.0;
      Body& X = m.bodies[static_cast<size_t>(R.x)];
      Body& Z = m.bodies[static_cast<size_t>(R.z)];
      R.attach[0] = ah, R.attach[1] = az;
      const double ra_h = ah * std::cos(psi0) - az * std::sin(psi0), ra_z = ah * std::sin(psi0) + az * std::cos(psi0);
      if (!spreader) {  // the rope's point where the point mass was: the centre c = r − R(ψ0) a
        X.q0 = sig(X.q0 - ra_h, 6);
        if (lift) R.h = sig(R.h + ra_z, 6);  // the centre on the stop at z = 0
        else Z.q0 = sig(Z.q0 - ra_z, 6);
      } else {  // each rope carries m g/2: its static stretch m g/(2c)
        const double off = sig(ah * rr.u(0.9, 1.1)), half = ml * g / (2.0 * c);
        if (lift) {  // the centre on the stop, the ropes from −0.03 to 0.3 of the static stretch long
          const double l0 = R.L0 + rr.u(-0.03, 0.3) * half;
          X.q0 = sig(0.5 * sx * R.L0);
          R.h = sig(std::sqrt(l0 * l0 - X.q0 * X.q0) + az, 6);
        } else {  // hanging at sin θ = sx, within 1 % of the static length
          const double rho = (R.L0 + half) * (1.0 + rr.u(-0.01, 0.002));
          R.h = sig(R.L0 + half + az, 6);
          X.q0 = sig(rho * sx, 6), Z.q0 = sig(R.h - az - rho * std::sqrt(1.0 - sx * sx), 6);
        }
        R.offset = off;
      }
      R.psi = static_cast<int>(m.bodies.size());
      m.bodies.push_back({"L.psi", J, psi0, w0});
      m.bodies.back().load_coordinate = true, m.bodies.back().angular = true;
      if (spreader) {
        SwayRope R2 = R;
        R2.name = "rope2", R2.attach[0] = -ah, R2.offset = -R.offset;
        m.sway.push_back(R);
        m.sway.push_back(R2);
      } else {
        m.sway.push_back(R);
      }
    } else {
      m.sway.push_back(R);
    }
  }
  // The family `gear`: a two-stage lossy gearbox (LossyTrain) in half the models, on three bodies of
  // its own driven from a chain body through a spring, with loads on its ends; drawn from a stream of
  // its own, so the family's other elements are as they were.
  if (family == "gear") {
    Rng q{seed * 0x2545F4914F6CDD1Dull + index * 0x9E3779B97F4A7C15ull + fnv("gear-train")};
    if (q.p(0.5)) {
      LossyTrain T;
      T.name1 = "LG1", T.name2 = "LG2";
      T.a = static_cast<int>(m.bodies.size()), T.m = T.a + 1, T.c = T.a + 2;
      T.i1 = sig(q.log_u(0.4, 3.0)), T.i2 = sig(q.log_u(0.4, 3.0));
      T.e1 = sig(q.u(0.5, 1.0)), T.e2 = sig(q.u(0.5, 1.0));
      T.r1 = q.p(0.2) ? 0.0 : sig(q.u(0.3, 1.0)), T.r2 = q.p(0.3) ? 0.0 : sig(q.u(0.3, 1.0));
      const double v = q.p(0.3) ? sig(q.u(-0.5, 0.5)) : 0.0;
      m.bodies.push_back({"t0", sig(q.log_u(0.5, 10.0)), 0.0, v});
      m.bodies.push_back({"t1", sig(q.log_u(0.2, 5.0)), 0.0, v / T.i1});
      m.bodies.push_back({"t2", sig(q.log_u(1.0, 20.0)), 0.0, v / (T.i1 * T.i2)});
      Link L;
      L.name = "kt";
      L.a = q.i(0, n - 1), L.b = T.a;
      L.c = sig(q.log_u(2e3, 5e4));
      L.d = q.p(0.5) ? 0.0 : sig(q.u(0.0, 0.1) * 2 * std::sqrt(L.c * m.bodies[static_cast<size_t>(T.a)].m));
      m.links.push_back(L);
      if (q.p(0.6)) m.loads.push_back({"Pt0", T.a, random_signal(q, m.t_end, force, true)});
      m.loads.push_back({"Pt2", T.c, random_signal(q, m.t_end, sig(force * T.i1 * T.i2), true)});
      m.trains.push_back(T);
    }
  }
  for (const auto& g : m.gears)
    if (!g.planetary) m.bodies[static_cast<size_t>(g.b)].v0 = m.bodies[static_cast<size_t>(g.a)].v0 / g.ratio;
  return m;
}

namespace {
std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
std::string end_name(const RefModel& m, int i) { return i < 0 ? "ground" : m.bodies[static_cast<size_t>(i)].name; }

/// A contact's kinetic level: a number, a table over the sliding speed (plain SI numbers), or the
/// Coulomb level with the Stribeck law's speed and exponent.
std::string kinetic_yaml(const Friction& f, const std::string& F) {
  if (!f.kinetic_table.empty()) {
    std::string y = "[";
    for (size_t k = 0; k < f.kinetic_table.size(); ++k)
      y += (k ? ", [" : "[") + num(f.kinetic_table[k].first) + ", " + num(f.kinetic_table[k].second) + "]";
    return y + "]";
  }
  if (f.stribeck_speed > 0.0) return num(f.Fk) + F + ", stribeck_speed: " + num(f.stribeck_speed) + " m/s, stribeck_exponent: " + num(f.stribeck_exponent);
  return num(f.Fk) + F;
}

/// The units of a model's bodies: translational (m, N) or rotational (rad, N·m).
struct Units {
  const char *q, *v, *F, *c, *d;
};
Units units_of(const RefModel& m) {
  return m.rotational ? Units{"rad", "rad/s", "N*m", "N*m/rad", "N*m*s/rad"} : Units{"m", "m/s", "N", "N/m", "N*s/m"};
}

std::string signal_yaml(const Signal& s, const char* unit) {
  const std::string u = *unit != 0 ? std::string(" ") + unit : std::string();
  switch (s.kind) {
    case Signal::Kind::constant: return "type: constant, value: " + num(s.value) + u;
    case Signal::Kind::step:
      return "type: step, value: " + num(s.value) + u + ", before: " + num(s.before) + u + ", time: " + num(s.t0) + " s";
    case Signal::Kind::ramp:
      return "type: ramp, value: " + num(s.value) + u + ", before: " + num(s.before) + u + ", start: " + num(s.t0) +
             " s, end: " + num(s.t1) + " s";
    case Signal::Kind::sine:
      return "type: sine, amplitude: " + num(s.amplitude) + u + ", frequency: " + num(s.frequency_hz) +
             " Hz, phase: " + num(s.phase) + ", offset: " + num(s.offset) + u + ", start: " + num(s.t0) + " s";
    case Signal::Kind::table: {
      std::string y = "type: table, points: [";  // plain numbers: SI
      for (size_t k = 0; k < s.points.size(); ++k) y += (k ? ", [" : "[") + num(s.points[k].first) + ", " + num(s.points[k].second) + "]";
      return y + "], outside: " + (s.extrapolate ? "extrapolate" : "hold");
    }
    case Signal::Kind::pulse:
      return "type: pulse, high: " + num(s.value) + u + ", low: " + num(s.before) + u + ", period: " + num(s.period) + " s, width: " +
             num(s.width) + " s, start: " + num(s.t0) + " s" + (s.count >= 0 ? ", count: " + std::to_string(s.count) : std::string());
    case Signal::Kind::expression: {
      // c0 + c1 t + A sin(2 pi f t + phase) + B exp(-t/tau), in SI (the expression language's text).
      std::string e = num(s.offset);
      if (s.slope != 0.0) e += " + " + num(s.slope) + "*t";
      if (s.amplitude != 0.0) e += " + " + num(s.amplitude) + "*sin(2*pi*" + num(s.frequency_hz) + "*t + " + num(s.phase) + ")";
      if (s.decay != 0.0) e += " + " + num(s.decay) + "*exp(-t/" + num(s.tau) + ")";
      return "type: expression, expression: '" + e + "'";
    }
  }
  return "";
}
}  // namespace

std::string to_yaml(const RefModel& m, const std::string& integrator, const std::string& header) {
  std::string y = header;
  const Units U = units_of(m);
  const std::string q = std::string(" ") + U.q, F = std::string(" ") + U.F;
  auto lin = [&](int i) { return i >= 0 && m.bodies[static_cast<size_t>(i)].linear; };  // a hook in a rotational model
  y += "name: random reference model\nbodies:\n";
  std::set<std::string> loads_written;
  for (const auto& b : m.bodies) {
    if (b.load_coordinate) {  // a point-mass load: its coordinates LOAD.x, LOAD.y, LOAD.z as one body
      const std::string load = b.name.substr(0, b.name.rfind('.'));
      if (!loads_written.insert(load).second) continue;
      std::string axes, pos, vel;
      const Body* psi = nullptr;  // a rigid load's angle LOAD.psi
      for (const auto& c : m.bodies)
        if (c.load_coordinate && c.name.rfind(load + ".", 0) == 0) {
          if (c.angular) {
            psi = &c;
            continue;
          }
          if (!axes.empty()) axes += ", ", pos += ", ", vel += ", ";
          axes.append(c.name, load.size() + 1), pos += num(c.q0), pos += " m", vel += num(c.v0), vel += " m/s";
        }
      if (psi)
        y += "  " + load + ": {type: rigid-load, mass: " + num(b.m) + " kg, inertia: " + num(psi->m) + " kg*m^2, axes: [" + axes +
             "], position: [" + pos + "], velocity: [" + vel + "], angle: " + num(psi->q0) + " rad, angular_velocity: " +
             num(psi->v0) + " rad/s}\n";
      else
        y += "  " + load + ": {type: point-mass, mass: " + num(b.m) + " kg, axes: [" + axes + "], position: [" + pos +
             "], velocity: [" + vel + "]}\n";
      continue;
    }
    if (b.angular) {  // a rotational body in a translational model (a spatial rope's drum)
      y += "  " + b.name + ": {type: rotational, inertia: " + num(b.m) + " kg*m^2, position: " + num(b.q0) +
           " rad, velocity: " + num(b.v0) + " rad/s}\n";
      continue;
    }
    y += "  " + b.name + (m.rotational && !b.linear ? ": {type: rotational, inertia: " + num(b.m) + " kg*m^2"
                                                    : ": {type: translational, mass: " + num(b.m) + " kg") +
         ", position: " + num(b.q0) + (b.linear ? std::string(" m") : q) +
         (b.motion == Body::Motion::speed ? std::string() : ", velocity: " + num(b.v0) + " " + (b.linear ? "m/s" : U.v)) +
         (b.motion == Body::Motion::free ? std::string()
          : b.motion == Body::Motion::speed ? std::string(", motion: {speed: {") + signal_yaml(b.prescribed, m.rotational ? "rad/s" : "m/s") + "}}"
                                            : std::string(", motion: {acceleration: {") + signal_yaml(b.prescribed, m.rotational ? "rad/s^2" : "m/s^2") + "}}") +
         "}\n";
  }
  bool first_link = true;
  if (!m.links.empty()) y += "links:\n", first_link = false;
  for (const auto& g : m.gears) {
    if (first_link) y += "links:\n", first_link = false;
    if (g.planetary)
      y += "  " + g.name + ": {type: planetary-gear, sun: " + end_name(m, g.a) + ", ring: " + end_name(m, g.b) + ", carrier: " +
           end_name(m, g.c) + ", ratio: " + num(g.ratio) + "}\n";
    else
      y += "  " + g.name + ": {type: ideal-gear, between: [" + end_name(m, g.a) + ", " + end_name(m, g.b) + "], ratio: " + num(g.ratio) +
           (m.bodies[static_cast<size_t>(g.b)].linear ? " rad/m" : "") + "}\n";
  }
  for (const auto& T : m.trains) {  // two lossy gears on one body (a two-stage gearbox)
    if (first_link) y += "links:\n", first_link = false;
    y += "  " + T.name1 + ": {type: lossy-gear, between: [" + end_name(m, T.a) + ", " + end_name(m, T.m) + "], ratio: " +
         num(T.i1) + ", efficiency: " + num(T.e1) + ", efficiency_reverse: " + num(T.r1) + "}\n";
    y += "  " + T.name2 + ": {type: lossy-gear, between: [" + end_name(m, T.m) + ", " + end_name(m, T.c) + "], ratio: " +
         num(T.i2) + ", efficiency: " + num(T.e2) + ", efficiency_reverse: " + num(T.r2) + "}\n";
  }
  for (const auto& L : m.links) {
    if (L.buffer) continue;  // under buffers:
    const bool rope = L.kind == Link::Kind::rope;
    y += "  " + L.name + ": {type: " + (rope ? "rope" : L.d > 0 || L.kind != Link::Kind::plain ? "spring-damper" : "spring") +
         ", between: [" + end_name(m, L.a) + ", " + end_name(m, L.b) + "], stiffness: " + num(L.c) + " " + (lin(L.a) ? "N/m" : U.c);
    if (L.d > 0 || (L.kind != Link::Kind::plain && !rope)) y += ", damping: " + num(L.d) + " " + (lin(L.a) ? "N*s/m" : U.d);
    if (L.kind == Link::Kind::gap) y += ", gap: " + num(L.gap) + q + ", gap_start: " + num(L.gap_start) + q;
    if (L.kind == Link::Kind::one_sided) y += ", flank: " + num(L.flank) + q;
    if (rope) y += ", slack: " + num(L.flank) + q;
    if (L.elasto) y += ", flank_law: elasto-backlash";
    y += "}\n";
  }
  for (const auto& R : m.sway) {
    if (first_link) y += "links:\n", first_link = false;
    y += "  " + R.name + ": {type: spatial-rope, load: " + R.load + (R.trolley >= 0 ? ", trolley: " + end_name(m, R.trolley) : "") +
         (R.bridge >= 0 ? ", bridge: " + end_name(m, R.bridge) : "") +
         (R.drum >= 0 ? ", drum: " + end_name(m, R.drum) + ", drum_radius: " + num(R.R) + " m" : "") + ", falls: " + num(R.falls) +
         ", length: " + num(R.L0) + " m, EA: " + num(R.EA) + " N, damping: " + num(R.d) + " N*s/m, height: " + num(R.h) + " m" +
         (R.psi >= 0 ? ", attach: [" + num(R.attach[0]) + " m, " + num(R.attach[1]) + " m]" : std::string()) +
         (R.offset != 0.0 ? ", offset: " + num(R.offset) + " m" : std::string()) + "}\n";
  }
  for (const auto& G : m.meshes) {
    if (first_link) y += "links:\n", first_link = false;
    y += "  " + G.name + ": {type: gear-mesh, between: [" + end_name(m, G.a) + ", " + end_name(m, G.b) + "], ratio: " + num(G.i) +
         ", stiffness: " + num(G.c) + " N*m/rad, damping: " + num(G.d) + " N*m*s/rad, backlash: " + num(G.backlash) +
         " rad, efficiency: " + num(G.eta) + "}\n";
  }
  if (!m.loads.empty()) y += "loads:\n";
  for (const auto& l : m.loads)
    y += "  " + l.name + ": {body: " + m.bodies[static_cast<size_t>(l.body)].name + ", " +
         signal_yaml(l.s, lin(l.body) ? "N" : m.bodies[static_cast<size_t>(l.body)].angular ? "N*m" : U.F) + "}\n";
  auto section = [&](Friction::Kind k, const char* title) {
    bool first = true;
    for (const auto& f : m.frictions) {
      if (f.kind != k) continue;
      if (first) y += std::string(title) + ":\n", first = false;
      y += "  " + f.name + ": {";
      switch (k) {
        case Friction::Kind::contact:
          y += "between: [" + end_name(m, f.a) + ", " + end_name(m, f.b) + "], ";
          y += !f.via_mu ? "static: " + num(f.Fs) + F + ", kinetic: " + kinetic_yaml(f, F)
               : "normal_force: " + (f.fN.kind == Signal::Kind::constant && f.fN.value == 0.0
                                         ? num(f.normal) + " N"
                                         : "{" + signal_yaml(f.fN, "N") + "}") +
                     ", mu_s: " + num(f.mu_s) + ", mu_k: " + num(f.mu_k);
          break;
        case Friction::Kind::brake:
          y += "body: " + end_name(m, f.a) + ", holding: " + num(f.Fs) + F + ", braking: " + num(f.Fk) + F + ", " +
               (f.with_application ? "application: {" + signal_yaml(f.application, "") + "}"
                                   : "time: " + num(f.time) + " s, ramp: " + num(f.ramp) + " s");
          break;
        case Friction::Kind::clutch:
          y += "between: [" + end_name(m, f.a) + ", " + end_name(m, f.b) + "], normal_force: {" + signal_yaml(f.fN, "N") +
               "}, mu_s: " + num(f.mu_s) + ", mu_k: " + num(f.mu_k);
          break;
        case Friction::Kind::freewheel:
          y += "between: [" + end_name(m, f.a) + ", " + end_name(m, f.b) + "], drag: " + num(f.drag) + F;
          break;
        case Friction::Kind::stop:
          y += "body: " + end_name(m, f.a) + (f.stop_max ? ", max: " : ", min: ") + num(f.stop_pos) + q + ", restitution: " + num(f.e);
          break;
      }
      y += "}\n";
    }
  };
  section(Friction::Kind::contact, "contacts");
  section(Friction::Kind::brake, "brakes");
  section(Friction::Kind::clutch, "clutches");
  section(Friction::Kind::freewheel, "freewheels");
  section(Friction::Kind::stop, "stops");
  bool first_buffer = true;
  for (const auto& L : m.links) {
    if (!L.buffer) continue;
    if (first_buffer) y += "buffers:\n", first_buffer = false;
    const bool upper = L.b == kGround;  // [body, ground]: max at δ₊; [ground, body]: min at −δ₊
    y += "  " + L.name + ": {body: " + end_name(m, upper ? L.a : L.b) + (upper ? ", max: " + num(L.flank) : ", min: " + num(-L.flank)) + q +
         ", stiffness: " + num(L.c) + " " + U.c + (L.d > 0 ? ", damping: " + num(L.d) + " " + U.d : std::string()) + "}\n";
  }
  if (!m.motors.empty()) y += "drives:\n";
  for (const auto& M : m.motors)
    y += "  " + M.name + ": {type: dc-motor, body: " + end_name(m, M.body) + ", resistance: " + num(M.R) + " ohm, inductance: " + num(M.L) +
         " H, motor_constant: " + num(M.k) + " N/A, initial_current: " + num(M.i0) + " A, voltage: {" + signal_yaml(M.u, "V") + "}}\n";
  if (!m.releases.empty()) y += "releases:\n";
  for (const auto& x : m.releases)
    y += "  " + x.name + ": {body: " + end_name(m, x.body) + (m.rotational ? ", inertia: " + num(x.dm) + " kg*m^2" : ", mass: " + num(x.dm) + " kg") +
         ", time: " + num(x.t) + " s}\n";
  y += "simulation: {t_end: " + num(m.t_end) + " s, dt_out: " + num(m.dt_out) + " s, rtol: 1e-10, atol: 1e-12, max_steps: 500000, integrator: " +
       integrator + "}\n";
  return y;
}

}  // namespace machdyn::reference
