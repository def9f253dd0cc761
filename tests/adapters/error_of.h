// Test helper shared by the adapter tests: the message of the InputError a call throws.
#pragma once

#include "unidist/types.h"

#include <gtest/gtest.h>

#include <exception>
#include <string>

namespace unidist::testing {

/// Runs f, expects InputError, and returns its message ("" and a failure otherwise).
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw a non-InputError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "did not throw";
  return "";
}

}  // namespace unidist::testing
