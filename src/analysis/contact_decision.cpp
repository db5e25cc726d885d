#include "machdyn/analysis/contact_decision.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "machdyn/common/diagnostics.hpp"

namespace machdyn {
namespace {

class Decision {
 public:
  Decision(DriveSystem& sys, double t, const double* y, const std::vector<int>& strict)
      : sys_(sys), t_(t), y_(y), strict_(strict) {
    const size_t n = static_cast<size_t>(sys.dof()), nc = sys.model().contacts.size();
    if (n + nc > small_.size()) big_.assign(n + nc, 0.0);
    acc_ = n + nc > small_.size() ? big_.data() : small_.data();
    fc_ = acc_ + n;
    for (size_t k = 0; k < nc; ++k) moving_surface_ = moving_surface_ || sys.contact(static_cast<int>(k)).moving_surface;
  }
  Decision(const Decision&) = delete;  // acc_ and fc_ point into this object
  Decision& operator=(const Decision&) = delete;

  /// The stick rule of contact k on the last evaluation (elements/contact.hpp).
  bool holds(int k) const {
    const bool strict = std::find(strict_.begin(), strict_.end(), k) != strict_.end();
    return sys_.contact(k).holds(fc_[static_cast<size_t>(k)], t_, strict);
  }
  void evaluate(const std::vector<ContactMode>& modes) {
    sys_.set_contact_modes(modes);
    // A rolling gear with clutches takes the driving side these modes imply (analysis/gear_clutch.hpp).
    if (sys_.has_coupled_gears()) sys_.settle_gear_sides(t_, y_);
    sys_.evaluate(t_, y_, acc_, fc_);
    // The loads λ the stick rule judges are those the event functions of these modes will read
    // (DriveSystem::contact_forces: a mode's affine map where there is one). Formed by the solve
    // above they may differ in the last bits, and a contact kept stuck at λ = F_s would start with
    // its event function at −1e-11: one quantity, one computation.
    sys_.contact_forces(t_, y_, fc_);
  }
  bool consistent(const std::vector<ContactMode>& modes, const std::vector<int>& Z) {
    evaluate(modes);
    return holds_all(modes, Z);
  }
  /// Whether the modes of Z are consistent on the last evaluation (of these modes).
  bool holds_all(const std::vector<ContactMode>& modes, const std::vector<int>& Z) const {
    for (int k : Z) {
      const ContactMode md = modes[static_cast<size_t>(k)];
      const double s = static_cast<double>(static_cast<int>(md));
      if (md == ContactMode::stuck ? !holds(k) : !sys_.contact(k).can_slide(md) || s * sliding_acceleration(k) < -rounding(k))
        return false;
      // Locked by the stuck set (its row in their span), its u̇ is 0 by the constraints whatever the
      // evaluation's rounding says: with every body of the set at rest u̇ came out ~1e-17 against a
      // rounding of 1e-12 |u̇| itself (f0: −8.8e-17 against 8.8e-29), and a contact the set ties (and one breaking away beside it)
      // was left sliding at u ≡ 0 (campaign `signals` seed 1 #95). Only a moving surface among the
      // rows gives a locked row a u̇ ≠ 0 (the surfaces' accelerations), judged to its rounding.
      if (md != ContactMode::stuck && (!moving_surface_ || std::abs(sliding_acceleration(k)) <= rounding(k)) &&
          locked(k, modes))
        return false;
    }
    return true;
  }
  /// Whether friction contact k (not a freewheel, stop or joint) is held at u ≡ 0 by the friction
  /// contacts, freewheels and stops stuck in `modes`: its row in the span of theirs (rank test to 1e-9). Such a contact
  /// cannot slide — its slide from rest is consistent only at u̇ = 0, by rounding — it is stuck with
  /// the set, its load within the set's limits (the bounded split; the audit's contact.locked_slide).
  /// Two parallel contacts to the ground, one breaking away at the instant another contact of the
  /// set did: the other kept it at u ≡ 0 (campaign `mixed` seed 2 model 83). A stuck freewheel or
  /// resting stop is such a row too (stuck, it is a constraint like any other: u ≡ 0 on its row): a
  /// contact beside a backstop that holds its body was released first where the set had no split
  /// (the weighted share overloading it, not the freewheel beyond its drag) and left "sliding" at
  /// u ≡ 0 (campaign `mixed` seed 1 #69; CampaignDefectsH).
  bool locked(int k, const std::vector<ContactMode>& modes) const {
    const ContactLaw& c = sys_.contact(k);
    if (c.lock != 0 || c.joint || c.kinematic) return false;
    const auto n = static_cast<Eigen::Index>(sys_.dof());
    std::vector<int> rows;
    for (size_t j = 0; j < modes.size(); ++j) {
      const ContactLaw& cj = sys_.contact(static_cast<int>(j));
      // A stuck freewheel or stop counts too — not yet beside a lossy gear that clutches couple
      // (analysis/gear_clutch.hpp): there a clutch beside a loaded freewheel (MSL's one-way clutch in
      // examples/msl/heat-losses.yaml) finds no other consistent mode in that decision (open).
      if (static_cast<int>(j) != k && modes[j] == ContactMode::stuck && !cj.joint && !cj.kinematic &&
          !cj.released(t_) && (cj.lock == 0 || !sys_.has_coupled_gears()))
        rows.push_back(static_cast<int>(j));
    }
    if (rows.empty()) return false;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()) + 1, n);
    auto put = [&](Eigen::Index i, const ContactLaw& x) {
      for (int j = 0; j < x.row.terms; ++j) G(i, x.row.body[j]) += x.row.w[j];
    };
    for (size_t i = 0; i < rows.size(); ++i) put(static_cast<Eigen::Index>(i), sys_.contact(rows[i]));
    put(G.rows() - 1, c);
    Eigen::FullPivLU<Eigen::MatrixXd> with(G), without(G.topRows(G.rows() - 1));
    with.setThreshold(1e-9), without.setThreshold(1e-9);
    return with.rank() == without.rank();
  }
  double force(int k) const { return fc_[static_cast<size_t>(k)]; }
  double sliding_acceleration(int k) const { return sys_.contact(k).sliding_acceleration(t_, acc_); }
  /// The rounding of u̇ = a_a − a_b: 1e-12 (|a_a| + |a_b|) (a general row: 1e-12 Σ |w_j a_j|). With μ_s = μ_k a breakaway starts with
  /// u̇ = 0 exactly; formed by the sliding equations it may come out −1e-14 while the stuck load is
  /// 1e-14 beyond the limit (MSL's Friction example on BDF), and neither mode would be consistent.
  double rounding(int k) const {
    const ContactLaw& c = sys_.contact(k);
    if (c.general) {  // Σ |w_j a_j| (and the surface's)
      double s = c.grounded ? std::abs(c.surface_acceleration(t_)) : 0.0;
      for (int j = 0; j < c.row.terms; ++j) s += std::abs(c.row.w[j] * acc_[static_cast<size_t>(c.row.body[j])]);
      return 1e-12 * s;
    }
    const double ab = c.b >= 0 ? acc_[static_cast<size_t>(c.b)] : c.surface_acceleration(t_);
    return 1e-12 * (std::abs(acc_[static_cast<size_t>(c.a)]) + std::abs(ab));
  }

 private:
  DriveSystem& sys_;
  double t_;
  const double* y_;
  const std::vector<int>& strict_;
  // The last evaluation's accelerations (dof) and contact forces: on the stack for a small model
  // (no allocation at every event), else on the heap.
  std::array<double, 32> small_{};
  std::vector<double> big_;
  double* acc_ = nullptr;
  double* fc_ = nullptr;
  bool moving_surface_ = false;  // some contact slides on a prescribed surface motion w(t)
};

}  // namespace

std::vector<ContactMode> decide_contacts(DriveSystem& sys, double t, const double* y, const std::vector<int>& Z,
                                         const std::vector<int>& strict) {
  std::vector<ContactMode> modes;
  decide_contacts(sys, t, y, Z, strict, modes);
  return modes;
}

void decide_contacts(DriveSystem& sys, double t, const double* y, const std::vector<int>& Z,
                     const std::vector<int>& strict, std::vector<ContactMode>& modes) {
  Decision d(sys, t, y, strict);
  const Model& m = sys.model();
  modes = sys.contact_modes();
  // A released brake or clutch is never stuck (elements/contact.hpp released()): labelled by its
  // sliding velocity (by its acceleration at u = 0), decided apart from the others.
  if (std::any_of(Z.begin(), Z.end(), [&](int k) { return sys.contact(k).released(t); })) {
    std::vector<int> rest;
    d.evaluate(modes);
    for (int k : Z) {
      if (!sys.contact(k).released(t)) {
        rest.push_back(k);
        continue;
      }
      const double u = sys.sliding_velocity(k, t, y), du = d.sliding_acceleration(k);
      modes[static_cast<size_t>(k)] = (u != 0.0 ? u : du) >= 0.0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    }
    sys.set_contact_modes(modes);
    if (!rest.empty()) decide_contacts(sys, t, y, rest, strict, modes);
    return;
  }
  // Kinematic contacts (between prescribed motions, elements/contact.hpp) change no acceleration:
  // their modes follow the motions, decided first and apart from the others.
  std::vector<int> kin;
  for (int k : Z)
    if (sys.contact(k).kinematic) kin.push_back(k);
  if (!kin.empty()) {
    d.evaluate(modes);
    for (int k : kin)
      modes[static_cast<size_t>(k)] = ContactLaw::kinematic_mode(sys.sliding_velocity(k, t, y), d.sliding_acceleration(k),
                                                                 d.rounding(k));
    std::vector<int> rest;
    for (int k : Z)
      if (!sys.contact(k).kinematic) rest.push_back(k);
    sys.set_contact_modes(modes);
    if (!rest.empty()) decide_contacts(sys, t, y, rest, strict, modes);
    return;
  }
  for (int k : Z) modes[static_cast<size_t>(k)] = ContactMode::stuck;
  // Release the most overloaded stuck contact until the stuck set holds.
  bool evaluated = false;  // the last evaluation is of `modes` (no contact released after it)
  for (size_t round = 0; round <= Z.size(); ++round) {
    d.evaluate(modes);
    int worst = -1;
    double worst_ratio = 1.0;
    for (int k : Z) {
      if (modes[static_cast<size_t>(k)] != ContactMode::stuck || d.holds(k)) continue;
      const double ratio = sys.contact(k).overload(d.force(k), t);
      if (worst < 0 || ratio > worst_ratio) worst = k, worst_ratio = ratio;
    }
    if (worst < 0) {
      evaluated = true;
      break;
    }
    modes[static_cast<size_t>(worst)] = d.force(worst) > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
  }
  // The same modes evaluated again would give the same accelerations and forces: checked as they are.
  if (evaluated ? d.holds_all(modes, Z) : d.consistent(modes, Z)) return;
  // Every combination, fewest sliding contacts first, then in index order.
  if (Z.size() > 10)
    throw SolverError(m.contacts[static_cast<size_t>(Z[0])].name, t,
                      "no consistent stick/slip modes found for more than 10 contacts at rest at once");
  long total = 1;
  for (size_t i = 0; i < Z.size(); ++i) total *= 3;
  std::vector<long> codes(static_cast<size_t>(total));
  for (long c = 0; c < total; ++c) codes[static_cast<size_t>(c)] = c;
  auto sliding = [&](long c) {
    int s = 0;
    for (size_t i = 0; i < Z.size(); ++i, c /= 3) s += c % 3 != 0;
    return s;
  };
  std::stable_sort(codes.begin(), codes.end(), [&](long x, long y2) { return sliding(x) < sliding(y2); });
  for (long code : codes) {
    long c = code;
    for (size_t i = 0; i < Z.size(); ++i, c /= 3)
      modes[static_cast<size_t>(Z[i])] =
          c % 3 == 0 ? ContactMode::stuck : c % 3 == 1 ? ContactMode::slip_pos : ContactMode::slip_neg;
    if (d.consistent(modes, Z)) return;
  }
  std::string names;
  for (int k : Z) names += (names.empty() ? "" : "', '") + m.contacts[static_cast<size_t>(k)].name;
  throw SolverError(names, t, "no consistent stick/slip modes (the contacts' static limits contradict)");
}

}  // namespace machdyn
