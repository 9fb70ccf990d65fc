#pragma once
// The one exception type arcplan throws for bad input or an impossible request. Its message is
// meant for the user: it names the file, line or field and what was expected. The command-line
// tool prints it on one line and exits non-zero.
#include <stdexcept>
#include <string>

namespace arcplan {

class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace arcplan
