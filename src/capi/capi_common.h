// Shared machinery of the C API: handle objects with reference counts and a magic tag, the
// catch-all that turns exceptions into status codes, the per-thread last error, and reading
// versioned options structs. Every mcon_* entry point is written as
//   return mcon::capi::guard("mcon_x", [&] { ... });
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <algorithm>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>

#include "base/error.h"
#include "macrocon/macrocon.h"

namespace mcon::capi {

struct LastError {
  mcon_status status = MCON_OK;
  std::string message;
};
LastError& thread_last_error();

// Records an error for the calling thread and forwards it to the log callback of `context` (if
// not NULL: callers pass a context only once its handle has been validated). Never throws.
mcon_status set_error(mcon_status status, const std::string& message, mcon_context context = nullptr) noexcept;

// set_error with the message "<function>: <prefix><detail>". Building the message allocates: when
// memory has run out that can fail too, and the status is then recorded with an empty message,
// because nothing may throw out of a noexcept entry point (it would terminate the host).
inline mcon_status report_error(mcon_status status, const char* function, const char* prefix, const char* detail,
                                mcon_context context) noexcept {
  try {
    return set_error(status, std::string(function) + ": " + prefix + detail, context);
  } catch (...) {
    static const std::string no_message;
    return set_error(status, no_message, context);
  }
}

// Runs `body`; maps mcon::Error, std::bad_alloc (MCON_ERROR_OUT_OF_MEMORY) and any other
// exception to a status code, and never throws itself. `log_context` is read only after `body`
// failed, so a body may set it once it has validated the handle that leads to the context
// (errors are then also sent to that context's log callback).
template <typename F>
mcon_status guard(const char* function, F&& body, const mcon_context& log_context = nullptr) noexcept {
  try {
    body();
    return MCON_OK;
  } catch (const Error& e) {
    return report_error(e.status(), function, "", e.what(), log_context);
  } catch (const std::bad_alloc&) {
    return report_error(MCON_ERROR_OUT_OF_MEMORY, function, "out of memory", "", log_context);
  } catch (const std::exception& e) {
    return report_error(MCON_ERROR_UNKNOWN, function, "internal error: ", e.what(), log_context);
  } catch (...) {
    return report_error(MCON_ERROR_UNKNOWN, function, "internal error", "", log_context);
  }
}

// The registry of live handle objects: check_handle asks it before it reads anything behind a
// handle, so a released (freed) or made-up handle is an error, not a read of freed memory.
// Handles are plain pointers, so a new object at a freed one's address is found again (the
// registry cannot tell them apart); docs/api.md says so.
void register_handle(const void* header);  // may throw std::bad_alloc
void unregister_handle(const void* header) noexcept;
bool handle_is_live(const void* header) noexcept;

// Every handle object starts with this header: a type tag and two reference counts in one
// atomic word. The low 32 bits count the caller's references (create and mcon_*_retain minus
// mcon_*_release), the high 32 bits the references other SDK objects hold (a map on its
// patches, every object on its context). The object lives while either is non-zero, and a
// caller's release beyond its own references is an error instead of freeing what a map holds.
struct HandleHeader {
  static constexpr std::uint64_t kCallerMask = 0xFFFFFFFFu;
  static constexpr std::uint64_t kOwnerUnit = std::uint64_t{1} << 32;
  std::uint32_t magic;
  std::atomic<std::uint64_t> references{1};
  explicit HandleHeader(std::uint32_t m) : magic(m) { register_handle(this); }
  ~HandleHeader() { unregister_handle(this); }
  HandleHeader(const HandleHeader&) = delete;
  HandleHeader& operator=(const HandleHeader&) = delete;
  std::uint64_t caller_references() const { return references.load() & kCallerMask; }
};

template <typename T>
T* check_handle(T* handle, const char* what) {
  require(handle != nullptr, MCON_ERROR_NULL_POINTER, std::string(what) + " handle is NULL");
  require(handle_is_live(&handle->header) && handle->header.magic == T::kMagic &&
              handle->header.caller_references() > 0,
          MCON_ERROR_INVALID_ARGUMENT,
          std::string(what) + " handle is not a valid " + what + " (wrong type or already released)");
  return handle;
}

// mcon_*_retain: one more caller reference.
template <typename T>
void retain(T* handle, const char* what) {
  check_handle(handle, what)->header.references.fetch_add(1);
}

// mcon_*_release: drops one caller reference, frees the object when nothing holds it any more.
template <typename T>
void release(T* handle, const char* what) {
  if (handle == nullptr) return;
  check_handle(handle, what);
  std::uint64_t v = handle->header.references.load();
  do {
    require((v & HandleHeader::kCallerMask) > 0, MCON_ERROR_INVALID_ARGUMENT,
            std::string(what) + " handle was released more often than it was created and retained");
  } while (!handle->header.references.compare_exchange_weak(v, v - 1));
  if (v - 1 == 0) {
    handle->header.magic = 0;
    delete handle;
  }
}

// A reference an SDK object takes on another one it keeps (the handle was validated by the
// caller's entry point), and its release in the keeper's destructor.
template <typename T>
void retain_owned(T* handle) noexcept {
  handle->header.references.fetch_add(HandleHeader::kOwnerUnit);
}

template <typename T>
void release_owned(T* handle) noexcept {
  if (handle != nullptr && handle->header.references.fetch_sub(HandleHeader::kOwnerUnit) == HandleHeader::kOwnerUnit) {
    handle->header.magic = 0;
    delete handle;
  }
}

template <typename T>
void require_pointer(const T* p, const char* name) {
  require(p != nullptr, MCON_ERROR_NULL_POINTER, std::string(name) + " is NULL");
}

// Reads a caller's options struct: struct_size must cover at least the first published version
// (`min_size`); fields beyond what the caller's struct_size covers keep their defaults.
template <typename T>
T read_options(const T* user, std::size_t min_size, const char* name, const T& defaults) {
  static_assert(std::is_trivially_copyable_v<T>, "options must be plain structs");
  T out = defaults;
  if (user == nullptr) return out;
  require(user->struct_size >= min_size, MCON_ERROR_STRUCT_SIZE,
          std::string(name) + ".struct_size is " + std::to_string(user->struct_size) + ", expected at least " +
              std::to_string(min_size) + " (call the matching _init function)");
  std::memcpy(&out, user, std::min<std::size_t>(user->struct_size, sizeof(T)));
  out.struct_size = static_cast<std::uint32_t>(sizeof(T));
  return out;
}

// Writes an output info struct: only the bytes the caller's struct_size covers.
template <typename T>
void write_info(T* user, std::size_t min_size, const char* name, const T& value) {
  require_pointer(user, name);
  require(user->struct_size >= min_size, MCON_ERROR_STRUCT_SIZE,
          std::string(name) + ".struct_size is " + std::to_string(user->struct_size) + ", expected at least " +
              std::to_string(min_size) + " (call the matching _init function)");
  const std::uint32_t caller_size = user->struct_size;
  std::memcpy(user, &value, std::min<std::size_t>(caller_size, sizeof(T)));
  user->struct_size = caller_size;
}

// The integer a C caller passed for an enum parameter. C enums are plain ints, so any value may
// arrive; reading the bytes avoids loading an out-of-range value as the C++ enum type (which is
// undefined behaviour, and UBSan reports it).
template <typename E>
std::int32_t enum_bits(const E& value) {
  static_assert(std::is_enum_v<E> && sizeof(E) == sizeof(std::int32_t), "a 32-bit C enum");
  std::int32_t raw;
  std::memcpy(&raw, &value, sizeof raw);
  return raw;
}

void require_capacity(std::size_t capacity, std::size_t needed, const char* name);

// A versioned struct with every field zero but struct_size (what an *_info_init writes).
template <typename T>
T zeroed_struct() {
  T value{};
  value.struct_size = sizeof(T);
  return value;
}

// Largest struct_size an mcon_*_init_sized accepts: far above any struct's size (all are under
// 200 bytes) yet small enough that a wrong value (a count, a pointer) is refused, not zeroed into.
constexpr std::size_t kMaxStructSize = 4096;

// The whole body of an mcon_*_init_sized function. `out` (called `name` in the message) must not
// be NULL and `size`, the caller's sizeof, must cover the first published version (`min_size`).
// Only `size` bytes are written: a struct from an older header gets the defaults of the fields it
// has, one from a newer header (larger than this library's) gets zeros beyond the fields this
// library knows, which it never reads (docs/api.md "Growing structs").
template <typename T>
mcon_status init_struct(const char* function, T* out, std::size_t size, std::size_t min_size, const char* name,
                        const T& defaults) noexcept {
  static_assert(std::is_trivially_copyable_v<T>, "options and info must be plain structs");
  return guard(function, [&] {
    require_pointer(out, name);
    require(size >= min_size && size <= kMaxStructSize, MCON_ERROR_STRUCT_SIZE,
            std::string(name) + " struct_size " + std::to_string(size) + " is outside [" +
                std::to_string(min_size) + ", " + std::to_string(kMaxStructSize) +
                "]; pass sizeof the struct (the inline *_init in macrocon.h does)");
    unsigned char* bytes = reinterpret_cast<unsigned char*>(out);
    std::memcpy(bytes, &defaults, std::min(size, sizeof(T)));
    if (size > sizeof(T)) std::memset(bytes + sizeof(T), 0, size - sizeof(T));
    const auto caller_size = static_cast<std::uint32_t>(size);
    std::memcpy(bytes + offsetof(T, struct_size), &caller_size, sizeof caller_size);
  });
}

// Copies `rows` (fixed-size rows: positions, uv, index triples) row after row into the caller's
// flat array `out` of N values per row, after (when there is a row) the NULL check (`name`) and the capacity check
// (`capacity_name` says in which unit, e.g. "out_xyz (capacity in doubles)").
template <int N, typename Out, typename Rows>
void write_rows(const Rows& rows, Out* out, std::size_t capacity, const char* name, const char* capacity_name) {
  if (rows.empty()) return;  // nothing to write: NULL is fine (an empty std::vector's data())
  require_pointer(out, name);
  require_capacity(capacity, N * rows.size(), capacity_name);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (int k = 0; k < N; ++k) out[N * r + k] = static_cast<Out>(rows[r][k]);
}

// Turns a C progress callback into the core's std::function (null when no callback). The
// function serializes calls (the header promises never two at once), clamps the fraction to
// [0, 1] and never lets it go backwards, and once the caller cancelled it keeps answering
// "cancel" without calling again. `cancelled`, if given, reports whether the caller cancelled
// (so a core routine that ignores the answer still ends in MCON_ERROR_CANCELLED).
std::function<bool(double)> make_progress(mcon_progress_callback callback, void* user,
                                          std::shared_ptr<const std::atomic<bool>>* cancelled = nullptr);

}  // namespace mcon::capi
