#include "machdyn/gears/tooth_profile.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include "common/constants.hpp"

namespace machdyn::gears {

namespace {


double wrap_s(double s, double perimeter) { return s - perimeter * std::floor(s / perimeter); }

/// A pitch curve made of circular arcs about the origin (the stepwise gear): arc k starts at arc
/// length s0[k], at polar angle beta0[k], with radius R[k]; all arcs have the length l.
struct ArcChain {
  std::vector<double> s0, beta0, R;
  double l = 0.0, perimeter = 0.0;
  [[nodiscard]] std::size_t arc_of(double s) const {
    const double w = wrap_s(s, perimeter);
    return std::min(static_cast<std::size_t>(w / l), R.size() - 1);
  }
  /// The circle of arc k, extended beyond its ends (s measured on the gear's global scale).
  [[nodiscard]] Frame on_arc(std::size_t k, double s) const { return circle_frame(R[k], beta0[k], s - s0[k]); }
  [[nodiscard]] Frame at(double s) const {
    const std::size_t k = arc_of(s);
    const double w = wrap_s(s, perimeter);
    return on_arc(k, w);
  }
};

/// Polar pitch curve ρ(β) with derivatives, for the continuous basis.
struct Polar {
  double r, r1, r2;
};

Frame polar_frame(double beta, const Polar& p) {
  const double c = std::cos(beta), s = std::sin(beta);
  Frame f;
  f.P = {p.r * c, p.r * s};
  const Vec2 d{p.r1 * c - p.r * s, p.r1 * s + p.r * c};
  const double n = std::hypot(d.x, d.y);
  f.T = {d.x / n, d.y / n};
  f.N = {-f.T.y, f.T.x};
  const double K = p.r * p.r + 2.0 * p.r1 * p.r1 - p.r * p.r2;
  f.rho = std::pow(p.r * p.r + p.r1 * p.r1, 1.5) / K;
  return f;
}

/// Dense table β(s) of a closed polar curve, s from 0 at beta_start, counter-clockwise.
struct PolarTrack {
  std::function<Polar(double)> polar;
  std::vector<double> beta, s;
  double perimeter = 0.0;
  [[nodiscard]] Frame at(double sq) const {
    const double w = wrap_s(sq, perimeter);
    std::size_t k = static_cast<std::size_t>(std::upper_bound(s.begin(), s.end(), w) - s.begin());
    k = std::clamp<std::size_t>(k, 1, s.size() - 1);
    const double t = (w - s[k - 1]) / (s[k] - s[k - 1]);
    const double b = beta[k - 1] + t * (beta[k] - beta[k - 1]);
    return polar_frame(b, polar(b));
  }
};

PolarTrack make_polar_track(std::function<Polar(double)> polar, double beta_start, int samples) {
  PolarTrack tr;
  tr.polar = std::move(polar);
  auto speed = [&](double b) {
    const Polar p = tr.polar(b);
    return std::sqrt(p.r * p.r + p.r1 * p.r1);
  };
  const double h = 2.0 * kPi / samples;
  double acc = 0.0;
  double prev = speed(beta_start);
  for (int q = 0; q <= samples; ++q) {
    const double b = beta_start + h * q;
    if (q > 0) {  // Simpson on [b − h, b]
      const double mid = speed(b - 0.5 * h), end = speed(b);
      acc += h / 6.0 * (prev + 4.0 * mid + end);
      prev = end;
    }
    tr.beta.push_back(b);
    tr.s.push_back(acc);
  }
  tr.perimeter = acc;
  return tr;
}

}  // namespace

Frame circle_frame(double R, double beta0, double s) {
  const double b = beta0 + s / R, c = std::cos(b), sn = std::sin(b);
  return Frame{{R * c, R * sn}, {-sn, c}, {-c, -sn}, R};
}

std::vector<Vec2> rack_flank(const Track& track, double x_f, int sigma, const RackCutter& rack, double y_from,
                             double y_to, int points) {
  std::vector<Vec2> out;
  const double sc = std::sin(rack.alpha) * std::cos(rack.alpha), c2 = std::cos(rack.alpha) * std::cos(rack.alpha);
  for (int q = 0; q < points; ++q) {
    const double y = y_from + (y_to - y_from) * q / (points - 1);
    const double s = x_f - sigma * y / sc;       // where the flank point of depth y is generated
    const double x = s - (s - x_f) * c2;         // the contact point on the rack flank
    const Frame f = track(s);
    out.push_back({f.P.x + (x - s) * f.T.x - y * f.N.x, f.P.y + (x - s) * f.T.y - y * f.N.y});
  }
  return out;
}

double undercut_margin(const Track& track, double x_f, int sigma, const RackCutter& rack) {
  const double sa = std::sin(rack.alpha), depth = rack.ha * rack.module;
  const double s_tip = x_f + sigma * depth / (sa * std::cos(rack.alpha));
  double margin = 1e300;
  for (int q = 0; q <= 8; ++q) {
    const double s = x_f + (s_tip - x_f) * q / 8.0;
    margin = std::min(margin, track(s).rho * sa * sa - depth);
  }
  return margin;
}

namespace {

/// The rack depth y at which the generated flank reaches the tip curve (the pitch curve offset
/// outward by h_a m): the flank point at depth y lies off the normal at its generating point, so it
/// reaches the tip curve before y = h_a m. Height above the pitch curve is measured on the
/// osculating circle at the flank's pitch point (exact on the circular arcs of the stepwise basis).
double tip_depth(const Track& track, double x_f, int sigma, const RackCutter& rack) {
  const double ha = rack.ha * rack.module;
  const Frame f = track(x_f);
  const Vec2 C{f.P.x + f.rho * f.N.x, f.P.y + f.rho * f.N.y};
  auto height = [&](double y) {
    const Vec2 q = rack_flank(track, x_f, sigma, rack, y, y, 2)[0];
    return std::hypot(q.x - C.x, q.y - C.y) - f.rho;
  };
  double lo = 0.0, hi = ha;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (height(mid) < ha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Builds one gear's outline: teeth centred at s_c = (t + offset)·p, t = 0..teeth−1.
/// `flank_track(x_f)` gives the track a flank with pitch point x_f rolls on; `root_at(s)` the pitch
/// curve frame under a root point.
GearTeeth build_gear(const std::string& name, int teeth, double p, double offset, const RackCutter& rack, int points,
                     const std::function<Track(double)>& flank_track, const std::function<Frame(double)>& root_at,
                     std::vector<UndercutSpot>& undercut) {
  GearTeeth g;
  g.teeth = teeth;
  const double m = rack.module, ha = rack.ha * m, hf = rack.hf * m, ta = std::tan(rack.alpha);
  for (int t = 0; t < teeth; ++t) {
    const double sc = (t + offset) * p, xl = sc - 0.25 * p, xr = sc + 0.25 * p;
    const Track tl = flank_track(xl), trr = flank_track(xr);
    const auto left = rack_flank(tl, xl, -1, rack, -ha, tip_depth(tl, xl, -1, rack), points);
    const auto right = rack_flank(trr, xr, +1, rack, tip_depth(trr, xr, +1, rack), -ha, points);
    g.outline.insert(g.outline.end(), left.begin(), left.end());
    g.outline.insert(g.outline.end(), right.begin(), right.end());
    if (double mg = undercut_margin(tl, xl, -1, rack); mg < 0.0) undercut.push_back({name, t, -1, mg});
    if (double mg = undercut_margin(trr, xr, +1, rack); mg < 0.0) undercut.push_back({name, t, +1, mg});
    // root across the space to the next tooth, on the dedendum offset of the pitch curve
    const double a = xr + hf * ta, b = xl + p - hf * ta;
    for (int q = 0; q <= 4; ++q) {
      const double s = a + (b - a) * q / 4.0;
      const Frame f = root_at(s);
      g.outline.push_back({f.P.x + hf * f.N.x, f.P.y + hf * f.N.y});
    }
  }
  return g;
}

}  // namespace

ToothProfiles generate_profiles(const GearModel& m, const GearSynthesis& syn) {
  ToothProfiles out;
  const double T = m.T(), Theta = m.Theta(), L = m.L;
  const int n = m.n;
  const int Np = static_cast<int>(std::lround(2.0 * kPi / Theta));  // big sectors of the pinion
  RackCutter rack{0.0, m.profile.pressure_angle, m.profile.addendum, m.profile.dedendum};
  const int pts = m.profile.points;

  if (m.profile.basis == ProfileBasis::Stepwise) {
    ArcChain wheel, pinion;
    wheel.l = pinion.l = syn.arc;
    for (int q = 0; q < m.N; ++q)
      for (int j = 0; j < n; ++j) {
        const Sector& row = syn.sectors[static_cast<std::size_t>(j)];
        wheel.s0.push_back((q * n + j) * syn.arc);
        wheel.beta0.push_back(-0.5 * T + q * T + (0.5 * T - row.phi));  // β = −φ, CCW from −T/2
        wheel.R.push_back(row.rH);
      }
    for (int q = 0; q < Np; ++q)
      for (int j = n - 1; j >= 0; --j) {
        const Sector& row = syn.sectors[static_cast<std::size_t>(j)];
        pinion.s0.push_back((q * n + (n - 1 - j)) * syn.arc);
        pinion.beta0.push_back(kPi + q * Theta + (row.theta - row.dtheta));  // β = π + θ
        pinion.R.push_back(row.r);
      }
    wheel.perimeter = static_cast<double>(wheel.R.size()) * syn.arc;
    pinion.perimeter = static_cast<double>(pinion.R.size()) * syn.arc;
    out.pitch = syn.arc;
    rack.module = syn.arc / kPi;
    out.rack = rack;
    auto chain_tracks = [](const ArcChain& c) {
      return std::function<Track(double)>([&c](double x_f) {
        const std::size_t k = c.arc_of(x_f);
        const double shift = x_f - wrap_s(x_f, c.perimeter);
        return Track([&c, k, shift](double s) { return c.on_arc(k, s - shift); });
      });
    };
    out.wheel = build_gear("wheel", m.zH, out.pitch, 0.5, rack, pts, chain_tracks(wheel),
                           [&](double s) { return wheel.at(s); }, out.undercut);
    out.pinion = build_gear("pinion", m.z, out.pitch, 0.0, rack, pts, chain_tracks(pinion),
                            [&](double s) { return pinion.at(s); }, out.undercut);
    for (const ArcChain* c : {&wheel, &pinion}) {
      auto& pitch = c == &wheel ? out.wheel.pitch : out.pinion.pitch;
      for (std::size_t k = 0; k < c->R.size(); ++k)
        for (int q = 0; q <= 6; ++q) pitch.push_back(c->on_arc(k, c->s0[k] + c->l * q / 6.0).P);
    }
    return out;
  }

  // ---- continuous basis: the rack rolls on the law's pitch curves
  // A corner at the big-sector boundary (i' jumps) is a concave notch on one gear and a point on the
  // other; neither can be generated by a rack.
  const Jet end = m.law.ratio(0.5 * T), start = m.law.ratio(-0.5 * T);
  if (std::abs(end.d - start.d) > 1e-6 * std::max(1.0, std::abs(end.d)))
    throw InputError(m.where.basis, fmt::format(
        "gears.profile: basis 'continuous' needs pitch curves without corners, but di/dφ jumps from {:.6g} to "
        "{:.6g} at the big-sector boundary φ = ±{:.6g} deg (a {} notch on the wheel, a {} on the pinion); a rack "
        "cannot generate a corner: use basis 'stepwise' (the paper's circular-arc teeth) or a law with a smooth "
        "period boundary", end.d, start.d, 0.5 * T / kDeg, end.d < start.d ? "concave" : "convex",
        end.d < start.d ? "point" : "concave notch"));
  auto wheel_polar = [&](double beta) {
    const Jet i = m.law.ratio(-beta);
    const double g1 = 1.0 / ((1.0 + i.v) * (1.0 + i.v)), g2 = -2.0 / std::pow(1.0 + i.v, 3);
    return Polar{L * i.v / (1.0 + i.v), -L * g1 * i.d, L * (g2 * i.d * i.d + g1 * i.dd)};
  };
  auto pinion_polar = [&](double beta) {
    const double phi = m.law.phi_of_theta(beta - kPi);
    const Jet i = m.law.ratio(phi);
    const double h1 = -1.0 / ((1.0 + i.v) * (1.0 + i.v)), h2 = 2.0 / std::pow(1.0 + i.v, 3);
    const double rp = L * h1 * i.d, rpp = L * (h2 * i.d * i.d + h1 * i.dd);
    return Polar{L / (1.0 + i.v), rp / i.v, rpp / (i.v * i.v) - rp * i.d / (i.v * i.v * i.v)};
  };
  const int samples = 1024 * std::max(m.N, Np);
  PolarTrack wt = make_polar_track(wheel_polar, -0.5 * T, samples);
  PolarTrack pt = make_polar_track(pinion_polar, kPi + m.law.theta(-0.5 * T), samples);
  for (const PolarTrack* tr : {&wt, &pt})
    for (double b : tr->beta) {
      const Polar p = tr->polar(b);
      if (p.r * p.r + 2.0 * p.r1 * p.r1 - p.r * p.r2 <= 0.0) {
        const bool w = tr == &wt;
        throw InputError(m.where.basis, fmt::format(
            "gears.profile: basis 'continuous' needs convex pitch curves, but the {} pitch curve is concave at "
            "{} = {:.4g} deg; a rack cannot generate it: use basis 'stepwise' or a law with a smaller range",
            w ? "wheel" : "pinion", w ? "φ" : "θ", (w ? -b : b - kPi) / kDeg));
      }
    }
  out.pitch = wt.perimeter / m.zH;
  rack.module = out.pitch / kPi;
  out.rack = rack;
  auto wt_at = [&](double s) { return wt.at(s); };
  auto pt_at = [&](double s) { return pt.at(s); };
  out.wheel = build_gear("wheel", m.zH, out.pitch, 0.5, rack, pts, [&](double) { return Track(wt_at); }, wt_at,
                         out.undercut);
  out.pinion = build_gear("pinion", m.z, out.pitch, 0.0, rack, pts, [&](double) { return Track(pt_at); }, pt_at,
                          out.undercut);
  for (double b : wt.beta) out.wheel.pitch.push_back(polar_frame(b, wt.polar(b)).P);
  for (double b : pt.beta) out.pinion.pitch.push_back(polar_frame(b, pt.polar(b)).P);
  return out;
}

}  // namespace machdyn::gears
