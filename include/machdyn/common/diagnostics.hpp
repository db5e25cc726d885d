#pragma once
/// @file
/// Input errors with their place in the source: every problem the reader or the compiler finds is
/// collected, then thrown together as one InputError, so a user fixes a file in one pass.

#include <stdexcept>
#include <string>
#include <vector>

namespace machdyn {

/// Where a value came from: a file with 1-based line and column, or a command-line override
/// (`file` then says e.g. "--set c1.stiffness", line and column are 0).
struct Location {
  std::string file;
  int line = 0;
  int column = 0;
  [[nodiscard]] std::string str() const;  ///< "file:line:col" or just "file" without a line
};

struct Diagnostic {
  Location where;
  std::string message;  ///< what is wrong and what was expected
  [[nodiscard]] std::string str() const;  ///< "file:line:col: error: message"
};

/// Collects problems without stopping at the first.
class Diagnostics {
 public:
  void error(const Location& where, std::string message);
  [[nodiscard]] bool empty() const { return list_.empty(); }
  [[nodiscard]] const std::vector<Diagnostic>& list() const { return list_; }
  /// Throws InputError with everything collected, if anything was.
  void throw_if_any() const;

 private:
  std::vector<Diagnostic> list_;
};

/// Bad input: a model file, a spec file or a command-line override. The CLI exits with code 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<Diagnostic> diagnostics);
  InputError(const Location& where, const std::string& message);
  [[nodiscard]] const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

/// A numerical failure during a run: which element (body, link, load) and at what time.
/// The CLI exits with code 3 and writes no result file.
class SolverError : public std::runtime_error {
 public:
  SolverError(std::string element, double t, const std::string& what);
  [[nodiscard]] const std::string& element() const { return element_; }
  [[nodiscard]] double time() const { return t_; }

 private:
  std::string element_;
  double t_;
};

}  // namespace machdyn
