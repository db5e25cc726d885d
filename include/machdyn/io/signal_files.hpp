#pragma once
/// @file
/// Signals of measured data (model/signal.hpp): `{type: file, path: FILE.csv, time: COLUMN,
/// column: COLUMN, unit: U, time_unit: U, outside: hold|extrapolate}` is read here, in io, and
/// replaced by the table it holds (`type: table` with the CSV's cells as `points`), before the model
/// compiles. The model layer reads no files.
///
/// The CSV: an optional `#` comment block, then a header row of names, then rows of numbers;
/// separated by `,` (or `;` or tabs, whichever the header uses). A header name may carry its unit
/// after the last `_`: `t_s`, `torque_kN*m`, `force_N`. `time` and `column` choose columns by name
/// (with or without that unit), by default the first and the second. `unit` and `time_unit` in the
/// spec take precedence over the header; without either the numbers are SI.
///
/// Every problem is reported with its place: a missing file at the spec's `path`; a bad cell, a
/// short row or a decreasing time at the CSV's row and column (naming the model file's place of
/// the signal too); an unknown column at the spec's `time`/`column`. Limits: kMaxSignalFileBytes
/// and kMaxSignalFileRows (the table's spec takes some 400 bytes per row while compiling).

#include <cstddef>

#include "machdyn/common/spec.hpp"

namespace machdyn {

inline constexpr std::size_t kMaxSignalFileBytes = 64u * 1024u * 1024u;  ///< 64 MiB
inline constexpr std::size_t kMaxSignalFileRows = 1'000'000;

/// Replaces every `type: file` signal under `loads:`, `contacts:`, `brakes:` (and those sections of
/// each case) by its table. A relative path is taken from the file the `path` value is written in.
/// Records every problem in `diag`; a signal whose file has a problem is left as it is.
void resolve_signal_files(SpecNode& root, Diagnostics& diag);

}  // namespace machdyn
