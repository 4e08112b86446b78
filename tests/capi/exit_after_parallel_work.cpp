// A host process that does heavy parallel work through the library from several threads (each
// with its own context and thread cap) while running its own TBB loops, as a DCC host does, then
// calls mcon_shutdown and exits. Checks that shutdown really joined every worker thread (the
// process is back to one thread) and that the library works again afterwards. Exit status 0 =
// clean; ctest runs it several times (docs/design.md §5: exits with live TBB workers crashed).

#include <atomic>
#include <cstdio>
#include <thread>
#include <vector>

#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "macrocon/macrocon.h"
#include "process_threads.h"
#include "test_meshes.h"

using mcon::test::process_thread_count;

namespace {

std::atomic<int> failures{0};
std::atomic<int> peak_threads{0};

void note_threads() {
  const int n = process_thread_count();
  int seen = peak_threads.load();
  while (n > seen && !peak_threads.compare_exchange_weak(seen, n)) {
  }
}

bool ok(mcon_status s, const char* what) {
  if (s == MCON_OK) return true;
  const char* message = nullptr;
  mcon_get_last_error(nullptr, &message);
  std::fprintf(stderr, "%s failed: %s\n", what, message ? message : "?");
  ++failures;
  return false;
}

// Meshes, patches and descriptors in one context; returns when done or at the first failure.
void library_work(uint32_t max_threads, int rounds) {
  mcon_context_options co;
  mcon_context_options_init(&co);
  co.max_threads = max_threads;
  mcon_context ctx = nullptr;
  if (!ok(mcon_context_create(&co, &ctx), "mcon_context_create")) return;
  const mcon::TriMesh sphere = mcon::test_meshes::make_icosphere(3);  // 642 vertices
  std::vector<double> xyz;
  std::vector<uint32_t> tris;
  for (const auto& p : sphere.positions) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  for (const auto& t : sphere.triangles)
    for (int v : t) tris.push_back(static_cast<uint32_t>(v));
  std::vector<double> values;
  for (int r = 0; r < rounds && failures == 0; ++r) {
    mcon_mesh_desc d;
    mcon_mesh_desc_init(&d);
    d.positions = xyz.data();
    d.position_type = MCON_SCALAR_FLOAT64;
    d.vertex_count = sphere.positions.size();
    d.indices = tris.data();
    d.triangle_count = sphere.triangles.size();
    mcon_mesh mesh = nullptr;
    if (!ok(mcon_mesh_create(ctx, &d, &mesh), "mcon_mesh_create")) break;
    for (uint32_t center : {0u, 100u, 400u}) {
      mcon_patch_options o;
      mcon_patch_options_init(&o);
      o.center_vertex = center + static_cast<uint32_t>(r);
      o.radius = 0.7;
      mcon_patch patch = nullptr;
      if (!ok(mcon_patch_extract(mesh, &o, &patch), "mcon_patch_extract")) break;
      mcon_patch_info info;
      mcon_patch_info_init(&info);
      ok(mcon_patch_get_info(patch, &info), "mcon_patch_get_info");
      values.resize(9 * info.vertex_count);
      ok(mcon_patch_compute_descriptors(patch, MCON_DESCRIPTOR_CURV9, values.data(), values.size()),
         "mcon_patch_compute_descriptors");
      note_threads();
      mcon_patch_release(patch);
    }
    mcon_mesh_release(mesh);
  }
  mcon_context_release(ctx);
}

// The host's own parallel loops, in its own arena (same TBB scheduler as the library).
void host_parallel_work() {
  tbb::task_arena arena;
  std::atomic<long> sum{0};
  arena.execute([&] {
    tbb::parallel_for(0, 2000, [&](int i) {
      long local = 0;
      for (int k = 0; k < 20000; ++k) local += (i * 31 + k) % 7;
      sum += local;
      if (i % 200 == 0) note_threads();
    });
  });
  if (sum.load() <= 0) ++failures;
}

}  // namespace

int main() {
  const int baseline = process_thread_count();
  std::vector<std::thread> host_threads;
  for (uint32_t t : {0u, 1u, 2u, 3u}) host_threads.emplace_back([t] { library_work(t, 2); });
  host_parallel_work();
  for (auto& t : host_threads) t.join();
  if (failures) return 1;
  if (mcon_shutdown() != MCON_OK) {
    ok(MCON_ERROR_UNKNOWN, "mcon_shutdown");
    return 1;
  }
  const int after = process_thread_count();
  std::printf("threads: %d at start, %d at peak, %d after mcon_shutdown\n", baseline, peak_threads.load(), after);
  if (peak_threads.load() <= baseline) {
    std::fprintf(stderr, "no worker thread ever ran: the test proves nothing\n");
    return 1;
  }
  if (after != baseline) {
    std::fprintf(stderr, "mcon_shutdown left %d threads running\n", after - baseline);
    return 1;
  }
  // The library works after shutdown, and a second shutdown is clean as well.
  library_work(0, 1);
  host_parallel_work();
  if (failures || mcon_shutdown() != MCON_OK || process_thread_count() != baseline) {
    std::fprintf(stderr, "second round failed (%d threads)\n", process_thread_count());
    return 1;
  }
  return 0;
}
