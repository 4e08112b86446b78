// Version, errors, shutdown and the context.
#include <algorithm>
#include <mutex>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include "capi/capi_handles.h"

namespace mcon::capi {
namespace {

std::mutex& scheduler_mutex() {
  static std::mutex m;
  return m;
}

// A reference to TBB's scheduler, taken when the first context is created, so mcon_shutdown can
// wait for the worker threads (docs/design.md §5: Mono crashed at exit without it).
tbb::task_scheduler_handle& scheduler_handle() {
  static tbb::task_scheduler_handle handle;
  return handle;
}

// Contexts alive (created and not yet destroyed). mcon_shutdown refuses while any lives: TBB
// alone cannot tell (an arena that never ran work does not stop finalize), and a context that
// outlived a shutdown would start workers nobody waits for.
std::atomic<long>& live_contexts() {
  static std::atomic<long> count{0};
  return count;
}

}  // namespace

LastError& thread_last_error() {
  thread_local LastError error;
  return error;
}

mcon_status set_error(mcon_status status, const std::string& message, mcon_context context) noexcept {
  LastError& e = thread_last_error();
  e.status = status;
  try {
    e.message = message;
  } catch (...) {  // out of memory while reporting: keep the status, drop the text
    e.message.clear();
  }
  if (context != nullptr && context->header.magic == mcon_context_t::kMagic &&
      context->options.log_callback != nullptr) {
    try {
      context->options.log_callback(context->options.log_user_data, status, e.message.c_str());
    } catch (...) {  // a C++ callback that throws must not cross the C boundary
    }
  }
  return status;
}

void require_capacity(std::size_t capacity, std::size_t needed, const char* name) {
  require(capacity >= needed, MCON_ERROR_BUFFER_TOO_SMALL,
          std::string(name) + " holds " + std::to_string(capacity) + " elements, " + std::to_string(needed) +
              " are needed");
}

namespace {

struct ProgressState {
  mcon_progress_callback callback;
  void* user;
  std::mutex mutex;
  double last = 0;
  std::atomic<bool> cancelled{false};
};

}  // namespace

std::function<bool(double)> make_progress(mcon_progress_callback callback, void* user,
                                          std::shared_ptr<const std::atomic<bool>>* cancelled) {
  if (cancelled) *cancelled = nullptr;
  if (callback == nullptr) return {};
  auto state = std::make_shared<ProgressState>();
  state->callback = callback;
  state->user = user;
  if (cancelled) *cancelled = std::shared_ptr<const std::atomic<bool>>(state, &state->cancelled);
  return [state](double fraction) {
    if (state->cancelled.load()) return false;
    std::lock_guard<std::mutex> lock(state->mutex);
    if (state->cancelled.load()) return false;
    // NaN compares false: it reports the last fraction again.
    if (fraction > state->last) state->last = std::min(fraction, 1.0);
    if (state->callback(state->user, state->last) == 0) state->cancelled.store(true);
    return !state->cancelled.load();
  };
}

}  // namespace mcon::capi

using namespace mcon;
using namespace mcon::capi;

mcon_context_t::mcon_context_t() { ++live_contexts(); }

mcon_context_t::~mcon_context_t() {
  arena.reset();  // the arena goes first, then the context stops counting as alive
  --live_contexts();
}

extern "C" {

mcon_status mcon_get_version(uint32_t* major, uint32_t* minor, uint32_t* patch) {
  if (major) *major = MCON_VERSION_MAJOR;
  if (minor) *minor = MCON_VERSION_MINOR;
  if (patch) *patch = MCON_VERSION_PATCH;
  return MCON_OK;
}

mcon_status mcon_get_status_name(mcon_status status, const char** name) {
  return guard("mcon_get_status_name", [&] {
    require_pointer(name, "name");
    const std::int32_t code = enum_bits(status);
    // 0..63 is the value range of the C++ enum; beyond it no code exists.
    *name = code >= 0 && code <= 63 ? mcon::status_name(static_cast<mcon_status>(code)) : nullptr;
    if (*name != nullptr) return;
    fail(MCON_ERROR_INVALID_ARGUMENT, "unknown status code " + std::to_string(code));
  });
}

mcon_status mcon_get_last_error(mcon_context /*context*/, const char** message) {
  // Errors are kept per thread, whichever context raised them; `context` may be NULL.
  const auto& e = mcon::capi::thread_last_error();
  if (message) *message = e.message.c_str();
  return e.status;
}

mcon_status mcon_shutdown(void) {
  return guard("mcon_shutdown", [&] {
    std::lock_guard<std::mutex> lock(scheduler_mutex());
    const long alive = live_contexts().load();
    require(alive == 0, MCON_ERROR_INVALID_ARGUMENT,
            std::to_string(alive) + " context(s) still alive: release every context, mesh and patch first "
            "(objects keep their context alive)");
    // The scheduler reference is taken here, not when contexts are created: taking it while
    // another thread initializes a task arena (a host's own TBB work) deadlocked inside oneTBB
    // 2021.8 (seen: 2 runs in 8 of capi.exit_clean_after_parallel_work). Here no SDK work runs.
    auto& handle = scheduler_handle();
    if (!handle) handle = tbb::task_scheduler_handle(tbb::attach{});
    // Blocks until TBB's workers have exited; fails while TBB is still in use in this process
    // (e.g. by the host's own parallel work). finalize() empties the handle either way.
    if (tbb::finalize(handle, std::nothrow)) return;
    fail(MCON_ERROR_INVALID_ARGUMENT,
         "TBB worker threads are still in use in this process (parallel work still running); call again "
         "once it has finished");
  });
}

mcon_status mcon_context_options_init_sized(mcon_context_options* options, size_t struct_size) {
  return init_struct("mcon_context_options_init_sized", options, struct_size, sizeof(mcon_context_options), "options",
                     zeroed_struct<mcon_context_options>());
}

mcon_status mcon_context_create(const mcon_context_options* options, mcon_context* out_context) {
  return guard("mcon_context_create", [&] {
    require_pointer(out_context, "out_context");
    *out_context = nullptr;
    auto defaults = zeroed_struct<mcon_context_options>();
    const auto opts = read_options(options, sizeof(mcon_context_options), "mcon_context_options", defaults);
    require(opts.max_threads <= 4096, MCON_ERROR_INVALID_ARGUMENT,
            "max_threads " + std::to_string(opts.max_threads) + " is out of range (0 = all, at most 4096)");
    // A cap above the hardware is no cap (and would only allocate unused arena slots).
    const int hardware = tbb::info::default_concurrency();
    const int threads = opts.max_threads == 0 ? hardware : std::min(hardware, static_cast<int>(opts.max_threads));
    auto ctx = std::make_unique<mcon_context_t>();
    ctx->options = opts;
    ctx->arena = std::make_unique<tbb::task_arena>(threads);
    ctx->arena->initialize();
    *out_context = ctx.release();
  });
}

mcon_status mcon_context_retain(mcon_context context) {
  return guard("mcon_context_retain", [&] { retain(context, "context"); });
}

mcon_status mcon_context_release(mcon_context context) {
  return guard("mcon_context_release", [&] { release(context, "context"); });
}

}  // extern "C"
