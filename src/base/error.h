// Internal error type: every failure in the core throws mcon::Error carrying the C status code,
// and the C API boundary turns it into a status + per-thread message (src/capi/capi_common.h).
#pragma once

#include <stdexcept>
#include <string>

#include "macrocon/macrocon.h"

namespace mcon {

class Error : public std::runtime_error {
 public:
  Error(mcon_status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  mcon_status status() const noexcept { return status_; }

 private:
  mcon_status status_;
};

// "MCON_ERROR_NOT_A_DISK" etc.; nullptr for an unknown code.
const char* status_name(mcon_status status);

[[noreturn]] inline void fail(mcon_status status, const std::string& message) { throw Error(status, message); }

inline void require(bool condition, mcon_status status, const std::string& message) {
  if (!condition) fail(status, message);
}

}  // namespace mcon
