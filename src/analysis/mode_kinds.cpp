// What a natural mode of a model with a swinging load is (analysis/mode_kinds.hpp, docs/sway.md).
#include "machdyn/analysis/mode_kinds.hpp"

#include <cmath>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/elements/spatial_rope.hpp"

namespace machdyn {

namespace mode_kinds_detail {

/// Per body: the part of its kinetic energy that is sway (the rest of a load's is stretch; −1: a
/// body of the drive line). A load's x, y: 1; its z: 0; a rigid load's ψ: the horizontal share of
/// its rope points' motion per unit rotation, Σ (∂w_h/∂ψ)² / Σ |∂w/∂ψ|² over its ropes (at the
/// initial positions).
std::vector<double> sway_part(const Model& m) {
  std::vector<double> part(m.bodies.size(), -1.0), h2(m.bodies.size(), 0.0), all2(m.bodies.size(), 0.0);
  for (const Drive& d : m.drives) {
    const auto* rope = dynamic_cast<const SpatialRope*>(d.law.get());
    if (!rope) continue;
    ElementMotion b;
    b.n = d.ports();
    auto body_of = [&](int p) { return p == 0 ? d.body : d.others[static_cast<size_t>(p - 1)]; };
    for (int p = 0; p < b.n; ++p) b.q[p] = m.bodies[static_cast<size_t>(body_of(p))].q0;
    const SpatialRope::Geometry g = rope->geometry(b);
    for (int p = 0; p < b.n; ++p) {
      const auto i = static_cast<size_t>(body_of(p));
      switch (rope->role[p]) {
        case SpatialRope::Role::load_x:
        case SpatialRope::Role::load_y: part[i] = 1.0; break;
        case SpatialRope::Role::load_z: part[i] = 0.0; break;
        case SpatialRope::Role::load_psi: {
          const double* w = g.dw[p];
          h2[i] += w[0] * w[0] + w[1] * w[1], all2[i] += w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
          part[i] = 0.0;
          break;
        }
        default: break;
      }
    }
  }
  for (size_t i = 0; i < part.size(); ++i)
    if (all2[i] > 0.0) part[i] = h2[i] / all2[i];
  return part;
}

}  // namespace mode_kinds_detail

const char* to_string(ModeKind k) {
  switch (k) {
    case ModeKind::pendulum: return "pendulum";
    case ModeKind::rope_stretch: return "rope stretch";
    case ModeKind::drive_line: break;
  }
  return "drive line";
}

bool has_swinging_load(const Model& m) {
  for (const Drive& d : m.drives)
    if (dynamic_cast<const SpatialRope*>(d.law.get())) return true;
  return false;
}

std::vector<ModeShares> mode_shares(const Model& m, const Eigen::VectorXd& mass, const Eigen::MatrixXd& shapes) {
  const std::vector<double> part = mode_kinds_detail::sway_part(m);
  std::vector<ModeShares> out;
  for (Eigen::Index k = 0; k < shapes.cols(); ++k) {
    double sway = 0.0, stretch = 0.0, drive = 0.0;
    for (Eigen::Index i = 0; i < shapes.rows() && i < mass.size(); ++i) {
      const double T = mass(i) * shapes(i, k) * shapes(i, k);
      const double p = static_cast<size_t>(i) < part.size() ? part[static_cast<size_t>(i)] : -1.0;
      if (p < 0.0) drive += T;
      else sway += p * T, stretch += (1.0 - p) * T;
    }
    const double total = sway + stretch + drive;  // 1 for a mass-normalized shape
    ModeShares s;
    if (total > 0.0) s.sway = sway / total, s.stretch = stretch / total, s.drive = drive / total;
    out.push_back(s);
  }
  return out;
}

ModeKind mode_kind(const ModeShares& s) {
  if (s.sway + s.stretch < kLoadShare) return ModeKind::drive_line;
  return s.sway >= s.stretch ? ModeKind::pendulum : ModeKind::rope_stretch;
}

std::vector<ModeKind> mode_kinds(const Model& m, const Eigen::MatrixXd& shapes) {
  std::vector<ModeKind> out(static_cast<size_t>(shapes.cols()), ModeKind::drive_line);
  if (!has_swinging_load(m)) return out;
  const std::vector<ModeShares> s = mode_shares(m, mass_diagonal(m), shapes);
  for (size_t k = 0; k < s.size(); ++k) out[k] = mode_kind(s[k]);
  return out;
}

}  // namespace machdyn
