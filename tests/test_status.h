// The mcon::Error status (and message) a call throws, or MCON_OK: how tests check error paths.
#pragma once

#include <string>
#include <utility>

#include "base/error.h"

namespace mcon::test {

// Runs f(); returns the status of the mcon::Error it throws (its message into *message), or
// MCON_OK if it throws none.
template <typename F>
mcon_status status_of(F&& f, std::string* message = nullptr) {
  try {
    std::forward<F>(f)();
  } catch (const Error& e) {
    if (message) *message = e.what();
    return e.status();
  }
  return MCON_OK;
}

}  // namespace mcon::test
