#pragma once
/// @file
/// A signal: a quantity given as a function of time s(t), in SI, the one way anything that varies in
/// time is written (loads, and switching and direction of motors). Immutable; built by the model
/// compiler (model/compile_signal.hpp) or directly with the factories below.
///
/// Kinds (t in s; values in the SI unit of the field that holds the signal):
///   constant   s = c
///   step       s = before for t < t0, after for t ≥ t0
///   ramp       s = before for t ≤ t0, linear to after at t1, after for t ≥ t1        (t1 > t0)
///   table      piecewise linear through (t_k, s_k), t_k non-decreasing; two points at one time make
///              a jump (s takes the second value from that time on). Outside [t_0, t_n]: held at the
///              end values (`hold`), or continued along the first/last segment (`extrapolate`).
///   sine       s = offset for t < t_s, offset + A sin(ω (t − t_s) + φ) for t ≥ t_s
///   pulse      s = high for t in [t_s + k P, t_s + k P + w), k = 0 … count−1 (count < 0: no end),
///              else low                                                             (0 < w < P)
///   expression s = f(t), an expression in `t` (common/expression.hpp)
///   sum        s = Σ s_i(t)
/// A CSV file of measured data is read by io (io/model_file.hpp) into a table.
///
/// Breakpoints are the times where s jumps or has a kink: step t0; ramp t0, t1; every table time;
/// the sine's start; every pulse edge; an expression's switches (step, comparisons, min, max:
/// Expression::switch_points, each the first time on the new side); those of each term of a sum. An
/// integrator must not step across them (the driver stops there, solve/event_system.hpp). abs in an
/// expression keeps no breakpoint (write max(x, -x) where its kink matters).

#include <memory>
#include <string>
#include <vector>

namespace machdyn {

class Expression;

class Signal {
 public:
  enum class Kind { constant, step, ramp, table, sine, pulse, expression, sum };

  Signal() = default;  ///< the constant 0
  static Signal constant(double c);
  static Signal step(double before, double after, double t0);
  static Signal ramp(double before, double after, double t0, double t1);
  /// `times` non-decreasing, at most two equal in a row; same size as `values`, not empty.
  /// `extrapolate` needs a first and a last segment of positive length. Throws std::invalid_argument.
  static Signal table(std::vector<double> times, std::vector<double> values, bool extrapolate = false);
  /// ω in rad/s (2π f), φ in rad.
  static Signal sine(double amplitude, double omega, double phase, double offset, double start);
  /// Period P > 0, width 0 < w < P; count < 0: unending. Throws std::invalid_argument.
  static Signal pulse(double low, double high, double period, double width, double start, long count);
  /// `f` is an expression with the one variable t.
  static Signal expression(std::shared_ptr<const Expression> f);
  static Signal sum(std::vector<Signal> terms);

  /// s(t).
  [[nodiscard]] double value(double t) const;
  /// ds/dt, the slope on the right of t at a kink (0 across a jump).
  [[nodiscard]] double slope(double t) const;
  /// d²s/dt², on the right of t at a breakpoint: 0 for constant, step, ramp, table and pulse (piecewise
  /// linear), −A ω² sin(ω (t − t_s) + φ) for a sine from its start, exact for an expression (its jet).
  [[nodiscard]] double curvature(double t) const;
  /// The breakpoints in the open interval (t0, t1), increasing, without repeats.
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t1) const;
  /// The number of breakpoints in (t0, t1) without listing them (a bound for the memory check).
  [[nodiscard]] double breakpoint_count(double t0, double t1) const;
  /// The times in (t0, t1), increasing, where s crosses `level` with a change of sign of s − level
  /// (the kinks of max(level, s), e.g. a normal force that turns negative: a clutch opens). Exact
  /// for ramp, table and sine; a jump that passes the level is a breakpoint, not a crossing. For an
  /// expression or a sum: s − level sampled at 4096 equal steps and at the breakpoints, each sign
  /// change refined by bisection to the last bit (two crossings within one sample step are missed).
  [[nodiscard]] std::vector<double> crossings(double level, double t0, double t1) const;
  /// An upper bound of |s| on [t0, t1]: exact for every kind but an expression, whose |s| is
  /// sampled at 1001 points (a scale for tolerances, not a limit that is enforced).
  [[nodiscard]] double magnitude_bound(double t0, double t1) const;
  /// Whether s is the same at every time.
  [[nodiscard]] bool is_constant() const;
  /// The values s takes if it is piecewise constant (constant, step, pulse, a table whose segments
  /// are flat, sums of those), sorted without repeats; empty if it is not piecewise constant.
  [[nodiscard]] std::vector<double> levels() const;
  /// A short description in words for reports, with `unit` after each value: "step 0 → 5 N at 2 s".
  [[nodiscard]] std::string describe(const std::string& unit) const;

  [[nodiscard]] Kind kind() const { return kind_; }
  /// The kind as the model file spells it: "constant", "step", ..., "sum".
  static const char* kind_name(Kind k);
  [[nodiscard]] const std::vector<double>& times() const { return x_; }   ///< table
  [[nodiscard]] const std::vector<double>& values() const { return y_; }  ///< table
  [[nodiscard]] const std::vector<Signal>& terms() const { return terms_; }  ///< sum

 private:
  Kind kind_ = Kind::constant;
  // constant: a; step: a before, b after, t0; ramp: a, b, t0, t1; sine: a amplitude, b ω, c φ,
  // d offset, t0 start; pulse: a low, b high, c period, d width, t0 start, count.
  double a_ = 0.0, b_ = 0.0, c_ = 0.0, d_ = 0.0, t0_ = 0.0, t1_ = 0.0;
  long count_ = -1;
  bool extrapolate_ = false;
  std::vector<double> x_, y_;  ///< table
  std::shared_ptr<const Expression> f_;
  std::vector<Signal> terms_;
};

}  // namespace machdyn
