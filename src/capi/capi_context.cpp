// Version, errors, shutdown and the context.
#include <mutex>
#include <thread>

#include <oneapi/tbb/global_control.h>

#include "capi_handles.h"

namespace mcon::capi {
namespace {


std::mutex& scheduler_mutex() {
  static std::mutex m;
  return m;
}

// A reference to TBB's scheduler, taken when the first context is created, so mcon_shutdown can
// wait for the worker threads (design-notes §5: Mono crashed at exit without it).
tbb::task_scheduler_handle& scheduler_handle() {
  static tbb::task_scheduler_handle handle;
  return handle;
}

}  // namespace

LastError& thread_last_error() {
  thread_local LastError error;
  return error;
}

mcon_status set_error(mcon_status status, const std::string& message, mcon_context context) {
  LastError& e = thread_last_error();
  e.status = status;
  e.message = message;
  if (context != nullptr && context->options.log_callback != nullptr)
    context->options.log_callback(context->options.log_user_data, status, e.message.c_str());
  return status;
}

void require_capacity(std::size_t capacity, std::size_t needed, const char* name) {
  require(capacity >= needed, MCON_ERROR_BUFFER_TOO_SMALL,
          std::string(name) + " holds " + std::to_string(capacity) + " elements, " + std::to_string(needed) +
              " are needed");
}

std::function<bool(double)> make_progress(mcon_progress_callback callback, void* user) {
  if (callback == nullptr) return {};
  return [callback, user](double fraction) { return callback(user, fraction) != 0; };
}

}  // namespace mcon::capi

using namespace mcon;
using namespace mcon::capi;

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
    *name = mcon::status_name(status);
    if (*name != nullptr) return;
    fail(MCON_ERROR_INVALID_ARGUMENT, "unknown status code " + std::to_string(static_cast<int>(status)));
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
    auto& handle = scheduler_handle();
    if (!handle) return;
    // Blocks until TBB's workers have exited; fails while any context (arena) is still alive.
    require(tbb::finalize(handle, std::nothrow), MCON_ERROR_INVALID_ARGUMENT,
            "worker threads are still in use: release every context (and wait for running calls) first");
  });
}

mcon_status mcon_context_options_init(mcon_context_options* options) {
  return guard("mcon_context_options_init", [&] {
    require_pointer(options, "options");
    *options = mcon_context_options{};
    options->struct_size = sizeof(mcon_context_options);
  });
}

mcon_status mcon_context_create(const mcon_context_options* options, mcon_context* out_context) {
  return guard("mcon_context_create", [&] {
    require_pointer(out_context, "out_context");
    *out_context = nullptr;
    mcon_context_options defaults{};
    defaults.struct_size = sizeof(mcon_context_options);
    const auto opts = read_options(options, sizeof(mcon_context_options), "mcon_context_options", defaults);
    require(opts.max_threads <= 4096, MCON_ERROR_INVALID_ARGUMENT,
            "max_threads " + std::to_string(opts.max_threads) + " is out of range (0 = all, at most 4096)");
    {
      std::lock_guard<std::mutex> lock(scheduler_mutex());
      auto& handle = scheduler_handle();
      if (!handle) handle = tbb::task_scheduler_handle(tbb::attach{});
    }
    auto ctx = std::make_unique<mcon_context_t>();
    ctx->options = opts;
    const int threads = opts.max_threads == 0 ? tbb::task_arena::automatic : static_cast<int>(opts.max_threads);
    ctx->arena = std::make_unique<tbb::task_arena>(threads);
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
