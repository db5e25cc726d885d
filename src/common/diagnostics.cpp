#include "machdyn/common/diagnostics.hpp"

#include <fmt/format.h>

namespace machdyn {

std::string Location::str() const {
  if (line <= 0) return file;
  return fmt::format("{}:{}:{}", file, line, column);
}

std::string Diagnostic::str() const { return fmt::format("{}: error: {}", where.str(), message); }

void Diagnostics::error(const Location& where, std::string message) {
  list_.push_back({where, std::move(message)});
}

void Diagnostics::throw_if_any() const {
  if (!list_.empty()) throw InputError(list_);
}

namespace {
std::string join(const std::vector<Diagnostic>& ds) {
  std::string s;
  for (const auto& d : ds) {
    if (!s.empty()) s += '\n';
    s += d.str();
  }
  return s;
}
}  // namespace

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join(diagnostics)), diagnostics_(std::move(diagnostics)) {}

InputError::InputError(const Location& where, const std::string& message)
    : InputError(std::vector<Diagnostic>{{where, message}}) {}

SolverError::SolverError(std::string element, double t, const std::string& what)
    : std::runtime_error(fmt::format("numerical failure in '{}' at t = {:.9g} s: {}", element, t, what)),
      element_(std::move(element)),
      t_(t) {}

}  // namespace machdyn
