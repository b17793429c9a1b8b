// A way for a caller to end a long library call early: while a CancelCheck lives on a thread, the
// library's long loops call its function now and then on that thread (parallel_for between the
// chunks the calling thread runs, sequential loops at cancellation_point()), and whatever it
// throws ends the call as an error of the loop would, leaving the caller's data as an error
// leaves it. The Python module ends a call on Ctrl-C this way (KeyboardInterrupt); the tool needs
// none, since SIGINT ends it.
#pragma once

#include <functional>

namespace bluetile {

class CancelCheck {
 public:
  // `check` runs on the thread that made this object, at most as often as the loops reach a
  // cancellation point; it should be cheap when it has nothing to do.
  explicit CancelCheck(std::function<void()> check);
  ~CancelCheck();
  CancelCheck(const CancelCheck&) = delete;
  CancelCheck& operator=(const CancelCheck&) = delete;

 private:
  std::function<void()> check_;
  const std::function<void()>* previous_;
};

// Calls the check of this thread's innermost CancelCheck, if any (a thread-local load otherwise).
void cancellation_point();

}  // namespace bluetile
