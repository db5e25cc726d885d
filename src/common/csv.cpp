#include "machdyn/common/csv.hpp"

namespace machdyn {

std::string csv_field(std::string_view text, bool always_quote) {
  const bool quote = always_quote || text.find_first_of(",\"\r\n") != std::string_view::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' '));
  if (!quote) return std::string(text);
  std::string q = "\"";
  for (const char ch : text) {
    if (ch == '"') q += '"';
    q += ch;
  }
  return q + '"';
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string s;
  for (size_t k = 0; k < fields.size(); ++k) {
    if (k) s += ',';
    s += csv_field(fields[k]);
  }
  return s;
}

}  // namespace machdyn
