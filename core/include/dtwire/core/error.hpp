#pragma once
// Errors that reach the user. InputError names where the bad input is (file:line:column) and
// what was expected; the CLI turns it into exit code 2.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace dtwire {

inline constexpr int kExitBadInput = 2;
inline constexpr int kExitFailure = 1;

class InputError : public std::runtime_error {
 public:
  // line and column are 1-based; 0 means "not applicable".
  InputError(std::string source, int line, int column, const std::string& message);
  InputError(std::string source, const std::string& message);

  const std::string& source() const { return source_; }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  std::string source_;
  int line_ = 0;
  int column_ = 0;
};

// A simulation or fit that did not reach an answer (non-convergence, failed evaluation).
class ComputationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dtwire
