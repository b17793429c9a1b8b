// The one error type of the project. Library code throws it for bad input and for
// environment failures; the command line catches it, prints "bluetile: <what>" and exits 1.
#pragma once

#include <stdexcept>
#include <string>

namespace bluetile {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace bluetile
