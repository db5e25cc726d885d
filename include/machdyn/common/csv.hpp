#pragma once
/// @file
/// CSV as RFC 4180 writes it, the one quoting rule of every CSV file machdyn writes (time series,
/// sweep tables, energy, modes, crane, plot data): a field holding a comma, a double quote, a line
/// break (CR or LF) or a space at either end is written in double quotes, each quote in it doubled.
/// Any CSV reader (Python's csv module, pandas, a spreadsheet) then reads the header and every row
/// with the same number of fields, whatever the names are.

#include <string>
#include <string_view>
#include <vector>

namespace machdyn {

/// `text` as one CSV field: quoted when it must be (see the file comment), or always with
/// `always_quote` (a text column whose cells are quoted alike, e.g. the labels of modes.csv).
std::string csv_field(std::string_view text, bool always_quote = false);

/// The fields joined by commas, each through csv_field (no line end).
std::string csv_line(const std::vector<std::string>& fields);

}  // namespace machdyn
