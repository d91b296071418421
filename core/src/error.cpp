#include "dtwire/core/error.hpp"

namespace dtwire {
namespace {
std::string locate(const std::string& source, int line, int column, const std::string& message) {
  std::string where = source;
  if (line > 0) where += ":" + std::to_string(line);
  if (line > 0 && column > 0) where += ":" + std::to_string(column);
  return where + ": " + message;
}
}  // namespace

InputError::InputError(std::string source, int line, int column, const std::string& message)
    : std::runtime_error(locate(source, line, column, message)),
      source_(std::move(source)),
      line_(line),
      column_(column) {}

InputError::InputError(std::string source, const std::string& message)
    : InputError(std::move(source), 0, 0, message) {}

}  // namespace dtwire
