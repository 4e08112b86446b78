// Running out of memory inside C API calls: this test binary replaces the global operator new
// with one that, once armed, refuses every allocation from the N-th on (so reporting the error
// cannot allocate either), and sweeps N over each call's allocations. Every call must then return
// MCON_ERROR_OUT_OF_MEMORY, or MCON_OK when it needed fewer allocations, and never terminate the
// process (an exception escaping a noexcept entry point would). The library links libstdc++
// dynamically, so its allocations come here too.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "capi/capi_test_util.h"

namespace {

std::atomic<bool> g_armed{false};
std::atomic<long> g_count{0};
std::atomic<long> g_fail_from{0};
std::atomic<bool> g_refused{false};

void* allocate(std::size_t size) {
  if (g_armed.load(std::memory_order_relaxed) && g_count.fetch_add(1) >= g_fail_from.load()) {
    g_refused.store(true);
    throw std::bad_alloc();
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

using namespace capi_test;

namespace {

struct Run {
  mcon_status status;
  bool refused;  // an allocation was refused during the call
  long allocations;
};

Run run_failing_from(long n, const std::function<mcon_status()>& call) {
  g_count.store(0);
  g_fail_from.store(n);
  g_refused.store(false);
  g_armed.store(true);
  const mcon_status status = call();
  g_armed.store(false);
  return {status, g_refused.load(), g_count.load()};
}

// Calls `call` failing from every allocation among the first 300 and at 100 points spread over
// the rest; `after` runs after each call (outside the armed region) to release what it made.
void sweep(const char* what, const std::function<mcon_status()>& call, const std::function<void()>& after) {
  const Run counting = run_failing_from(std::numeric_limits<long>::max(), call);
  ASSERT_EQ(counting.status, MCON_OK) << what << ": " << last_message();
  after();
  const long total = counting.allocations;
  if (total == 0) {
    std::printf("%s: no allocations, nothing can run out\n", what);
    return;
  }
  std::vector<long> points;
  for (long n = 0; n < total && n < 300; ++n) points.push_back(n);
  for (long k = 1; k <= 100 && total > 300; ++k) points.push_back(300 + (total - 300) * k / 101);
  int refused = 0;
  for (long n : points) {
    const Run r = run_failing_from(n, call);
    const std::string message = last_message();
    after();
    if (r.refused) {
      ++refused;
      ASSERT_EQ(r.status, MCON_ERROR_OUT_OF_MEMORY) << what << ", allocation " << n << " of " << total << ": " << message;
      const char* text = nullptr;
      EXPECT_EQ(mcon_get_last_error(nullptr, &text), MCON_ERROR_OUT_OF_MEMORY);
      ASSERT_NE(text, nullptr);
    } else {
      ASSERT_EQ(r.status, MCON_OK) << what << ", allocation " << n << ": " << message;
    }
  }
  EXPECT_GT(refused, 0) << what;
  std::printf("%s: %ld allocations, %zu failure points, all OUT_OF_MEMORY\n", what, total, points.size());
}

class OutOfMemory : public ::testing::Test {
 protected:
  void SetUp() override {
    ctx_ = make_context(1);  // one thread: the allocation sequence is the same every run
    arrays_ = arrays_of(mcon::test_meshes::make_disk(6));
    mesh_ = make_mesh(ctx_.get(), arrays_);
    mcon_patch_options o;
    ASSERT_EQ(mcon_patch_options_init(&o), MCON_OK);
    o.center_vertex = 0;
    o.radius = 0.6;
    mcon_patch p = nullptr;
    ASSERT_EQ(mcon_patch_extract(mesh_.get(), &o, &p), MCON_OK) << last_message();
    patch_.reset(p);
  }
  void TearDown() override {
    if (library_ != nullptr) {
      EXPECT_EQ(mcon_library_release(library_), MCON_OK);
    }
  }

  // A library with two entries, a vocabulary and named metadata.
  void make_library() {
    ASSERT_EQ(mcon_library_create(ctx_.get(), &library_), MCON_OK);
    for (const char* name : {"first", "second"}) {
      mcon_library_entry_desc d;
      ASSERT_EQ(mcon_library_entry_desc_init(&d), MCON_OK);
      d.patch = patch_.get();
      d.name = name;
      d.class_label = "disk";
      ASSERT_EQ(mcon_library_add_entry(library_, &d, nullptr), MCON_OK) << last_message();
    }
    mcon_retrieval_options o;
    ASSERT_EQ(mcon_retrieval_options_init(&o), MCON_OK);
    o.vocabulary_size = 4;
    ASSERT_EQ(mcon_library_build_retrieval(library_, &o), MCON_OK) << last_message();
  }
  std::vector<uint8_t> library_bytes() {
    size_t size = 0;
    EXPECT_EQ(mcon_library_save_memory(library_, nullptr, 0, &size), MCON_OK);
    std::vector<uint8_t> bytes(size);
    EXPECT_EQ(mcon_library_save_memory(library_, bytes.data(), size, &size), MCON_OK);
    return bytes;
  }

  ContextPtr ctx_;
  Arrays arrays_;
  MeshPtr mesh_;
  PatchPtr patch_;
  mcon_library library_ = nullptr;
};

TEST_F(OutOfMemory, MeshAndPatchCreation) {
  const mcon_mesh_desc desc = desc_of(arrays_);
  mcon_mesh mesh = nullptr;
  EXPECT_GT(run_failing_from(std::numeric_limits<long>::max(), [&] { return mcon_mesh_create(ctx_.get(), &desc, &mesh); })
                .allocations,
            0)
      << "the library's allocations do not reach the replacement operator new";
  mcon_mesh_release(mesh);
  mesh = nullptr;
  sweep(
      "mcon_mesh_create", [&] { return mcon_mesh_create(ctx_.get(), &desc, &mesh); },
      [&] {
        if (mesh) mcon_mesh_release(mesh);
        mesh = nullptr;
      });
  mcon_patch_options o;
  ASSERT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_vertex = 0;
  o.radius = 0.6;
  mcon_patch patch = nullptr;
  sweep(
      "mcon_patch_extract", [&] { return mcon_patch_extract(mesh_.get(), &o, &patch); },
      [&] {
        if (patch) mcon_patch_release(patch);
        patch = nullptr;
      });
}

TEST_F(OutOfMemory, LibraryAddBuildAndQuery) {
  mcon_library lib = nullptr;
  mcon_library_entry_desc d;
  ASSERT_EQ(mcon_library_entry_desc_init(&d), MCON_OK);
  d.patch = patch_.get();
  d.name = "disk";
  ASSERT_EQ(mcon_library_create(ctx_.get(), &lib), MCON_OK);
  sweep(
      "mcon_library_add_entry", [&] { return mcon_library_add_entry(lib, &d, nullptr); },
      [&] {
        size_t count = 0;
        mcon_library_get_count(lib, &count);
        if (count > 0) mcon_library_remove_entry(lib, 1);  // back to empty
      });
  ASSERT_EQ(mcon_library_add_entry(lib, &d, nullptr), MCON_OK);
  d.name = "other";
  ASSERT_EQ(mcon_library_add_entry(lib, &d, nullptr), MCON_OK);
  mcon_retrieval_options o;
  ASSERT_EQ(mcon_retrieval_options_init(&o), MCON_OK);
  o.vocabulary_size = 4;
  sweep("mcon_library_build_retrieval", [&] { return mcon_library_build_retrieval(lib, &o); }, [] {});
  uint64_t ids[2];
  size_t count = 0;
  sweep(
      "mcon_library_query", [&] { return mcon_library_query(lib, patch_.get(), 2, ids, nullptr, nullptr, 2, &count); },
      [] {});
  EXPECT_EQ(mcon_library_release(lib), MCON_OK);
}

TEST_F(OutOfMemory, LibraryFilesAndGetters) {
  make_library();
  const std::vector<uint8_t> bytes = library_bytes();
  mcon_library opened = nullptr;
  auto release = [&] {
    if (opened) mcon_library_release(opened);
    opened = nullptr;
  };
  sweep(
      "mcon_library_open_memory",
      [&] { return mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &opened); }, release);
  const std::string path = std::string(MACROCON_BINARY_DIR) + "/test_capi_out_of_memory.mclb";
  sweep("mcon_library_save", [&] { return mcon_library_save(library_, path.c_str()); }, [] {});
  sweep("mcon_library_open", [&] { return mcon_library_open(ctx_.get(), path.c_str(), &opened); }, release);
  std::remove(path.c_str());
  std::vector<uint8_t> out(bytes.size());
  size_t size = 0;
  sweep("mcon_library_save_memory",
        [&] { return mcon_library_save_memory(library_, out.data(), out.size(), &size); }, [] {});
  char name[32];
  sweep(
      "mcon_library_get_entry_string",
      [&] { return mcon_library_get_entry_string(library_, 1, MCON_ENTRY_NAME, 0, name, sizeof name, nullptr); },
      [] {});
}

}  // namespace
