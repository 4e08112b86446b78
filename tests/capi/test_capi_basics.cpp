// Version, status names, the per-thread last error, contexts and their log callback.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "capi/capi_test_util.h"
#include "process_threads.h"

using namespace capi_test;
using mcon::test::process_thread_count;

TEST(CapiVersion, MatchesHeaderMacrosAndAcceptsNullPointers) {
  uint32_t major = 99, minor = 99, patch = 99;
  ASSERT_EQ(mcon_get_version(&major, &minor, &patch), MCON_OK);
  EXPECT_EQ(major, static_cast<uint32_t>(MCON_VERSION_MAJOR));
  EXPECT_EQ(minor, static_cast<uint32_t>(MCON_VERSION_MINOR));
  EXPECT_EQ(patch, static_cast<uint32_t>(MCON_VERSION_PATCH));
  EXPECT_EQ(major * 10000 + minor * 100 + patch, static_cast<uint32_t>(MCON_VERSION));
  // Any pointer may be NULL.
  uint32_t only_minor = 99;
  EXPECT_EQ(mcon_get_version(nullptr, &only_minor, nullptr), MCON_OK);
  EXPECT_EQ(only_minor, static_cast<uint32_t>(MCON_VERSION_MINOR));
  EXPECT_EQ(mcon_get_version(nullptr, nullptr, nullptr), MCON_OK);
}

TEST(CapiStatusNames, EveryCodeHasItsOwnName) {
  const std::vector<std::pair<mcon_status, const char*>> codes = {
      {MCON_OK, "MCON_OK"},
      {MCON_ERROR_UNKNOWN, "MCON_ERROR_UNKNOWN"},
      {MCON_ERROR_INVALID_ARGUMENT, "MCON_ERROR_INVALID_ARGUMENT"},
      {MCON_ERROR_NULL_POINTER, "MCON_ERROR_NULL_POINTER"},
      {MCON_ERROR_STRUCT_SIZE, "MCON_ERROR_STRUCT_SIZE"},
      {MCON_ERROR_OUT_OF_MEMORY, "MCON_ERROR_OUT_OF_MEMORY"},
      {MCON_ERROR_BUFFER_TOO_SMALL, "MCON_ERROR_BUFFER_TOO_SMALL"},
      {MCON_ERROR_CANCELLED, "MCON_ERROR_CANCELLED"},
      {MCON_ERROR_IO, "MCON_ERROR_IO"},
      {MCON_ERROR_NON_FINITE, "MCON_ERROR_NON_FINITE"},
      {MCON_ERROR_INDEX_OUT_OF_RANGE, "MCON_ERROR_INDEX_OUT_OF_RANGE"},
      {MCON_ERROR_REPEATED_INDEX, "MCON_ERROR_REPEATED_INDEX"},
      {MCON_ERROR_DEGENERATE_TRIANGLE, "MCON_ERROR_DEGENERATE_TRIANGLE"},
      {MCON_ERROR_NON_MANIFOLD_EDGE, "MCON_ERROR_NON_MANIFOLD_EDGE"},
      {MCON_ERROR_NON_MANIFOLD_VERTEX, "MCON_ERROR_NON_MANIFOLD_VERTEX"},
      {MCON_ERROR_ISOLATED_VERTEX, "MCON_ERROR_ISOLATED_VERTEX"},
      {MCON_ERROR_EMPTY_MESH, "MCON_ERROR_EMPTY_MESH"},
      {MCON_ERROR_NON_ORIENTABLE, "MCON_ERROR_NON_ORIENTABLE"},
      {MCON_ERROR_NOT_A_DISK, "MCON_ERROR_NOT_A_DISK"},
      {MCON_ERROR_NUMERICAL, "MCON_ERROR_NUMERICAL"},
      {MCON_ERROR_INVALID_LIBRARY, "MCON_ERROR_INVALID_LIBRARY"},
      {MCON_ERROR_UNSUPPORTED, "MCON_ERROR_UNSUPPORTED"},
      {MCON_ERROR_NOT_FOUND, "MCON_ERROR_NOT_FOUND"},
  };
  for (const auto& [code, expected] : codes) {
    const char* name = nullptr;
    ASSERT_EQ(mcon_get_status_name(code, &name), MCON_OK) << expected;
    ASSERT_NE(name, nullptr);
    EXPECT_STREQ(name, expected);
    // Static: the same pointer every time.
    const char* again = nullptr;
    mcon_get_status_name(code, &again);
    EXPECT_EQ(name, again);
  }
}

TEST(CapiStatusNames, RejectsUnknownCodesAndNullOutput) {
  const char* name = "untouched";
  EXPECT_EQ(mcon_get_status_name(MCON_OK, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("name"), std::string::npos) << last_message();
  for (int code : {9, 19, 33, 63}) {  // within the C++ enum range; c_api_check.c passes wilder ones
    EXPECT_EQ(mcon_get_status_name(static_cast<mcon_status>(code), &name), MCON_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_message().find(std::to_string(code)), std::string::npos) << last_message();
  }
}

TEST(CapiLastError, IsPerThreadKeptAfterSuccessAndNamesTheFunction) {
  EXPECT_EQ(mcon_context_options_init(nullptr), MCON_ERROR_NULL_POINTER);
  const char* message = nullptr;
  EXPECT_EQ(mcon_get_last_error(nullptr, &message), MCON_ERROR_NULL_POINTER);
  ASSERT_NE(message, nullptr);
  EXPECT_NE(std::string(message).find("mcon_context_options_init"), std::string::npos) << message;
  // Querying does not clear it; a later successful call does not either.
  uint32_t major = 0;
  EXPECT_EQ(mcon_get_version(&major, nullptr, nullptr), MCON_OK);
  EXPECT_EQ(mcon_get_last_error(nullptr, nullptr), MCON_ERROR_NULL_POINTER);
  // Another thread has its own (empty) slot, and its errors do not reach this thread.
  mcon_status other_status = MCON_ERROR_UNKNOWN, other_after = MCON_ERROR_UNKNOWN;
  std::string other_message = "untouched";
  std::thread([&] {
    const char* m = nullptr;
    other_status = mcon_get_last_error(nullptr, &m);
    other_message = m ? m : "<null>";
    mcon_context_create(nullptr, nullptr);
    other_after = mcon_get_last_error(nullptr, nullptr);
  }).join();
  EXPECT_EQ(other_status, MCON_OK);
  EXPECT_EQ(other_message, "");
  EXPECT_EQ(other_after, MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_get_last_error(nullptr, &message), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(std::string(message).find("mcon_context_options_init"), std::string::npos) << message;
}

TEST(CapiContext, CreatesWithDefaultsNullOptionsAndMaxThreads) {
  mcon_context_options o;
  std::memset(&o, 0xAB, sizeof(o));
  ASSERT_EQ(mcon_context_options_init(&o), MCON_OK);
  EXPECT_EQ(o.struct_size, sizeof(mcon_context_options));
  EXPECT_EQ(o.max_threads, 0u);
  EXPECT_EQ(o.log_callback, nullptr);
  EXPECT_EQ(o.log_user_data, nullptr);

  mcon_context c = nullptr;
  ASSERT_EQ(mcon_context_create(nullptr, &c), MCON_OK) << last_message();
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(mcon_context_release(c), MCON_OK);

  for (uint32_t threads : {1u, 2u, 3u, 64u, 4096u}) {
    o.max_threads = threads;
    c = nullptr;
    ASSERT_EQ(mcon_context_create(&o, &c), MCON_OK) << threads << ": " << last_message();
    // The context works: a mesh can be made in it.
    MeshPtr m = make_mesh(c, arrays_of(mcon::test_meshes::make_grid(4)));
    EXPECT_NE(m, nullptr);
    m.reset();
    EXPECT_EQ(mcon_context_release(c), MCON_OK);
  }
}

TEST(CapiContext, RejectsBadOptions) {
  mcon_context_options o;
  ASSERT_EQ(mcon_context_options_init(&o), MCON_OK);
  mcon_context c = reinterpret_cast<mcon_context>(&o);
  o.max_threads = 4097;
  EXPECT_EQ(mcon_context_create(&o, &c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(c, nullptr);
  EXPECT_NE(last_message().find("max_threads 4097"), std::string::npos) << last_message();
  o.max_threads = 0xFFFFFFFFu;
  EXPECT_EQ(mcon_context_create(&o, &c), MCON_ERROR_INVALID_ARGUMENT);
  o.max_threads = 0;
  EXPECT_EQ(mcon_context_create(&o, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("out_context"), std::string::npos) << last_message();
  for (uint32_t size : {0u, 4u, static_cast<uint32_t>(sizeof(o) - 1)}) {
    o.struct_size = size;
    EXPECT_EQ(mcon_context_create(&o, &c), MCON_ERROR_STRUCT_SIZE) << size;
    EXPECT_NE(last_message().find("struct_size is " + std::to_string(size)), std::string::npos) << last_message();
  }
}

TEST(CapiContext, AcceptsLargerStructFromNewerHeader) {
  struct Newer {
    mcon_context_options v1;
    uint64_t future_field;
  } newer;
  ASSERT_EQ(mcon_context_options_init(&newer.v1), MCON_OK);
  newer.v1.struct_size = sizeof(Newer);
  newer.v1.max_threads = 2;
  newer.future_field = 0xDEADBEEF;
  mcon_context c = nullptr;
  ASSERT_EQ(mcon_context_create(&newer.v1, &c), MCON_OK) << last_message();
  EXPECT_EQ(mcon_context_release(c), MCON_OK);
}

TEST(CapiContext, RetainReleaseCountAndRejectBadHandles) {
  mcon_context c = nullptr;
  ASSERT_EQ(mcon_context_create(nullptr, &c), MCON_OK);
  EXPECT_EQ(mcon_context_retain(c), MCON_OK);
  EXPECT_EQ(mcon_context_release(c), MCON_OK);
  // Still alive after one release: one reference is left.
  MeshPtr m = make_mesh(c, arrays_of(mcon::test_meshes::make_grid(3)));
  EXPECT_NE(m, nullptr);
  // The mesh keeps the context alive after the caller's last release.
  EXPECT_EQ(mcon_context_release(c), MCON_OK);
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(m.get(), &nv, &nt), MCON_OK);
  EXPECT_EQ(nv, 9u);
  m.reset();

  EXPECT_EQ(mcon_context_retain(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_context_release(nullptr), MCON_OK);  // releasing NULL is a no-op
  Garbage g;
  EXPECT_EQ(mcon_context_retain(reinterpret_cast<mcon_context>(&g)), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_context_release(reinterpret_cast<mcon_context>(&g)), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("not a valid context"), std::string::npos) << last_message();
  // A mesh handle passed as a context is caught by the magic tag.
  ContextPtr ctx = make_context();
  MeshPtr mesh = make_mesh(ctx.get(), arrays_of(mcon::test_meshes::make_grid(3)));
  EXPECT_EQ(mcon_context_retain(reinterpret_cast<mcon_context>(mesh.get())), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_context_release(reinterpret_cast<mcon_context>(mesh.get())), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_mesh_get_counts(mesh.get(), &nv, &nt), MCON_OK);  // and nothing happened to it
}

// A released handle is recognized without reading the freed object (the registry of live
// handles): under AddressSanitizer the old magic-tag check was a heap-use-after-free here.
TEST(CapiContext, ReleasedHandlesAreErrorsWithoutTouchingFreedMemory) {
  mcon_context c = nullptr;
  ASSERT_EQ(mcon_context_create(nullptr, &c), MCON_OK);
  mcon_mesh m = make_mesh(c, arrays_of(mcon::test_meshes::make_grid(3))).release();
  ASSERT_EQ(mcon_mesh_release(m), MCON_OK);  // freed
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(m, &nv, &nt), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("already released"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_mesh_release(m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_context_release(c), MCON_OK);
  EXPECT_EQ(mcon_context_release(c), MCON_ERROR_INVALID_ARGUMENT);
}

// The caller's references and those SDK objects hold are counted apart: releasing a context more
// often than it was created and retained is an error even while a mesh still keeps it alive.
TEST(CapiContext, OverReleaseIsAnErrorWhileAnotherObjectHoldsTheHandle) {
  mcon_context c = nullptr;
  ASSERT_EQ(mcon_context_create(nullptr, &c), MCON_OK);
  MeshPtr m = make_mesh(c, arrays_of(mcon::test_meshes::make_grid(3)));
  ASSERT_EQ(mcon_context_release(c), MCON_OK);  // the caller's only reference
  EXPECT_EQ(mcon_context_release(c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("released"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_context_retain(c), MCON_ERROR_INVALID_ARGUMENT);  // the caller gave it up
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(m.get(), &nv, &nt), MCON_OK);  // the mesh's reference is intact
  EXPECT_EQ(nv, 9u);
}

namespace {

struct LogRecord {
  std::vector<std::pair<mcon_status, std::string>> entries;
};

void record_log(void* user, mcon_status status, const char* message) {
  static_cast<LogRecord*>(user)->entries.emplace_back(status, message ? message : "<null>");
}

}  // namespace

TEST(CapiContext, LogCallbackReceivesErrorsOfItsObjects) {
  LogRecord log;
  mcon_context_options o;
  ASSERT_EQ(mcon_context_options_init(&o), MCON_OK);
  o.log_callback = record_log;
  o.log_user_data = &log;
  mcon_context raw = nullptr;
  ASSERT_EQ(mcon_context_create(&o, &raw), MCON_OK);
  ContextPtr ctx(raw);

  Arrays a = arrays_of(mcon::test_meshes::make_grid(4));
  a.positions[3 * 5 + 1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(create_status(ctx.get(), a), MCON_ERROR_NON_FINITE);
  ASSERT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.entries[0].first, MCON_ERROR_NON_FINITE);
  EXPECT_EQ(log.entries[0].second, last_message());
  EXPECT_NE(log.entries[0].second.find("vertex 5"), std::string::npos) << log.entries[0].second;

  // An error on an object of the context goes to the same log.
  MeshPtr m = make_mesh(ctx.get(), arrays_of(mcon::test_meshes::make_grid(4)));
  size_t nv = 0;
  EXPECT_EQ(mcon_mesh_get_counts(m.get(), &nv, nullptr), MCON_ERROR_NULL_POINTER);
  ASSERT_EQ(log.entries.size(), 2u);
  EXPECT_EQ(log.entries[1].first, MCON_ERROR_NULL_POINTER);
  EXPECT_NE(log.entries[1].second.find("triangle_count"), std::string::npos) << log.entries[1].second;

  // Errors without a context (here: a NULL context) are not logged anywhere, and no crash.
  EXPECT_EQ(create_status(nullptr, a), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(log.entries.size(), 2u);
  // Successful calls log nothing.
  EXPECT_NE(make_mesh(ctx.get(), arrays_of(mcon::test_meshes::make_grid(3))), nullptr);
  EXPECT_EQ(log.entries.size(), 2u);
}

namespace {

// Parallel work in the process's TBB scheduler (the one the library shares), so workers exist.
void spin_up_workers() {
  tbb::task_arena arena;
  arena.execute([] {
    tbb::parallel_for(0, 512, [](int i) {
      volatile double x = i;
      for (int k = 0; k < 20000; ++k) x = x * 1.0000001 + 1e-9;
    });
  });
}

}  // namespace

TEST(CapiShutdown, RefusesWhileObjectsLiveThenJoinsEveryWorker) {
  ContextPtr ctx = make_context();
  MeshPtr mesh = make_mesh(ctx.get(), arrays_of(mcon::test_meshes::make_grid(4)));
  spin_up_workers();
  EXPECT_GT(process_thread_count(), 1) << "no TBB worker started: the test below proves nothing";
  EXPECT_EQ(mcon_shutdown(), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("1 context(s) still alive"), std::string::npos) << last_message();
  ctx.reset();  // the mesh still holds the context
  EXPECT_EQ(mcon_shutdown(), MCON_ERROR_INVALID_ARGUMENT);
  mesh.reset();
  ASSERT_EQ(mcon_shutdown(), MCON_OK) << last_message();
  EXPECT_EQ(process_thread_count(), 1) << "mcon_shutdown returned before the workers exited";
  EXPECT_EQ(mcon_shutdown(), MCON_OK);  // again: nothing to do
  // The library works again, and the next shutdown waits again.
  ctx = make_context(2);
  EXPECT_NE(make_mesh(ctx.get(), arrays_of(mcon::test_meshes::make_grid(4))), nullptr);
  ctx.reset();
  spin_up_workers();
  EXPECT_GT(process_thread_count(), 1);
  ASSERT_EQ(mcon_shutdown(), MCON_OK) << last_message();
  EXPECT_EQ(process_thread_count(), 1);
}

TEST(CapiShutdown, FailsWhileTbbIsBusyAndStillWaitsWhenCalledAgain) {
  ContextPtr ctx = make_context();
  ctx.reset();
  // Another thread of the host is in the middle of parallel work.
  std::atomic<bool> started{false}, stop{false};
  std::thread busy([&] {
    tbb::task_arena arena;
    arena.execute([&] {
      tbb::parallel_for(0, 64, [&](int) {
        started = true;
        while (!stop) std::this_thread::yield();
      });
    });
  });
  while (!started) std::this_thread::yield();
  const mcon_status during = mcon_shutdown();
  const std::string message = last_message();
  stop = true;
  busy.join();
  EXPECT_EQ(during, MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find("still in use"), std::string::npos) << message;
  // The failed call must not have dropped the scheduler reference: this one still joins workers.
  ASSERT_EQ(mcon_shutdown(), MCON_OK) << last_message();
  EXPECT_EQ(process_thread_count(), 1) << "the second mcon_shutdown did not wait for the workers";
}
