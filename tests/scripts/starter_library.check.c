/* Checks the generated starter library through the C API only:
 *   starter_library_check LIBRARY.mclb ENTRY_COUNT CLASS...
 *  - it opens (validated) and has ENTRY_COUNT entries covering every CLASS;
 *  - every entry is labelled honestly (tag "example", the CC0/MakeHuman licence, an author), stores
 *    the body's up direction (+Y, entries.json "up") and
 *    carries the example fields: uv in the unit disk, skin weights that sum to 1, a colour in
 *    [0, 1], integer region labels;
 *  - eyes and mouth have closed edge-loop guides, hands open finger flow lines with a valence-3
 *    singularity at each tip, every singularity index is nonzero;
 *  - retrieval works: each entry's own patch, queried back, finds an entry of its class first.
 * Prints every failure; exit status 1 if any. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "macrocon/macrocon.h"

static int failures = 0;

#define EXPECT(cond, ...)                 \
  do {                                    \
    if (!(cond)) {                        \
      printf("FAIL: " __VA_ARGS__);       \
      printf("\n");                       \
      ++failures;                         \
    }                                     \
  } while (0)

static int ok(mcon_status s, const char* what) {
  if (s == MCON_OK) return 1;
  const char* message = NULL;
  mcon_get_last_error(NULL, &message);
  printf("FAIL: %s: status %d: %s\n", what, (int)s, message ? message : "");
  ++failures;
  return 0;
}

static void entry_string(mcon_library lib, size_t i, mcon_entry_string which, size_t item, char* out, size_t cap) {
  out[0] = '\0';
  ok(mcon_library_get_entry_string(lib, i, which, item, out, cap, NULL), "mcon_library_get_entry_string");
}

/* Checks one entry; writes its class into klass. */
static void check_entry(mcon_context ctx, mcon_library lib, size_t i, char* klass, size_t klass_cap) {
  char name[256], text[256];
  mcon_library_entry_info info;
  mcon_library_entry_info_init(&info);
  if (!ok(mcon_library_get_entry_info(lib, i, &info), "mcon_library_get_entry_info")) return;
  entry_string(lib, i, MCON_ENTRY_NAME, 0, name, sizeof(name));
  entry_string(lib, i, MCON_ENTRY_CLASS_LABEL, 0, klass, klass_cap);
  entry_string(lib, i, MCON_ENTRY_LICENCE, 0, text, sizeof(text));
  EXPECT(strcmp(text, "CC0-1.0 (geometry: MakeHuman)") == 0, "%s: licence '%s'", name, text);
  entry_string(lib, i, MCON_ENTRY_AUTHOR, 0, text, sizeof(text));
  EXPECT(text[0] != '\0', "%s: no author", name);
  EXPECT(info.has_up == 1 && info.up[0] == 0 && info.up[1] > 0 && info.up[2] == 0, "%s: up %d (%g, %g, %g), not +Y",
         name, (int)info.has_up, info.up[0], info.up[1], info.up[2]);
  int example = 0;
  for (size_t t = 0; t < info.tag_count; ++t) {
    entry_string(lib, i, MCON_ENTRY_TAG, t, text, sizeof(text));
    example |= strcmp(text, "example") == 0;
  }
  EXPECT(example, "%s: not tagged 'example'", name);

  /* Fields. */
  const size_t n = info.vertex_count;
  double* weight_sum = calloc(n, sizeof(double));
  double* values = calloc(3 * n, sizeof(double));
  int32_t* labels = calloc(n, sizeof(int32_t));
  int have_uv = 0, have_color = 0, have_region = 0, weights = 0;
  for (size_t f = 0; f < info.field_count && weight_sum && values && labels; ++f) {
    uint32_t kind = 0, dim = 0;
    ok(mcon_library_get_entry_field(lib, i, f, &kind, &dim, NULL, NULL, 0), "mcon_library_get_entry_field");
    entry_string(lib, i, MCON_ENTRY_FIELD_NAME, f, text, sizeof(text));
    if (dim > 3) continue;
    if (kind == MCON_FIELD_INTEGER_LABEL) {
      ok(mcon_library_get_entry_field(lib, i, f, NULL, NULL, NULL, labels, n * dim), "get labels");
      if (strcmp(text, "region") == 0) {
        have_region = 1;
        for (size_t v = 0; v < n; ++v) EXPECT(labels[v] >= 0 && labels[v] <= 5, "%s: region label %d", name, labels[v]);
      }
      continue;
    }
    ok(mcon_library_get_entry_field(lib, i, f, NULL, NULL, values, NULL, n * dim), "get values");
    if (kind == MCON_FIELD_UV && strcmp(text, "uv") == 0) {
      have_uv = 1;
      double worst = 0;
      for (size_t v = 0; v < n; ++v) {
        const double r2 = values[2 * v] * values[2 * v] + values[2 * v + 1] * values[2 * v + 1];
        if (r2 > worst) worst = r2;
      }
      EXPECT(worst <= 1 + 1e-5, "%s: uv leaves the unit disk (|uv|^2 = %g)", name, worst);
    } else if (kind == MCON_FIELD_VECTOR3 && strcmp(text, "color") == 0) {
      have_color = 1;
      for (size_t v = 0; v < 3 * n; ++v) EXPECT(values[v] >= 0 && values[v] <= 1, "%s: colour %g", name, values[v]);
    } else if (kind == MCON_FIELD_SCALAR && strncmp(text, "skin_weight_", 12) == 0) {
      ++weights;
      for (size_t v = 0; v < n; ++v) weight_sum[v] += values[v];
    }
  }
  EXPECT(have_uv && have_color && have_region, "%s: missing uv, color or region", name);
  EXPECT(weights >= 3, "%s: %d skin weight fields", name, weights);
  double worst = 0;
  for (size_t v = 0; v < n && weight_sum; ++v)
    if (fabs(weight_sum[v] - 1) > worst) worst = fabs(weight_sum[v] - 1);
  /* Stored as float32: each weight is off by at most 2^-24 relative. */
  EXPECT(worst < 1e-5, "%s: skin weights sum to 1 only within %g", name, worst);
  free(weight_sum);
  free(values);
  free(labels);

  /* Constraints. */
  size_t closed_guides = 0, open_guides = 0, features = 0;
  for (size_t p = 0; p < info.polyline_count; ++p) {
    uint32_t kind = 0, closed = 0;
    size_t count = 0;
    ok(mcon_library_get_entry_polyline(lib, i, p, &kind, &closed, &count, NULL, 0), "get polyline");
    EXPECT(count >= 2, "%s: polyline %zu has %zu points", name, p, count);
    if (kind == MCON_POLYLINE_GUIDE) {
      if (closed) ++closed_guides; else ++open_guides;
    } else {
      ++features;
    }
  }
  mcon_singularity sing[64];
  int plus = 0;
  if (info.singularity_count <= 64 &&
      ok(mcon_library_get_entry_singularities(lib, i, sing, 64), "get singularities"))
    for (size_t s = 0; s < info.singularity_count; ++s) {
      EXPECT(sing[s].index_quarters != 0, "%s: singularity of index 0", name);
      plus += sing[s].index_quarters == 1;
    }
  if (strcmp(klass, "eye") == 0 || strcmp(klass, "mouth") == 0) {
    EXPECT(closed_guides >= 3, "%s: %zu edge loops", name, closed_guides);
    EXPECT(info.singularity_count == 2, "%s: %zu corner singularities", name, info.singularity_count);
  }
  if (strcmp(klass, "hand") == 0) {
    EXPECT(open_guides == 5, "%s: %zu finger flow lines", name, open_guides);
    EXPECT(plus == 5, "%s: %d valence-3 tip singularities", name, plus);
  }
  EXPECT(info.polyline_count > 0, "%s: no constraints", name);
  (void)features;

  /* Retrieval: the entry's own patch is found first as its class. */
  double* xyz = malloc(3 * n * sizeof(double));
  uint32_t* tris = malloc(3 * info.triangle_count * sizeof(uint32_t));
  mcon_patch patch = NULL;
  if (xyz && tris && ok(mcon_library_get_entry_positions(lib, i, xyz, 3 * n), "positions") &&
      ok(mcon_library_get_entry_triangles(lib, i, tris, 3 * info.triangle_count), "triangles")) {
    mcon_mesh_desc d;
    mcon_patch_frame frame;
    mcon_mesh_desc_init(&d);
    d.positions = xyz;
    d.position_type = MCON_SCALAR_FLOAT64;
    d.vertex_count = n;
    d.indices = tris;
    d.triangle_count = info.triangle_count;
    mcon_patch_frame_init(&frame);
    frame.center_triangle = info.center.face;
    for (int k = 0; k < 3; ++k) frame.center_barycentric[k] = info.center.barycentric[k];
    if (ok(mcon_patch_create_from_arrays(ctx, &d, &frame, &patch), "mcon_patch_create_from_arrays")) {
      uint32_t index = 0;
      size_t found = 0;
      if (ok(mcon_library_query(lib, patch, 1, NULL, &index, NULL, 1, &found), "mcon_library_query")) {
        char got[64];
        entry_string(lib, index, MCON_ENTRY_CLASS_LABEL, 0, got, sizeof(got));
        EXPECT(found == 1 && strcmp(got, klass) == 0, "%s: its own patch retrieves class '%s' first", name, got);
      }
    }
  }
  mcon_patch_release(patch);
  free(xyz);
  free(tris);
}

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: starter_library_check LIBRARY.mclb ENTRY_COUNT CLASS...\n");
    return 2;
  }
  mcon_context ctx = NULL;
  mcon_library lib = NULL;
  size_t count = 0;
  char classes[64][64];
  if (ok(mcon_context_create(NULL, &ctx), "mcon_context_create") &&
      ok(mcon_library_open(ctx, argv[1], &lib), "mcon_library_open") &&
      ok(mcon_library_get_count(lib, &count), "mcon_library_get_count")) {
    EXPECT(count == strtoul(argv[2], NULL, 10), "%zu entries, expected %s", count, argv[2]);
    mcon_library_info info;
    mcon_library_info_init(&info);
    if (ok(mcon_library_get_info(lib, &info), "mcon_library_get_info"))
      EXPECT(info.vocabulary_size > 0, "no retrieval vocabulary: queries would fail");
    for (size_t i = 0; i < count && i < 64; ++i) check_entry(ctx, lib, i, classes[i], sizeof(classes[i]));
    for (int c = 3; c < argc; ++c) {
      int present = 0;
      for (size_t i = 0; i < count && i < 64; ++i) present |= strcmp(classes[i], argv[c]) == 0;
      EXPECT(present, "no entry of benchmark class '%s'", argv[c]);
    }
  }
  mcon_library_release(lib);
  mcon_context_release(ctx);
  mcon_shutdown();
  printf("%s: %zu entries, %d failure(s)\n", argv[1], count, failures);
  return failures == 0 ? 0 : 1;
}
