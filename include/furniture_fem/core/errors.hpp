#pragma once
// Exceptions shared by every module. An error names where the bad value came from (a file and line,
// a scene key path, a member or element) and the value, so a user can fix the input.
#include <sstream>
#include <stdexcept>
#include <string>

namespace furniture_fem {

// Bad input read from a file: "file:line: field: message".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, long line, std::string field, std::string message)
      : std::runtime_error(format(file, line, field, message)),
        file_(std::move(file)), line_(line), field_(std::move(field)) {}
  const std::string& file() const noexcept { return file_; }
  long line() const noexcept { return line_; }
  const std::string& field() const noexcept { return field_; }

 private:
  static std::string format(const std::string& file, long line, const std::string& field,
                            const std::string& message) {
    std::ostringstream os;
    os << file;
    if (line > 0) os << ':' << line;
    if (!field.empty()) os << ": " << field;
    os << ": " << message;
    return os.str();
  }
  std::string file_;
  long line_;
  std::string field_;
};

// A model that cannot be simulated: "member 'left post' element 12: zero length (0 m)".
class ModelError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A run that can no longer be trusted (NaN, divergence): carries the time and a diagnosis.
class SimulationError : public std::runtime_error {
 public:
  SimulationError(double time, std::string diagnosis)
      : std::runtime_error("t = " + std::to_string(time) + " s: " + diagnosis), time_(time) {}
  double time() const noexcept { return time_; }

 private:
  double time_;
};

}  // namespace furniture_fem
