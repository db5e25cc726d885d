#pragma once
/// @file
/// Frequency response of one topology's linear model (elements/linear_model.hpp): for a harmonic
/// generalized force f = b û e^{iωt} on the constraint manifold q = T z (analysis/modal.hpp),
///   (K_r − ω² M_r + iω D_r) ẑ = Tᵀ b û,   ŷ = (c_q + iω c_v)ᵀ T ẑ,
/// so H(iω) = ŷ/û, the complex amplitude ratio of an output y = c_qᵀ q + c_vᵀ q̇ (a link load, a
/// body's position or speed) to the input û (N·m or N). |H| in the output's unit per the input's,
/// phase in degrees (y lags û by −phase). Solved directly at each frequency (sparse LU, the
/// pattern analysed once). Where the dynamic stiffness is singular (ω = 0 with a rigid-body mode,
/// an undamped resonance hit exactly) H is NaN.

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// An input or output of the linear model as weights over q and q̇ (n each).
struct LinearSignal {
  std::string name;   ///< e.g. "MB", "c1.load", "I2.speed"
  std::string unit;   ///< "N*m", "rad/s", ...
  Eigen::VectorXd q, v;
};

/// The input named `name`: a load of the model (its body's generalized force) or a body
/// ("I1": a force or torque on it). Throws InputError at `where` otherwise.
LinearSignal linear_input(const Model& m, const std::string& name, const Location& where);

/// The output named `name`: LINK.load (the link's law linearized in `topo`, initial state),
/// BODY.position or BODY.speed. Throws InputError at `where` otherwise.
LinearSignal linear_output(const Model& m, const Topology& topo, const std::string& name, const Location& where);

struct FrequencyResponse {
  LinearSignal input;
  std::vector<LinearSignal> outputs;
  Eigen::VectorXd omega;   ///< rad/s
  Eigen::MatrixXcd H;      ///< omega.size() × outputs.size()
  /// |H| and the phase in degrees, unwrapped along ω (continuous from the first frequency).
  [[nodiscard]] Eigen::MatrixXd magnitude() const;
  [[nodiscard]] Eigen::MatrixXd phase_deg() const;
};

/// H at each ω for the input and outputs. Throws std::invalid_argument on sizes that do not match
/// lin.n or a negative ω.
FrequencyResponse frequency_response(const LinearModel& lin, const LinearSignal& input,
                                     const std::vector<LinearSignal>& outputs, const Eigen::VectorXd& omega);

/// A local maximum of |H| of output `output` on the frequency grid (the grid's resolution).
struct ResonancePeak {
  int output = 0;
  double omega = 0.0;      ///< rad/s
  double magnitude = 0.0;
  double phase_deg = 0.0;
};
std::vector<ResonancePeak> resonance_peaks(const FrequencyResponse& r);

/// `count` frequencies from lo to hi (rad/s), evenly spaced on a log scale (lo > 0) or linearly.
Eigen::VectorXd frequency_grid(double lo, double hi, int count, bool log);

}  // namespace machdyn
