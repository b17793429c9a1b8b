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

// A write to a pipe or FIFO whose reader has gone (EPIPE), as in `bluetile relax -o - | head`.
// A pipeline's writer is expected to stop quietly there: the command line exits 141 without a
// message (the status a shell reports for a writer ended by SIGPIPE). Staged outputs are still
// discarded.
class ReaderGone : public Error {
 public:
  using Error::Error;
};

}  // namespace bluetile
