/* A host that loads the library at run time (as Mono, Python or a DCC plug-in does): dlopen,
 * work in several contexts from the C ABI, mcon_shutdown, dlclose, and again, a few times.
 * docs/design.md §5: a program that dlclose'd the library after TBB work crashed 1 run in 5;
 * ctest runs this program repeatedly. Exit status 0 means every cycle went through cleanly,
 * worker threads did run, and each mcon_shutdown left the process with its one thread. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <macrocon/macrocon.h>

typedef mcon_status (*context_options_init_fn)(mcon_context_options*, size_t);
typedef mcon_status (*context_create_fn)(const mcon_context_options*, mcon_context*);
typedef mcon_status (*context_release_fn)(mcon_context);
typedef mcon_status (*mesh_desc_init_fn)(mcon_mesh_desc*, size_t);
typedef mcon_status (*mesh_create_fn)(mcon_context, const mcon_mesh_desc*, mcon_mesh*);
typedef mcon_status (*mesh_release_fn)(mcon_mesh);
typedef mcon_status (*patch_options_init_fn)(mcon_patch_options*, size_t);
typedef mcon_status (*patch_extract_fn)(mcon_mesh, const mcon_patch_options*, mcon_patch*);
typedef mcon_status (*patch_release_fn)(mcon_patch);
typedef mcon_status (*patch_compute_descriptors_fn)(mcon_patch, mcon_descriptor, double*, size_t);
typedef mcon_status (*patch_get_info_fn)(mcon_patch, mcon_patch_info*);
typedef mcon_status (*patch_info_init_fn)(mcon_patch_info*, size_t);
typedef mcon_status (*get_last_error_fn)(mcon_context, const char**);
typedef mcon_status (*shutdown_fn)(void);

#define GRID 24 /* GRID x GRID vertices on the unit square */

static int peak_threads = 0;

static int thread_count(void) {
  int n = 0;
  DIR* d = opendir("/proc/self/task");
  struct dirent* e;
  if (d == NULL) return -1;
  while ((e = readdir(d)) != NULL)
    if (e->d_name[0] != '.') ++n;
  closedir(d);
  return n;
}

static void* symbol(void* lib, const char* name) {
  void* p = dlsym(lib, name);
  if (p == NULL) {
    fprintf(stderr, "dlsym(%s) failed: %s\n", name, dlerror());
    exit(2);
  }
  return p;
}

static int fail(const char* what, get_last_error_fn last_error) {
  const char* message = NULL;
  last_error(NULL, &message);
  fprintf(stderr, "%s failed: %s\n", what, message ? message : "?");
  return 1;
}

/* Unions keep the object-pointer -> function-pointer conversions pedantic-clean. */
#define LOAD(type, var, name)   \
  union {                       \
    void* p;                    \
    type f;                     \
  } var##_u;                    \
  type var;                     \
  var##_u.p = symbol(lib, name); \
  var = var##_u.f

static int cycle(const char* path, int round, double* positions, uint32_t* indices, double* values) {
  void* lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  int c, k;
  if (lib == NULL) {
    fprintf(stderr, "dlopen(%s) failed: %s\n", path, dlerror());
    return 1;
  }
  {
    LOAD(context_options_init_fn, context_options_init, "mcon_context_options_init_sized");
    LOAD(context_create_fn, context_create, "mcon_context_create");
    LOAD(context_release_fn, context_release, "mcon_context_release");
    LOAD(mesh_desc_init_fn, mesh_desc_init, "mcon_mesh_desc_init_sized");
    LOAD(mesh_create_fn, mesh_create, "mcon_mesh_create");
    LOAD(mesh_release_fn, mesh_release, "mcon_mesh_release");
    LOAD(patch_options_init_fn, patch_options_init, "mcon_patch_options_init_sized");
    LOAD(patch_extract_fn, patch_extract, "mcon_patch_extract");
    LOAD(patch_release_fn, patch_release, "mcon_patch_release");
    LOAD(patch_compute_descriptors_fn, compute_descriptors, "mcon_patch_compute_descriptors");
    LOAD(patch_get_info_fn, patch_get_info, "mcon_patch_get_info");
    LOAD(patch_info_init_fn, patch_info_init, "mcon_patch_info_init_sized");
    LOAD(get_last_error_fn, last_error, "mcon_get_last_error");
    LOAD(shutdown_fn, shutdown, "mcon_shutdown");

    for (c = 0; c < 2; ++c) {
      mcon_context_options co;
      mcon_context context = NULL;
      mcon_mesh_desc desc;
      mcon_mesh mesh = NULL;
      context_options_init(&co, sizeof co);
      co.max_threads = (uint32_t)(2 * c); /* 0 = all, then 2 */
      if (context_create(&co, &context) != MCON_OK) return fail("mcon_context_create", last_error);
      mesh_desc_init(&desc, sizeof desc);
      desc.positions = positions;
      desc.position_type = MCON_SCALAR_FLOAT64;
      desc.vertex_count = GRID * GRID;
      desc.indices = indices;
      desc.triangle_count = 2 * (GRID - 1) * (GRID - 1);
      if (mesh_create(context, &desc, &mesh) != MCON_OK) return fail("mcon_mesh_create", last_error);
      /* Patches around a few centers, and their descriptors: the library's parallel work. */
      for (k = 0; k < 2; ++k) {
        mcon_patch_options po;
        mcon_patch patch = NULL;
        mcon_patch_info info;
        patch_options_init(&po, sizeof po);
        po.center_vertex = (uint32_t)((GRID / 2) * GRID + GRID / 2 + k - 1);
        po.radius = 0.2 + 0.05 * k;
        if (patch_extract(mesh, &po, &patch) != MCON_OK) return fail("mcon_patch_extract", last_error);
        patch_info_init(&info, sizeof info);
        if (patch_get_info(patch, &info) != MCON_OK) return fail("mcon_patch_get_info", last_error);
        if (info.vertex_count > (size_t)GRID * GRID * 4) return fail("patch size", last_error);
        if (compute_descriptors(patch, MCON_DESCRIPTOR_CURV9, values, (size_t)GRID * GRID * 4 * 9) != MCON_OK)
          return fail("mcon_patch_compute_descriptors", last_error);
        if (thread_count() > peak_threads) peak_threads = thread_count();
        patch_release(patch);
      }
      /* Release the context first: the mesh keeps it alive until its own release. */
      context_release(context);
      mesh_release(mesh);
    }
    if (shutdown() != MCON_OK) return fail("mcon_shutdown", last_error);
    /* mcon_shutdown has joined the workers, but a joined thread can still be listed in
     * /proc/self/task for a moment while the kernel finishes its exit (seen once in ~60 runs on a
     * loaded machine): allow it up to 2 s to disappear. A worker that really survived stays. */
    for (k = 0; k < 200 && thread_count() != 1; ++k) {
      const struct timespec pause = {0, 10 * 1000 * 1000};
      nanosleep(&pause, NULL);
    }
    if (thread_count() != 1) {
      fprintf(stderr, "round %d: %d threads left after mcon_shutdown\n", round, thread_count());
      return 1;
    }
  }
  if (dlclose(lib) != 0) {
    fprintf(stderr, "dlclose failed in round %d: %s\n", round, dlerror());
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  static double positions[3 * GRID * GRID];
  static uint32_t indices[6 * (GRID - 1) * (GRID - 1)];
  /* Patch vertices can outnumber host vertices (cut edges): room for 4x, 9 values each. */
  static double values[(size_t)GRID * GRID * 4 * 9];
  int i, j, n = 0, round;
  if (argc < 2) {
    fprintf(stderr, "usage: %s path/to/libmacrocon.so [rounds]\n", argv[0]);
    return 2;
  }
  for (j = 0; j < GRID; ++j)
    for (i = 0; i < GRID; ++i) {
      positions[3 * (j * GRID + i) + 0] = (double)i / (GRID - 1);
      positions[3 * (j * GRID + i) + 1] = (double)j / (GRID - 1);
      positions[3 * (j * GRID + i) + 2] = 0.1 * ((double)(i * i) / (GRID * GRID)); /* gently curved */
    }
  for (j = 0; j + 1 < GRID; ++j)
    for (i = 0; i + 1 < GRID; ++i) {
      const uint32_t a = (uint32_t)(j * GRID + i), b = a + 1, c = a + GRID + 1, d = a + GRID;
      indices[n++] = a, indices[n++] = b, indices[n++] = c;
      indices[n++] = a, indices[n++] = c, indices[n++] = d;
    }
  for (round = 0; round < (argc > 2 ? atoi(argv[2]) : 3); ++round)
    if (cycle(argv[1], round, positions, indices, values) != 0) return 1;
  if (peak_threads < 2) {
    fprintf(stderr, "no worker thread ever ran: the test proves nothing\n");
    return 1;
  }
  printf("dlopen_cycle: %d rounds clean, up to %d threads during work\n", round, peak_threads);
  return 0;
}
