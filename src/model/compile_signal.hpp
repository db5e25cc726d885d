#pragma once
// Compiler of the signal grammar (model/signal.hpp): the one way a field that varies in time is
// written, for every element that takes one. Called from compile.cpp; messages follow its conventions.
//
//   FIELD: 12 kN*m                                  a constant (a quantity of the field's dimension)
//   FIELD: {type: KIND, ...}                        KIND and its fields:
//     constant   value
//     step       value, before (0), time
//     ramp       value, before (0), start (0), end
//     table      points [[t, s], ...] (two points at one time: a jump), outside: hold|extrapolate,
//                unit / time_unit (the points are then plain numbers in these units)
//     sine       amplitude, frequency (Hz, or rad/s, rpm: any unit with rad or rev), phase (0),
//                offset (0), start (0)
//     pulse      high, low (0), period, width (a time, or a % of the period), start (0), count
//     expression expression (of t)
//     sum        terms: [signal, ...]
//     shaped     shaper: none|zv|zvd|two-step, frequency | length, damping (0), signal (model/shaper.hpp)
//     file       a CSV file: replaced by a table when the model file is read (io/model_file.hpp)
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/signal.hpp"

namespace machdyn::detail {

/// The signal kinds a `type:` may name.
const std::vector<std::string>& signal_types();
bool is_signal_type(std::string_view type);

/// Reads a signal from a field's value: a scalar quantity of dimension `d` (a constant) or a map
/// with `type:`. `what` names the element and field in messages ("load 'M1': field 'on'").
std::optional<Signal> compile_signal(const SpecNode& node, const Dim& d, const std::string& what, Diagnostics& diag);

/// Reads the fields of a signal of kind `type` from the element's own map (as `type: sine` under a
/// load). Marks the fields used in `f`; the caller calls f.finish().
std::optional<Signal> read_signal_fields(FieldReader& f, const std::string& type, const Dim& d);

/// A piecewise-linear table y(x) from `points` [[x, y], ...] with x in `xd` and y in `yd`; x must
/// increase strictly unless `jumps` (then two equal x in a row are allowed). Honours `outside`,
/// `unit` and `time_unit` of the map `f` reads (the last two only if `units`). At most
/// kMaxTablePoints points (the limit of a CSV signal file's rows, io/signal_files.hpp).
inline constexpr std::size_t kMaxTablePoints = 1'000'000;
std::optional<Signal> read_table(FieldReader& f, const Dim& xd, const Dim& yd, bool jumps, bool units);

/// Sines that no run could follow to t_end: a sine of frequency f makes f·t_end periods, and an
/// integrator needs some kMinStepsPerPeriod steps in each (far more at a usual tolerance), so more
/// than max_steps / kMinStepsPerPeriod periods would end in the step limit after hours (1e300 Hz).
/// Walks the spec (every `type: sine` map outside `cases:`, whatever element holds it) and reports
/// each such sine at its `frequency`.
inline constexpr double kMinStepsPerPeriod = 4.0;
void check_sine_periods(const SpecNode& root, double t_end, long max_steps, Diagnostics& diag);

}  // namespace machdyn::detail
