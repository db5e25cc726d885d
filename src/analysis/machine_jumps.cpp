#include "analysis/machine_jumps.hpp"

#include <algorithm>
#include <cmath>

namespace machdyn::detail {

namespace {
/// How far beside a jump position a sample is taken (beyond next_jump()'s own tolerance).
double side_offset(double q) { return 1e-11 * (1.0 + std::abs(q)); }
}  // namespace

MachineJumps::MachineJumps(const Model& m, DriveSystem& sys)
    : sys_(sys), n_(m.dof()), y_(static_cast<size_t>(sys.size())) {
  for (int i = 0; i < n_; ++i) {
    const Machine* mach = m.bodies[static_cast<size_t>(i)].machine.get();
    if (!mach || !(mach->has_jumps() || mach->reports_point_speed())) continue;
    Trace tr;
    tr.body = i;
    tr.name = m.bodies[static_cast<size_t>(i)].name;
    tr.machine = mach;
    traces_.push_back(std::move(tr));
    if (mach->has_jumps()) {
      Jumper J;
      J.body = i, J.machine = mach, J.trace = static_cast<int>(traces_.size()) - 1;
      jumpers_.push_back(J);
    }
  }
}

void MachineJumps::sample(Trace& tr, double t, double q, double v) {
  tr.t.push_back(t);
  tr.q.push_back(q);
  tr.v.push_back(v);
}

void MachineJumps::start(double t0, const double* y0) {
  for (auto& tr : traces_) sample(tr, t0, y0[tr.body], y0[n_ + tr.body]);
  arm(y0);
}

void MachineJumps::sample_piece(const Stepper& s, double ta, double tb) {
  const double t0 = ta, h = tb - ta;
  for (int j = 1; j <= 4; ++j) {
    const double t = j == 4 ? tb : t0 + 0.25 * j * h;
    const double* y = s.y();
    if (j < 4 || tb != s.t()) {
      s.interpolate(t, y_.data());
      y = y_.data();
    }
    for (auto& tr : traces_) sample(tr, t, y[tr.body], y[n_ + tr.body]);
  }
  // A step that ends on an event may end a hair beyond the jump position (the re-integration to the
  // located time): keep such samples on the side of the motion before the jump.
  for (const auto& J : jumpers_) {
    Trace& tr = traces_[static_cast<size_t>(J.trace)];
    double& q = tr.q.back();
    if (q > J.up - side_offset(J.up)) q = J.up - side_offset(J.up);
    if (q < J.down + side_offset(J.down)) q = J.down + side_offset(J.down);
  }
}

void MachineJumps::arm(const double* y) {
  for (auto& J : jumpers_) {
    const double q = y[J.body];
    J.up = J.machine->next_jump(q, +1);
    J.down = J.machine->next_jump(q, -1);
    // Right after a jump q is on the jump position, which is then the boundary behind the motion
    // (next_jump() looks strictly beyond q).
    if (J.last_dir != 0 && q == J.last_q) (J.last_dir > 0 ? J.down : J.up) = q;
    // Until the next event the machine is evaluated on its current piece only (q is on a jump
    // position right after a jump: the window starts a hair into the piece of the motion).
    sys_.set_evaluation_window(J.body, J.down + side_offset(J.down), J.up - side_offset(J.up));
  }
}

void MachineJumps::event_functions(const double* y, double* g) const {
  for (size_t k = 0; k < jumpers_.size(); ++k) {
    const Jumper& J = jumpers_[k];
    const double q = y[J.body];
    g[2 * k] = J.up - q;
    g[2 * k + 1] = q - J.down;
  }
}

void MachineJumps::jump(double t, double* y, int which) {
  const auto k = static_cast<size_t>(which / 2);
  const int dir = which % 2 == 0 ? +1 : -1;
  Jumper& J = jumpers_[k];
  const double qb = dir > 0 ? J.up : J.down;
  Trace& tr = traces_[static_cast<size_t>(J.trace)];
  const double w = y[n_ + J.body];
  // Samples just before and after, a hair on each side of the jump position so that the point
  // speed uses the ratio of that side (the stepwise extremes are here).
  const double side = dir * side_offset(qb);
  sample(tr, t, qb - side, w);
  double loss = 0.0;
  y[J.body] = qb;  // on the boundary exactly (the located time is within ~1e-15 s of it)
  y[n_ + J.body] = J.machine->velocity_after_jump(qb, dir, w, &loss);
  sample(tr, t, qb + side, y[n_ + J.body]);
  J.last_dir = dir;
  J.last_q = qb;
  tr.jump_t.push_back(t);
  tr.jump_loss.push_back(loss);
  ++jumps_;
  arm(y);
}

namespace {

/// The last time at or before sample `hi` where q crosses qx coming from the side −dir (linear
/// between samples); *j is the last sample before it. NaN when q never was on that side.
double crossing_time(const std::vector<double>& t, const std::vector<double>& q, size_t hi, double qx, int dir,
                     size_t* j) {
  size_t k = hi;
  while (k > 0 && dir * (q[k] - qx) > 0) --k;
  *j = k;
  if (dir * (q[k] - qx) > 0) return std::nan("");
  if (k == hi) return t[k];
  const double dq = q[k + 1] - q[k];
  return dq != 0.0 ? t[k] + (qx - q[k]) * (t[k + 1] - t[k]) / dq : t[k];
}

}  // namespace

std::vector<MachineRunReport> MachineJumps::reports() const {
  std::vector<MachineRunReport> out;
  for (const auto& tr : traces_) {
    MachineRunReport r;
    const Machine& M = *tr.machine;
    r.body = tr.name;
    if (M.reports_point_speed()) r.point = M.point_name();
    r.period = M.period();
    r.jumps = static_cast<long>(tr.jump_t.size());
    for (double l : tr.jump_loss) r.jump_loss += l;
    const size_t last = tr.t.size() - 1;
    if (r.period > 0.0 && tr.t.size() >= 2) {
      const double q0 = tr.q.front(), qe = tr.q[last];
      const int dir = qe >= q0 ? 1 : -1;
      const double P = r.period;
      r.periods_run = std::abs(qe - q0) / P;
      auto point_speed = [&](size_t k) {
        double p, dp, ddp;
        M.point(tr.q[k], &p, &dp, &ddp);
        return dp * tr.v[k];
      };
      auto travel = [&](double q) {
        double p, dp, ddp;
        M.point(q, &p, &dp, &ddp);
        return p;
      };
      // δ of the point speed over the period ending at sample `hi` (time t_hi, position q_hi).
      auto window = [&](size_t hi, double t_hi, double q_hi, MachineRunReport* w) -> bool {
        size_t j;
        const double t_lo = crossing_time(tr.t, tr.q, hi, q_hi - dir * P, dir, &j);
        if (std::isnan(t_lo) || !(t_hi > t_lo)) return false;
        w->t_from = t_lo, w->t_to = t_hi;
        w->v_mean = (travel(q_hi) - travel(q_hi - dir * P)) / (t_hi - t_lo);
        w->omega_mean = (q_hi - (q_hi - dir * P)) / (t_hi - t_lo);
        w->v_max = w->omega_max = -HUGE_VAL;
        w->v_min = w->omega_min = HUGE_VAL;
        for (size_t k = j + 1; k <= hi; ++k) {
          const double V = point_speed(k);
          w->v_max = std::max(w->v_max, V), w->v_min = std::min(w->v_min, V);
          w->omega_max = std::max(w->omega_max, tr.v[k]), w->omega_min = std::min(w->omega_min, tr.v[k]);
        }
        w->delta = (w->v_max - w->v_min) / std::abs(w->v_mean);
        w->omega_delta = (w->omega_max - w->omega_min) / std::abs(w->omega_mean);
        return true;
      };
      if (r.periods_run >= 1.0 && window(last, tr.t[last], qe, &r)) {
        r.window = true;
        for (size_t k = 0; k < tr.jump_t.size(); ++k)
          if (tr.jump_t[k] > r.t_from && tr.jump_t[k] <= r.t_to) ++r.jumps_window, r.jump_loss_window += tr.jump_loss[k];
        if (r.periods_run >= 2.0) {
          // The period before: ends where the window starts.
          size_t j;
          const double qs = qe - dir * P;
          crossing_time(tr.t, tr.q, last, qs, dir, &j);
          MachineRunReport prev;
          if (window(j, r.t_from, qs, &prev)) r.delta_previous = prev.delta;
        }
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace machdyn::detail
