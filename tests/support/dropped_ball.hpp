#pragma once
// A reference-simulator model the campaign tests share (tests/reference/reference.hpp).
#include "reference/reference.hpp"

namespace machdyn::test {

/// A ball of 2 kg dropped from h (m) onto a floor at 0 under its weight (19.62 N, g = 9.81 m/s²),
/// restitution e = 0.5: impacts at t₁ = √(2 h/g), then every 2 v_k/g with v_k = eᵏ √(2 g h) (v⁻ of
/// impact k), resting at the accumulation instant t∞ = t₁ (1 + e)/(1 − e).
inline reference::RefModel dropped_ball(double h, double t_end = 1.0) {
  reference::RefModel m;
  m.bodies = {{"ball", 2.0, h, 0.0}};
  reference::Signal G;
  G.kind = reference::Signal::Kind::constant, G.value = -19.62;
  m.loads = {{"G", 0, G}};
  reference::Friction s;
  s.kind = reference::Friction::Kind::stop, s.name = "floor", s.a = 0, s.stop_pos = 0.0, s.e = 0.5;
  m.frictions = {s};
  m.t_end = t_end, m.dt_out = 0.01;
  return m;
}

}  // namespace machdyn::test
