/*
 * Macrocon sample: the integration pattern of a DCC plugin, in plain C against the C API only.
 *
 *   transfer_fields LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT.ply
 *
 *  1. the host mesh (here read from an OBJ; a plugin takes its host's arrays) -> mcon_mesh
 *  2. the user's region (a vertex + a geodesic radius) -> a normalized disk patch
 *  3. query the constraint library for the most similar macro constraints
 *  4. re-embed the best one: its patch -> the region's patch (mcon_map_compute)
 *  5. transfer its per-vertex fields (uv, skin weights, colour, labels) onto the region
 *  6. write them back onto the host vertices (here: a PLY file; a plugin sets attributes)
 *
 * Everything an SDK call returns is checked: on failure, mcon_get_last_error() gives the status
 * and a message naming the problem, which a plugin shows to the user. Handles are released in one
 * cleanup block (releasing NULL is a no-op, so the block works from any point of failure), and
 * mcon_shutdown() runs once before the process exits / the plugin unloads.
 *
 * The OBJ reader and PLY writer (samples/common/sample_mesh.c) are sample helpers, not SDK API.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "macrocon/macrocon.h"
#include "sample_mesh.h"

/* Report a failed SDK call with the library's own message and jump to cleanup. A plugin would
 * show `message` in its UI instead of printing it. */
#define CHECK(call)                                                                     \
  do {                                                                                  \
    const mcon_status status_ = (call);                                                 \
    if (status_ != MCON_OK) {                                                           \
      const char* message_ = NULL;                                                      \
      const char* name_ = NULL;                                                         \
      mcon_get_last_error(ctx, &message_);                                              \
      mcon_get_status_name(status_, &name_);                                            \
      fprintf(stderr, "transfer_fields: %s failed: %s: %s\n", #call, name_ ? name_ : "?", \
              message_ ? message_ : "");                                                \
      goto cleanup;                                                                     \
    }                                                                                   \
  } while (0)

/* malloc that treats failure like any other error. */
#define ALLOC(ptr, count)                                              \
  do {                                                                 \
    const size_t count_ = (count);                                     \
    (ptr) = calloc(count_ > 0 ? count_ : 1, sizeof(*(ptr)));           \
    if ((ptr) == NULL) {                                               \
      fprintf(stderr, "transfer_fields: out of memory\n");             \
      goto cleanup;                                                    \
    }                                                                  \
  } while (0)

#define MAX_FIELDS 16
#define TOP_N 3

int main(int argc, char** argv) {
  int exit_code = 1;
  mcon_context ctx = NULL;
  mcon_mesh host = NULL;
  mcon_patch region = NULL;
  mcon_library library = NULL;
  mcon_patch entry_patch = NULL;
  mcon_map map = NULL;
  sample_mesh mesh = {0};
  double* entry_xyz = NULL;
  uint32_t* entry_tris = NULL;
  uint32_t* host_v0 = NULL;
  uint32_t* host_v1 = NULL;
  double* host_t = NULL;
  uint8_t* outside = NULL;
  double* source_values = NULL;
  int32_t* source_labels = NULL;
  double* patch_values = NULL;
  int32_t* patch_labels = NULL;
  double* host_fields[MAX_FIELDS + 1] = {NULL};
  char* field_names[MAX_FIELDS] = {NULL};
  sample_ply_attribute attributes[MAX_FIELDS + 1];
  size_t attribute_count = 0;
  size_t i, f;

  if (argc != 6) {
    fprintf(stderr, "usage: transfer_fields LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT.ply\n");
    return 2;
  }
  const char* library_path = argv[1];
  const char* host_path = argv[2];
  const unsigned long center_vertex = strtoul(argv[3], NULL, 10);
  const double radius = strtod(argv[4], NULL);
  const char* out_path = argv[5];

  /* 0. The loaded library must have the major version this code was compiled against. */
  uint32_t major = 0, minor = 0, patch_version = 0;
  CHECK(mcon_get_version(&major, &minor, &patch_version));
  if (major != MCON_VERSION_MAJOR) {
    fprintf(stderr, "transfer_fields: libmacrocon %u.%u is not ABI-compatible with this build (%d.x)\n", major,
            minor, MCON_VERSION_MAJOR);
    goto cleanup;
  }

  /* 1. A context owns the worker threads (max_threads = 0: all cores; results do not depend on
   *    it). Then the host mesh: the SDK validates and copies the arrays, so the host may free or
   *    change its own buffers right after the call. */
  {
    char error[512];
    if (sample_mesh_read_obj(host_path, &mesh, error, sizeof(error)) != 0) {
      fprintf(stderr, "transfer_fields: %s\n", error);
      goto cleanup;
    }
  }
  CHECK(mcon_context_create(NULL, &ctx));
  {
    mcon_mesh_desc desc;
    CHECK(mcon_mesh_desc_init(&desc)); /* always *_init first: it sets struct_size and defaults */
    desc.positions = mesh.positions;
    desc.position_type = MCON_SCALAR_FLOAT32;
    desc.vertex_count = mesh.vertex_count;
    desc.indices = mesh.indices;
    desc.triangle_count = mesh.triangle_count;
    /* Non-manifold or degenerate input fails here with a status naming the first bad element. */
    CHECK(mcon_mesh_create(ctx, &desc, &host));
  }

  /* 2. The user's region: a geodesic disk around the picked vertex. MCON_ERROR_NOT_A_DISK means
   *    the radius wraps around a limb or a handle: ask the user for a smaller radius. */
  {
    mcon_patch_options options;
    CHECK(mcon_patch_options_init(&options));
    options.center_vertex = (uint32_t)center_vertex;
    options.radius = radius;
    CHECK(mcon_patch_extract(host, &options, &region));
  }
  mcon_patch_info region_info;
  CHECK(mcon_patch_info_init(&region_info));
  CHECK(mcon_patch_get_info(region, &region_info));
  printf("region: vertex %lu, radius %g: %zu vertices, %zu triangles\n", center_vertex, radius,
         region_info.vertex_count, region_info.triangle_count);

  /* 3. Open the library (read into memory and validated: a corrupt or foreign file is
   *    MCON_ERROR_INVALID_LIBRARY, a newer format MCON_ERROR_UNSUPPORTED, never a crash) and ask
   *    for the TOP_N nearest entries. A plugin lists these as suggestions. */
  CHECK(mcon_library_open(ctx, library_path, &library));
  uint64_t ids[TOP_N];
  uint32_t indices[TOP_N];
  double distances[TOP_N];
  size_t found = 0;
  CHECK(mcon_library_query(library, region, TOP_N, ids, indices, distances, TOP_N, &found));
  for (i = 0; i < found; ++i) {
    char name[256], klass[64];
    CHECK(mcon_library_get_entry_string(library, indices[i], MCON_ENTRY_NAME, 0, name, sizeof(name), NULL));
    CHECK(mcon_library_get_entry_string(library, indices[i], MCON_ENTRY_CLASS_LABEL, 0, klass, sizeof(klass), NULL));
    printf("suggestion %zu: id %llu, class %s, distance %.4f: %s\n", i + 1, (unsigned long long)ids[i], klass,
           distances[i], name);
  }
  if (found == 0) {
    fprintf(stderr, "transfer_fields: the library is empty\n");
    goto cleanup;
  }
  const size_t best = indices[0];

  /* Licensing travels with every entry: a plugin shows it and keeps it with the asset. */
  {
    char licence[256], author[256];
    CHECK(mcon_library_get_entry_string(library, best, MCON_ENTRY_LICENCE, 0, licence, sizeof(licence), NULL));
    CHECK(mcon_library_get_entry_string(library, best, MCON_ENTRY_AUTHOR, 0, author, sizeof(author), NULL));
    printf("using entry %llu by %s, licence %s\n", (unsigned long long)ids[0], author, licence);
  }

  /* 4. The entry's patch as an mcon_patch (arrays out of the library, then
   *    mcon_patch_create_from_arrays with the entry's center and frame), and the re-embedding map
   *    from it onto the region. The map is locally injective and partial: parts of the entry that
   *    fall outside the region have no image. */
  mcon_library_entry_info entry;
  CHECK(mcon_library_entry_info_init(&entry));
  CHECK(mcon_library_get_entry_info(library, best, &entry));
  ALLOC(entry_xyz, 3 * entry.vertex_count);
  ALLOC(entry_tris, 3 * entry.triangle_count);
  CHECK(mcon_library_get_entry_positions(library, best, entry_xyz, 3 * entry.vertex_count));
  CHECK(mcon_library_get_entry_triangles(library, best, entry_tris, 3 * entry.triangle_count));
  {
    mcon_mesh_desc desc;
    mcon_patch_frame frame;
    CHECK(mcon_mesh_desc_init(&desc));
    desc.positions = entry_xyz;
    desc.position_type = MCON_SCALAR_FLOAT64;
    desc.vertex_count = entry.vertex_count;
    desc.indices = entry_tris;
    desc.triangle_count = entry.triangle_count;
    CHECK(mcon_patch_frame_init(&frame));
    frame.center_triangle = entry.center.face;
    for (i = 0; i < 3; ++i) {
      frame.center_barycentric[i] = entry.center.barycentric[i];
      frame.origin[i] = entry.source_origin[i];
    }
    frame.scale = entry.source_scale;
    CHECK(mcon_patch_create_from_arrays(ctx, &desc, &frame, &entry_patch));
  }
  {
    mcon_map_options options;
    mcon_map_info info;
    CHECK(mcon_map_options_init(&options)); /* seed 0: the same map on every run and thread count */
    CHECK(mcon_map_compute(entry_patch, region, &options, &map));
    CHECK(mcon_map_info_init(&info));
    CHECK(mcon_map_get_info(map, &info));
    printf("map: overlap %.3f, matching score %.3f, %u iterations, %s, %u flipped triangles\n", info.overlap_ratio,
           info.matching_score, info.iterations, info.reflected ? "mirrored" : "not mirrored", info.flipped_triangles);
  }

  /* 5 + 6. Fields onto the region's vertices, then onto the host: a region vertex that is a host
   *    vertex (v0 == v1, t == 0) carries its value back; vertices the cut created on host edges
   *    have no host vertex and are skipped. Region vertices outside the overlap get 0 from the
   *    transfer; the mask attribute tells a plugin which host vertices received values. */
  const size_t nr = region_info.vertex_count, nh = mesh.vertex_count;
  ALLOC(host_v0, nr);
  ALLOC(host_v1, nr);
  ALLOC(host_t, nr);
  ALLOC(outside, nr);
  CHECK(mcon_patch_get_host_vertices(region, host_v0, host_v1, host_t, nr));
  CHECK(mcon_map_get_outside_mask(map, outside, nr));

  ALLOC(host_fields[0], nh);
  size_t transferred_vertices = 0;
  for (i = 0; i < nr; ++i)
    if (host_v0[i] == host_v1[i] && host_v0[i] != MCON_INVALID_INDEX && !outside[i]) {
      host_fields[0][host_v0[i]] = 1.0;
      ++transferred_vertices;
    }
  attributes[attribute_count].name = "macro_mask";
  attributes[attribute_count].dimension = 1;
  attributes[attribute_count].values = host_fields[0];
  ++attribute_count;

  for (f = 0; f < entry.field_count && f < MAX_FIELDS; ++f) {
    uint32_t kind = 0, dim = 0;
    size_t name_size = 0;
    CHECK(mcon_library_get_entry_field(library, best, f, &kind, &dim, NULL, NULL, 0));
    /* Strings: ask for the size first, then read into a buffer of that size. */
    CHECK(mcon_library_get_entry_string(library, best, MCON_ENTRY_FIELD_NAME, f, NULL, 0, &name_size));
    ALLOC(field_names[f], name_size);
    CHECK(mcon_library_get_entry_string(library, best, MCON_ENTRY_FIELD_NAME, f, field_names[f], name_size, NULL));

    const size_t ns = entry.vertex_count * dim, nt = nr * dim;
    ALLOC(patch_values, nt);
    if (kind == MCON_FIELD_INTEGER_LABEL) {
      /* Labels are never blended: each region vertex takes the nearest corner's label. */
      ALLOC(source_labels, ns);
      ALLOC(patch_labels, nt);
      CHECK(mcon_library_get_entry_field(library, best, f, NULL, NULL, NULL, source_labels, ns));
      CHECK(mcon_map_transfer_labels(map, dim, source_labels, ns, -1, patch_labels, nt));
      for (i = 0; i < nt; ++i) patch_values[i] = (double)patch_labels[i];
    } else {
      /* Scalars, colours and uv are interpolated; tangent vectors are pushed forward by the
       * map's Jacobian (mcon_map_transfer_field handles each kind). */
      ALLOC(source_values, ns);
      CHECK(mcon_library_get_entry_field(library, best, f, NULL, NULL, source_values, NULL, ns));
      CHECK(mcon_map_transfer_field(map, (mcon_field_kind)kind, dim, source_values, ns, patch_values, nt));
    }
    ALLOC(host_fields[f + 1], nh * dim);
    for (i = 0; i < nr; ++i) {
      if (host_v0[i] != host_v1[i] || host_v0[i] == MCON_INVALID_INDEX || outside[i]) continue;
      memcpy(host_fields[f + 1] + (size_t)host_v0[i] * dim, patch_values + i * dim, dim * sizeof(double));
    }
    attributes[attribute_count].name = field_names[f];
    attributes[attribute_count].dimension = dim;
    attributes[attribute_count].values = host_fields[f + 1];
    ++attribute_count;
    printf("field %-20s kind %u, %u channel(s)\n", field_names[f], kind, dim);
    free(source_values);
    free(source_labels);
    free(patch_values);
    free(patch_labels);
    source_values = NULL;
    source_labels = NULL;
    patch_values = NULL;
    patch_labels = NULL;
  }
  if (sample_ply_write(out_path, &mesh, attributes, attribute_count) != 0) {
    fprintf(stderr, "transfer_fields: cannot write '%s'\n", out_path);
    goto cleanup;
  }
  printf("transferred %zu field(s) onto %zu host vertices -> %s\n", attribute_count - 1, transferred_vertices,
         out_path);
  exit_code = transferred_vertices > 0 ? 0 : 1;

cleanup:
  /* Release in any order (objects keep what they depend on alive); NULL is a no-op. */
  mcon_map_release(map);
  mcon_patch_release(entry_patch);
  mcon_library_release(library);
  mcon_patch_release(region);
  mcon_mesh_release(host);
  mcon_context_release(ctx);
  /* Once, after every handle is released: joins the SDK's worker threads so the process (or a
   * host such as Maya unloading the plugin) exits cleanly. */
  mcon_shutdown();
  for (f = 0; f < MAX_FIELDS; ++f) free(field_names[f]);
  for (f = 0; f <= MAX_FIELDS; ++f) free(host_fields[f]);
  free(source_values);
  free(source_labels);
  free(patch_values);
  free(patch_labels);
  free(outside);
  free(host_t);
  free(host_v1);
  free(host_v0);
  free(entry_tris);
  free(entry_xyz);
  sample_mesh_free(&mesh);
  return exit_code;
}
