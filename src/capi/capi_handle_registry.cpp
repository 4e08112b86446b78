// The set of live handle objects (capi_common.h). One mutex: every entry point looks a handle
// up once, which is cheap next to the work behind it.
#include <mutex>
#include <unordered_set>

#include "capi/capi_common.h"

namespace mcon::capi {

namespace {

struct Registry {
  std::mutex mutex;
  std::unordered_set<const void*> live;
};

// Never destroyed: handles may be released from static destructors of the host after ours ran.
Registry& registry() {
  static Registry* r = new Registry;
  return *r;
}

}  // namespace

void register_handle(const void* header) {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.live.insert(header);  // std::bad_alloc fails the creating call with MCON_ERROR_OUT_OF_MEMORY
}

void unregister_handle(const void* header) noexcept {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.live.erase(header);
}

bool handle_is_live(const void* header) noexcept {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  return r.live.count(header) > 0;
}

}  // namespace mcon::capi
