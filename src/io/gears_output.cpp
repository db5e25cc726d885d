#include "machdyn/io/gears_output.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>
#include "common/constants.hpp"

namespace machdyn::io {

namespace {

using gears::Vec2;

const char* law_name(const gears::RatioLaw& l) {
  switch (l.kind()) {
    case gears::RatioLaw::Kind::Walking: return "walking";
    case gears::RatioLaw::Kind::Travel: return "travel";
    case gears::RatioLaw::Kind::Expression: return "expression";
    case gears::RatioLaw::Kind::Table: return "table";
  }
  return "";
}

/// SVG polyline from points in mm, y up (SVG y down).
std::string svg_poly(const std::vector<Vec2>& pts, double dx, const char* style, bool closed = false) {
  std::string s = fmt::format("<{} fill=\"none\" {} points=\"", closed ? "polygon" : "polyline", style);
  for (const Vec2& p : pts) s += fmt::format("{:.4f},{:.4f} ", p.x * 1e3 + dx, -p.y * 1e3);
  return s + "\"/>\n";
}

std::vector<Vec2> zip(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<Vec2> v;
  for (std::size_t k = 0; k < x.size(); ++k) v.push_back({x[k], y[k]});
  return v;
}

/// Radial lines at the sector boundaries of both gears, body frames (m).
void sector_rays(const GearReport& r, std::vector<std::pair<Vec2, Vec2>>& wheel, std::vector<std::pair<Vec2, Vec2>>& pinion) {
  const auto& m = r.model;
  const double T = m.T(), Theta = m.Theta();
  const int Np = static_cast<int>(std::lround(2 * kPi / Theta));
  for (int q = 0; q < m.N; ++q)
    for (const auto& row : r.synthesis.sectors) {
      const double b = -row.phi + q * T, R = row.rH * 1.08;
      wheel.push_back({{0, 0}, {R * std::cos(b), R * std::sin(b)}});
    }
  for (int q = 0; q < Np; ++q)
    for (const auto& row : r.synthesis.sectors) {
      const double b = kPi + row.theta + q * Theta, R = row.r * 1.15;
      pinion.push_back({{0, 0}, {R * std::cos(b), R * std::sin(b)}});
    }
}

}  // namespace

std::string gears_text(const GearReport& r) {
  const auto& m = r.model;
  const auto& s = r.synthesis;
  std::string o;
  o += fmt::format("non-circular gears: law {}, u = {:.5f}", law_name(m.law), m.law.u());
  if (m.law.kind() == gears::RatioLaw::Kind::Walking) o += fmt::format(", k = {:.6g}", m.law.k());
  o += fmt::format("\nL = {:.6g} mm (installed {:.6g} mm), z = {}, zH = {}, {} big sectors of {} teeth\n\n",
                   m.L * 1e3, m.L_installed * 1e3, m.z, m.zH, m.N, m.n);
  o += "   i    phi,rad  phi,deg  dphi,rad dphi,deg    rH,mm  theta,rad theta,deg dtheta,rad dtheta,deg     r,mm\n";
  for (const auto& row : s.sectors)
    o += fmt::format("{:4d} {:10.4f} {:8.2f} {:9.4f} {:8.2f} {:8.2f} {:10.4f} {:9.2f} {:10.4f} {:10.2f} {:8.2f}\n", row.i,
                     row.phi, row.phi / kDeg, row.dphi, row.dphi / kDeg, row.rH * 1e3, row.theta, row.theta / kDeg,
                     row.dtheta, row.dtheta / kDeg, row.r * 1e3);
  o += fmt::format("\narc per sector l = r_Hj dphi_j = r_j dtheta_j = {:.6f} mm (eq. 52, max deviation {:.1e}), "
                   "module m = l/pi = {:.5f} mm\n", s.arc * 1e3, s.eq52_deviation, s.module * 1e3);
  o += fmt::format("successive approximations: wheel {} cycles (defect {:.1e} rad), pinion {} cycles (defect {:.1e} "
                   "rad); closure theta(T/2) - theta(-T/2) - Theta = {:.1e} rad\n",
                   s.wheel_cycles, s.wheel_defect, s.pinion_cycles, s.pinion_defect, s.closure);
  o += fmt::format("teeth: {} basis, rack module {:.5f} mm, pressure angle {:.4g} deg, ", 
                   m.profile.basis == gears::ProfileBasis::Stepwise ? "stepwise" : "continuous",
                   r.teeth.rack.module * 1e3, r.teeth.rack.alpha / kDeg);
  if (r.teeth.undercut.empty()) o += "no undercut\n";
  else o += fmt::format("UNDERCUT on {} flanks (first: {} tooth {})\n", r.teeth.undercut.size(),
                        r.teeth.undercut[0].gear, r.teeth.undercut[0].tooth);
  if (r.speed.available)
    o += fmt::format("travel speed at pinion speed {:.6g} rad/s: mean {:.6g}/s; fluctuation (max-min)/mean: "
                     "continuous ratio {:.2e}, stepwise ratio {:.4f}, circular gears {:.4f}\n",
                     r.speed.omega, r.speed.mean, r.speed.continuous_delta, r.speed.stepwise_delta,
                     r.speed.circular_delta);
  return o;
}

std::string gears_json(const GearReport& r) {
  const auto& m = r.model;
  const auto& s = r.synthesis;
  nlohmann::ordered_json j;
  j["law"] = law_name(m.law);
  j["u"] = m.law.u();
  if (m.law.kind() == gears::RatioLaw::Kind::Walking) j["k"] = m.law.k();
  j["L_mm"] = m.L * 1e3;
  j["L_installed_mm"] = m.L_installed * 1e3;
  j["z"] = m.z;
  j["zH"] = m.zH;
  j["big_sectors"] = m.N;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const auto& row : s.sectors)
    rows.push_back({{"i", row.i}, {"phi", row.phi}, {"dphi", row.dphi}, {"rH", row.rH * 1e3}, {"theta", row.theta},
                    {"dtheta", row.dtheta}, {"r", row.r * 1e3}});
  j["sectors"] = rows;
  j["arc_mm"] = s.arc * 1e3;
  j["module_mm"] = s.module * 1e3;
  j["checks"] = {{"eq52_max_relative_deviation", s.eq52_deviation},
                 {"wheel_cycles", s.wheel_cycles},
                 {"wheel_defect_rad", s.wheel_defect},
                 {"pinion_cycles", s.pinion_cycles},
                 {"pinion_defect_rad", s.pinion_defect},
                 {"closure_rad", s.closure}};
  nlohmann::ordered_json uc = nlohmann::ordered_json::array();
  for (const auto& u : r.teeth.undercut)
    uc.push_back({{"gear", u.gear}, {"tooth", u.tooth}, {"side", u.side}, {"margin_mm", u.margin * 1e3}});
  j["teeth"] = {{"basis", m.profile.basis == gears::ProfileBasis::Stepwise ? "stepwise" : "continuous"},
                {"module_mm", r.teeth.rack.module * 1e3},
                {"pressure_angle_deg", r.teeth.rack.alpha / kDeg},
                {"undercut", uc}};
  if (r.speed.available)
    j["travel_speed"] = {{"pinion_speed", r.speed.omega},        {"mean", r.speed.mean},
                         {"continuous_delta", r.speed.continuous_delta}, {"stepwise_delta", r.speed.stepwise_delta},
                         {"stepwise_min", r.speed.stepwise_min}, {"stepwise_max", r.speed.stepwise_max},
                         {"circular_delta", r.speed.circular_delta}};
  return j.dump(2) + "\n";
}

std::string gears_csv(const GearReport& r) {
  std::string o = "i,phi_rad,phi_deg,dphi_rad,dphi_deg,rH_mm,theta_rad,theta_deg,dtheta_rad,dtheta_deg,r_mm\n";
  for (const auto& row : r.synthesis.sectors)
    o += fmt::format("{},{:.9f},{:.7f},{:.9f},{:.7f},{:.7f},{:.9f},{:.7f},{:.9f},{:.7f},{:.7f}\n", row.i, row.phi,
                     row.phi / kDeg, row.dphi, row.dphi / kDeg, row.rH * 1e3, row.theta, row.theta / kDeg, row.dtheta,
                     row.dtheta / kDeg, row.r * 1e3);
  return o;
}

std::string gears_pitch_svg(const GearReport& r) {
  const auto& m = r.model;
  const auto c = gears::sample_pitch_curves(m, 360);
  const double dx = m.L_installed * 1e3;
  double rw = 0, rp = 0;
  for (std::size_t k = 0; k < c.wheel_x.size(); ++k) rw = std::max(rw, std::hypot(c.wheel_x[k], c.wheel_y[k]));
  for (std::size_t k = 0; k < c.pinion_x.size(); ++k) rp = std::max(rp, std::hypot(c.pinion_x[k], c.pinion_y[k]));
  const double x0 = -rw * 1.2e3, x1 = dx + rp * 1.25e3, h = std::max(rw, rp) * 1.25e3;
  std::string o = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.2f} {:.2f} {:.2f} {:.2f}\" width=\"900\">\n"
      "<title>Pitch curves with sector boundaries (paper 003, Fig. 1), mm</title>\n",
      x0, -h, x1 - x0, 2 * h);
  std::vector<std::pair<Vec2, Vec2>> rw_rays, rp_rays;
  sector_rays(r, rw_rays, rp_rays);
  for (auto& [a, b] : rw_rays)
    o += fmt::format("<line x1=\"0\" y1=\"0\" x2=\"{:.3f}\" y2=\"{:.3f}\" stroke=\"#bbb\" stroke-width=\"0.2\"/>\n",
                     b.x * 1e3, -b.y * 1e3);
  for (auto& [a, b] : rp_rays)
    o += fmt::format("<line x1=\"{:.3f}\" y1=\"0\" x2=\"{:.3f}\" y2=\"{:.3f}\" stroke=\"#bbb\" stroke-width=\"0.2\"/>\n",
                     dx, dx + b.x * 1e3, -b.y * 1e3);
  o += svg_poly(zip(c.wheel_x, c.wheel_y), 0.0, "stroke=\"#1f4e9c\" stroke-width=\"0.6\"");
  o += svg_poly(zip(c.pinion_x, c.pinion_y), dx, "stroke=\"#b22222\" stroke-width=\"0.6\"");
  o += svg_poly(r.teeth.wheel.pitch, 0.0, "stroke=\"#1f4e9c\" stroke-width=\"0.25\" stroke-dasharray=\"1,1\"");
  o += svg_poly(r.teeth.pinion.pitch, dx, "stroke=\"#b22222\" stroke-width=\"0.25\" stroke-dasharray=\"1,1\"");
  o += fmt::format("<circle cx=\"0\" cy=\"0\" r=\"1\"/><circle cx=\"{:.3f}\" cy=\"0\" r=\"1\"/>\n", dx);
  o += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"6\">wheel (H): r_H(phi); pinion: r(theta); "
                   "L = {:.5g} mm; dashed: {} pitch arcs</text>\n</svg>\n",
                   x0 + 2, h - 4, m.L_installed * 1e3,
                   m.profile.basis == gears::ProfileBasis::Stepwise ? "stepwise" : "continuous");
  return o;
}

std::string gears_ratio_svg(const GearReport& r) {
  const auto& m = r.model;
  const double T = m.T();
  const double W = 600, H = 300, pad = 50;
  double imin = 1e300, imax = -1e300;
  std::vector<std::pair<double, double>> law, step;
  for (int q = 0; q <= 600; ++q) {
    const double phi = -0.5 * T + T * q / 600.0, i = m.law.ratio(phi).v;
    law.push_back({phi, i});
    imin = std::min(imin, i), imax = std::max(imax, i);
  }
  for (const auto& row : r.synthesis.sectors) {
    const double i = row.dtheta / row.dphi;
    step.push_back({row.phi, i});
    step.push_back({row.phi - row.dphi, i});
    imin = std::min(imin, i), imax = std::max(imax, i);
  }
  const double span = std::max(imax - imin, 1e-9);
  imin -= 0.05 * span, imax += 0.05 * span;
  auto X = [&](double phi) { return pad + (phi + 0.5 * T) / T * (W - 2 * pad); };
  auto Y = [&](double i) { return H - pad - (i - imin) / (imax - imin) * (H - 2 * pad); };
  std::string o = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" width=\"{}\">\n"
                              "<title>Theoretical and stepwise gear ratio (paper 003, Fig. 2)</title>\n", W, H, 1.5 * W);
  o += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n", pad, pad,
                   W - 2 * pad, H - 2 * pad);
  auto poly = [&](const std::vector<std::pair<double, double>>& v, const char* style) {
    std::string p = fmt::format("<polyline fill=\"none\" {} points=\"", style);
    for (auto& [x, y] : v) p += fmt::format("{:.2f},{:.2f} ", X(x), Y(y));
    return p + "\"/>\n";
  };
  o += poly(law, "stroke=\"#1f4e9c\" stroke-width=\"1.5\"");
  o += poly(step, "stroke=\"#b22222\" stroke-width=\"1\"");
  for (int q = 0; q <= 4; ++q) {
    const double phi = -0.5 * T + T * q / 4, i = imin + (imax - imin) * q / 4;
    o += fmt::format("<text x=\"{:.1f}\" y=\"{}\" font-size=\"10\" text-anchor=\"middle\">{:.1f}</text>\n", X(phi),
                     H - pad + 14, phi / kDeg);
    o += fmt::format("<text x=\"{}\" y=\"{:.1f}\" font-size=\"10\" text-anchor=\"end\">{:.3f}</text>\n", pad - 4, Y(i) + 3, i);
  }
  o += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\" text-anchor=\"middle\">phi, deg</text>\n", W / 2, H - 12);
  o += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\">i = dtheta/dphi: law (blue), stepwise "
                   "dtheta_j/dphi_j (red)</text>\n</svg>\n", pad, pad - 10);
  return o;
}

std::string gears_teeth_svg(const GearReport& r) {
  const double dx = r.model.L_installed * 1e3;
  double rw = 0, rp = 0;
  for (const Vec2& p : r.teeth.wheel.outline) rw = std::max(rw, std::hypot(p.x, p.y));
  for (const Vec2& p : r.teeth.pinion.outline) rp = std::max(rp, std::hypot(p.x, p.y));
  const double x0 = -rw * 1.05e3, x1 = dx + rp * 1.05e3, h = std::max(rw, rp) * 1.05e3;
  std::string o = fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{:.2f} {:.2f} {:.2f} {:.2f}\" "
                              "width=\"1000\">\n<title>Tooth outlines (rack-cutter envelope), mm</title>\n",
                              x0, -h, x1 - x0, 2 * h);
  o += svg_poly(r.teeth.wheel.outline, 0.0, "stroke=\"#1f4e9c\" stroke-width=\"0.15\"", true);
  o += svg_poly(r.teeth.pinion.outline, dx, "stroke=\"#b22222\" stroke-width=\"0.15\"", true);
  o += svg_poly(r.teeth.wheel.pitch, 0.0, "stroke=\"#888\" stroke-width=\"0.08\" stroke-dasharray=\"0.5,0.5\"");
  o += svg_poly(r.teeth.pinion.pitch, dx, "stroke=\"#888\" stroke-width=\"0.08\" stroke-dasharray=\"0.5,0.5\"");
  return o + "</svg>\n";
}

std::string gears_dxf(const GearReport& r) {
  std::string body;
  auto line = [&](const char* layer, Vec2 a, Vec2 b, double dx) {
    body += fmt::format("0\nLINE\n8\n{}\n10\n{:.6f}\n20\n{:.6f}\n30\n0.0\n11\n{:.6f}\n21\n{:.6f}\n31\n0.0\n", layer,
                        a.x * 1e3 + dx, a.y * 1e3, b.x * 1e3 + dx, b.y * 1e3);
  };
  auto poly = [&](const char* layer, const std::vector<Vec2>& pts, double dx, bool closed) {
    for (std::size_t k = 1; k < pts.size(); ++k) line(layer, pts[k - 1], pts[k], dx);
    if (closed && pts.size() > 2) line(layer, pts.back(), pts.front(), dx);
  };
  const double dx = r.model.L_installed * 1e3;
  const auto c = gears::sample_pitch_curves(r.model, 720);
  poly("PITCH_WHEEL", zip(c.wheel_x, c.wheel_y), 0.0, false);
  poly("PITCH_PINION", zip(c.pinion_x, c.pinion_y), dx, false);
  poly("SECTOR_ARCS_WHEEL", r.teeth.wheel.pitch, 0.0, false);
  poly("SECTOR_ARCS_PINION", r.teeth.pinion.pitch, dx, false);
  std::vector<std::pair<Vec2, Vec2>> rw, rp;
  sector_rays(r, rw, rp);
  for (auto& [a, b] : rw) line("SECTORS_WHEEL", a, b, 0.0);
  for (auto& [a, b] : rp) line("SECTORS_PINION", a, b, dx);
  poly("TEETH_WHEEL", r.teeth.wheel.outline, 0.0, true);
  poly("TEETH_PINION", r.teeth.pinion.outline, dx, true);
  return "999\nmachdyn gears: non-circular gear pair, mm, wheel centre at the origin, pinion centre at (L_installed, 0)\n"
         "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n" +
         body + "0\nENDSEC\n0\nEOF\n";
}

}  // namespace machdyn::io
