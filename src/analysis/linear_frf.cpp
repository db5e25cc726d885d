#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <Eigen/SparseLU>
#include <fmt/format.h>

#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/modal.hpp"
#include "machdyn/elements/link.hpp"

namespace machdyn {

LinearSignal linear_input(const Model& m, const std::string& name, const Location& where) {
  LinearSignal s;
  s.name = name;
  s.q = Eigen::VectorXd::Zero(m.dof());
  s.v = Eigen::VectorXd::Zero(m.dof());
  int body = -2;
  const Load* load = nullptr;
  for (const Load& l : m.loads)
    if (l.name == name) body = l.body, load = &l;
  if (body < 0) body = m.body_index(name);
  if (body < 0) {
    std::string known;
    for (const Load& l : m.loads) known += (known.empty() ? "" : ", ") + l.name;
    for (const Body& b : m.bodies) known += (known.empty() ? "" : ", ") + b.name;
    throw InputError(where, fmt::format("no load or body '{}' to excite (expected one of: {})", name, known));
  }
  s.q(body) = 1.0;  // the generalized force's weight on its body
  if (load && load->body2 >= 0) {  // a load on a member without inertia: ρ, ρ₂ (model.hpp: Load)
    s.q(body) = load->ratio;
    s.q(load->body2) = load->ratio2;
  }
  s.unit = load_unit(m.bodies[static_cast<size_t>(body)].kind);
  return s;
}

LinearSignal linear_output(const Model& m, const Topology& topo, const std::string& name, const Location& where) {
  LinearSignal s;
  s.name = name;
  const int n = m.dof();
  s.q = Eigen::VectorXd::Zero(n);
  s.v = Eigen::VectorXd::Zero(n);
  const size_t dot = name.rfind('.');
  const std::string element = dot == std::string::npos ? name : name.substr(0, dot);
  const std::string field = dot == std::string::npos ? "" : name.substr(dot + 1);
  for (size_t l = 0; l < m.links.size(); ++l) {
    if (m.links[l].name != element) continue;
    if (field != "load") throw InputError(where, fmt::format("'{}': a link's output is {}.load", name, element));
    std::vector<double> q(static_cast<size_t>(n)), v(q);
    for (int i = 0; i < n; ++i) q[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].q0, v[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].v0;
    LinkLaw::of(m, m.links[l]).add_load_gradient(q.data(), v.data(), topo.gaps[l], s.q.data(), s.v.data());
    s.unit = link_load_unit(m, m.links[l]);
    return s;
  }
  const int b = m.body_index(element);
  if (b >= 0 && (field == "position" || field == "speed")) {
    (field == "position" ? s.q : s.v)(b) = 1.0;
    s.unit = field == "position" ? position_unit(m.bodies[static_cast<size_t>(b)].kind)
                                 : velocity_unit(m.bodies[static_cast<size_t>(b)].kind);
    return s;
  }
  throw InputError(where, fmt::format("no output '{}': expected LINK.load, BODY.position or BODY.speed", name));
}

FrequencyResponse frequency_response(const LinearModel& lin, const LinearSignal& input,
                                     const std::vector<LinearSignal>& outputs, const Eigen::VectorXd& omega) {
  using C = std::complex<double>;
  if (input.q.size() != lin.n) throw std::invalid_argument("frequency_response: the input does not match the model");
  for (const auto& o : outputs)
    if (o.q.size() != lin.n || o.v.size() != lin.n)
      throw std::invalid_argument("frequency_response: an output does not match the model");
  for (double w : omega)
    if (!(w >= 0.0)) throw std::invalid_argument("frequency_response: frequencies must be >= 0");
  const ReducedModel red = reduce_constraints(lin);
  FrequencyResponse out;
  out.input = input;
  out.outputs = outputs;
  out.omega = omega;
  out.H.resize(omega.size(), static_cast<Eigen::Index>(outputs.size()));
  const Eigen::SparseMatrix<double> Tt = red.T.transpose();
  const Eigen::VectorXcd b = (Tt * input.q).cast<C>();
  Eigen::MatrixXd Cq(red.r, outputs.size()), Cv(red.r, outputs.size());
  for (size_t k = 0; k < outputs.size(); ++k) {
    Cq.col(static_cast<Eigen::Index>(k)) = Tt * outputs[k].q;
    Cv.col(static_cast<Eigen::Index>(k)) = Tt * outputs[k].v;
  }
  // Z(ω) = K − ω² M + iω D on the union of the three patterns (explicit zeros kept), so the
  // symbolic analysis is done once.
  Eigen::SparseMatrix<C> K = red.K.cast<C>(), M = red.M.cast<C>(), D = red.D.cast<C>();
  Eigen::SparseMatrix<C> pattern = K + M + D;
  for (int k = 0; k < pattern.outerSize(); ++k)
    for (Eigen::SparseMatrix<C>::InnerIterator it(pattern, k); it; ++it) it.valueRef() = C(0.0);
  K += pattern, M += pattern, D += pattern;  // the same pattern in all three
  Eigen::SparseLU<Eigen::SparseMatrix<C>> lu;
  Eigen::SparseMatrix<C> Z = K;
  if (red.r > 0) lu.analyzePattern(Z);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Index f = 0; f < omega.size(); ++f) {
    const double w = omega(f);
    // The same compressed pattern: combine the value arrays directly.
    for (Eigen::Index k = 0; k < Z.nonZeros(); ++k)
      Z.valuePtr()[k] = K.valuePtr()[k] - w * w * M.valuePtr()[k] + C(0.0, w) * D.valuePtr()[k];
    if (red.r == 0) {
      out.H.row(f).setZero();
      continue;
    }
    lu.factorize(Z);
    bool ok = lu.info() == Eigen::Success;
    Eigen::VectorXcd z;
    if (ok) {
      z = lu.solve(b);
      ok = lu.info() == Eigen::Success && z.allFinite();
    }
    if (!ok) {
      out.H.row(f).setConstant(C(nan, nan));
      continue;
    }
    for (size_t k = 0; k < outputs.size(); ++k) {
      const auto kk = static_cast<Eigen::Index>(k);
      out.H(f, kk) = Cq.col(kk).cast<C>().dot(z) + C(0.0, w) * Cv.col(kk).cast<C>().dot(z);
    }
  }
  return out;
}

Eigen::MatrixXd FrequencyResponse::magnitude() const { return H.cwiseAbs(); }

Eigen::MatrixXd FrequencyResponse::phase_deg() const {
  Eigen::MatrixXd p(H.rows(), H.cols());
  for (Eigen::Index k = 0; k < H.cols(); ++k) {
    double prev = std::numeric_limits<double>::quiet_NaN();
    for (Eigen::Index f = 0; f < H.rows(); ++f) {
      double a = std::arg(H(f, k)) * 180.0 / std::numbers::pi;
      if (std::isfinite(prev) && std::isfinite(a)) a -= 360.0 * std::round((a - prev) / 360.0);
      p(f, k) = a;
      if (std::isfinite(a)) prev = a;
    }
  }
  return p;
}

std::vector<ResonancePeak> resonance_peaks(const FrequencyResponse& r) {
  const Eigen::MatrixXd mag = r.magnitude(), ph = r.phase_deg();
  std::vector<ResonancePeak> peaks;
  for (Eigen::Index k = 0; k < mag.cols(); ++k)
    for (Eigen::Index f = 1; f + 1 < mag.rows(); ++f) {
      const double y = mag(f, k);
      if (std::isfinite(y) && y > mag(f - 1, k) && y >= mag(f + 1, k))
        peaks.push_back({static_cast<int>(k), r.omega(f), y, ph(f, k)});
    }
  return peaks;
}

Eigen::VectorXd frequency_grid(double lo, double hi, int count, bool log) {
  if (count < 1 || !(hi >= lo) || (log && !(lo > 0.0)) || lo < 0.0)
    throw std::invalid_argument("frequency_grid: expected 0 <= lo <= hi (lo > 0 on a log scale) and count >= 1");
  Eigen::VectorXd w(count);
  for (int i = 0; i < count; ++i) {
    const double s = count == 1 ? 0.0 : static_cast<double>(i) / (count - 1);
    w(i) = log ? lo * std::pow(hi / lo, s) : lo + (hi - lo) * s;
  }
  return w;
}

}  // namespace machdyn
