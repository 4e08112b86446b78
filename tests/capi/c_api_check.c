/* The public header compiles as strict C99 (-Wall -Wextra -Werror -pedantic) and a plain C
 * program can use the library: context, mesh, version, errors, release, shutdown. Also passes
 * enum values no C++ caller could (C enums are ints), which the library must reject cleanly. */
#include <macrocon/macrocon.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static int failures = 0;

#define CHECK(cond)                                                  \
  do {                                                               \
    if (!(cond)) {                                                   \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                    \
    }                                                                \
  } while (0)

static int log_calls = 0;
static void on_log(void* user, mcon_status status, const char* message) {
  (void)user;
  (void)status;
  if (message != NULL && strstr(message, "vertex 1") != NULL) ++log_calls;
}

int main(void) {
  uint32_t major = 0, minor = 0, patch = 0;
  const char* name = NULL;
  const char* message = NULL;
  mcon_context_options options;
  mcon_context context = NULL;
  mcon_mesh_desc desc;
  mcon_mesh mesh = NULL;
  size_t vertex_count = 0, triangle_count = 0;
  uint32_t dimension = 0;
  /* A unit square, floats, with a fourth (ignored) component per vertex: stride 16 bytes. */
  float positions[4][4] = {{0, 0, 0, 9}, {1, 0, 0, 9}, {1, 1, 0, 9}, {0, 1, 0, 9}};
  uint32_t indices[6] = {0, 1, 2, 0, 2, 3};

  CHECK(mcon_get_version(&major, &minor, &patch) == MCON_OK);
  CHECK(major == MCON_VERSION_MAJOR && minor == MCON_VERSION_MINOR && patch == MCON_VERSION_PATCH);
  CHECK(mcon_get_status_name(MCON_ERROR_NOT_A_DISK, &name) == MCON_OK);
  CHECK(name != NULL && strcmp(name, "MCON_ERROR_NOT_A_DISK") == 0);
  CHECK(mcon_get_status_name((mcon_status)-1, &name) == MCON_ERROR_INVALID_ARGUMENT);
  CHECK(mcon_get_status_name((mcon_status)100000, &name) == MCON_ERROR_INVALID_ARGUMENT);
  CHECK(mcon_descriptor_get_dimension((mcon_descriptor)-7, &dimension) == MCON_ERROR_INVALID_ARGUMENT);
  CHECK(mcon_descriptor_get_dimension((mcon_descriptor)1000, &dimension) == MCON_ERROR_INVALID_ARGUMENT);

  CHECK(mcon_context_options_init(&options) == MCON_OK);
  options.max_threads = 2;
  options.log_callback = on_log;
  CHECK(mcon_context_create(&options, &context) == MCON_OK);
  CHECK(context != NULL);

  CHECK(mcon_mesh_desc_init(&desc) == MCON_OK);
  desc.positions = positions;
  desc.position_type = MCON_SCALAR_FLOAT32;
  desc.position_stride = sizeof(positions[0]);
  desc.vertex_count = 4;
  desc.indices = indices;
  desc.triangle_count = 2;
  CHECK(mcon_mesh_create(context, &desc, &mesh) == MCON_OK);
  CHECK(mcon_mesh_get_counts(mesh, &vertex_count, &triangle_count) == MCON_OK);
  CHECK(vertex_count == 4 && triangle_count == 2);

  /* An error: NaN at vertex 1, reported with its message and to the log callback. */
  positions[1][1] = (float)NAN;
  {
    mcon_mesh bad = NULL;
    CHECK(mcon_mesh_create(context, &desc, &bad) == MCON_ERROR_NON_FINITE);
    CHECK(bad == NULL);
  }
  CHECK(mcon_get_last_error(NULL, &message) == MCON_ERROR_NON_FINITE);
  CHECK(message != NULL && strstr(message, "vertex 1") != NULL);
  CHECK(log_calls == 1);
  /* A scalar type outside the enum. */
  positions[1][1] = 0;
  desc.position_type = 77;
  {
    mcon_mesh bad = NULL;
    CHECK(mcon_mesh_create(context, &desc, &bad) == MCON_ERROR_INVALID_ARGUMENT);
  }

  CHECK(mcon_mesh_release(mesh) == MCON_OK);
  CHECK(mcon_context_release(context) == MCON_OK);
  CHECK(mcon_shutdown() == MCON_OK);
  if (failures == 0) printf("c_api_check: all checks passed (library %u.%u.%u)\n", major, minor, patch);
  return failures == 0 ? 0 : 1;
}
