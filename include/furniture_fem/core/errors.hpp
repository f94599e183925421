#pragma once
// Exceptions shared by every module, one hierarchy under furniture_fem::Error:
//
//   Error (std::runtime_error)
//   ├── InputError       bad input: a file, a scene key, an argument ("file:line: field: message")
//   │   └── ModelError   a model that cannot be simulated (a bad model is bad input)
//   ├── SimulationError  a run that can no longer be trusted (NaN, divergence, a failed solve)
//   └── OutputError      a result that cannot be written (a file that cannot be opened or written)
//
// An error names where the bad value came from (a file and line, a scene key path, a member or
// element, a function's argument) and the value, so a user can fix the input.
#include <sstream>
#include <stdexcept>
#include <string>

namespace furniture_fem {

// Whether x, a count of steps, samples or elements computed in double, may be converted to an integer:
// at least 0 and at most `max` (false for NaN and infinities). Converting a double outside the
// integer's range is undefined behaviour (3 / (f dt) = 5e59 went to size_t; issue 13), so every such
// conversion of an input-derived value is checked first and refused with a message naming the input.
inline bool count_fits(double x, double max) { return x >= 0 && x <= max; }

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad input: "file:line: field: message" for what was read from a file or a scene, or a message
// alone ("low_pass: order must be 1..16 (got 20)") for a bad argument of a function.
class InputError : public Error {
 public:
  InputError(std::string file, long line, std::string field, std::string message)
      : Error(format(file, line, field, message)), file_(std::move(file)), line_(line), field_(std::move(field)) {}
  explicit InputError(const std::string& message) : Error(message), line_(0) {}
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
class ModelError : public InputError {
 public:
  explicit ModelError(const std::string& message) : InputError(message) {}
};

// A run that can no longer be trusted (NaN, divergence): carries the time and a diagnosis.
class SimulationError : public Error {
 public:
  SimulationError(double time, std::string diagnosis)
      : Error("t = " + std::to_string(time) + " s: " + diagnosis), time_(time) {}
  double time() const noexcept { return time_; }

 private:
  double time_;
};

// A result file that cannot be opened or written: "LinePlot::save_png: cannot write 'a/b.png': ...".
class OutputError : public Error {
 public:
  using Error::Error;
};

}  // namespace furniture_fem
