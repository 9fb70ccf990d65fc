#pragma once
// The message of the arcplan::Error an action throws, for tests that check what an error says.
#include <functional>
#include <string>

#include "arcplan/common/error.h"

namespace arcplan::testing {

// "(no error)" when the action does not throw; other exception types propagate (and fail the test).
inline std::string errorMessageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const arcplan::Error& error) {
    return error.what();
  }
  return "(no error)";
}

}  // namespace arcplan::testing
