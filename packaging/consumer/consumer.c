/* Builds a unit square, checks the version, and cleans up: proves headers + library link. */
#include <stdio.h>
#include <macrocon/macrocon.h>

int main(void) {
  uint32_t major = 0, minor = 0, patch = 0;
  mcon_context ctx = NULL;
  mcon_mesh mesh = NULL;
  mcon_mesh_desc desc;
  const float xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const uint32_t tris[] = {0, 1, 2, 0, 2, 3};
  size_t nv = 0, nt = 0;
  if (mcon_get_version(&major, &minor, &patch) != MCON_OK || major != MCON_VERSION_MAJOR) return 1;
  if (mcon_context_create(NULL, &ctx) != MCON_OK) return 2;
  mcon_mesh_desc_init(&desc);
  desc.positions = xyz;
  desc.position_type = MCON_SCALAR_FLOAT32;
  desc.vertex_count = 4;
  desc.indices = tris;
  desc.triangle_count = 2;
  if (mcon_mesh_create(ctx, &desc, &mesh) != MCON_OK) return 3;
  if (mcon_mesh_get_counts(mesh, &nv, &nt) != MCON_OK || nv != 4 || nt != 2) return 4;
  mcon_mesh_release(mesh);
  mcon_context_release(ctx);
  mcon_shutdown();
  printf("macrocon %u.%u.%u: ok\n", (unsigned)major, (unsigned)minor, (unsigned)patch);
  return 0;
}
