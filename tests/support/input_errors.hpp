#pragma once
// The message of a named input error, for tests that check what a user would read.
#include <furniture_fem/core/errors.hpp>

#include <string>

namespace ffem_test {

// The message of the InputError f() throws, or "no error".
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const furniture_fem::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace ffem_test
