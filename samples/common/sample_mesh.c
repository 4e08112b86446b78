/* Sample-only OBJ reader and PLY writer (see sample_mesh.h). */
#include "sample_mesh.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static void set_error(char* error, size_t size, const char* path, const char* what, long line) {
  if (error == NULL || size == 0) return;
  if (line > 0)
    snprintf(error, size, "%s:%ld: %s", path, line, what);
  else
    snprintf(error, size, "%s: %s", path, what);
}

/* Appends to a growing array; returns 0 on success. */
static int grow(void** data, size_t* capacity, size_t needed, size_t element) {
  if (needed <= *capacity) return 0;
  size_t c = *capacity ? *capacity : 1024;
  while (c < needed) c *= 2;
  void* p = realloc(*data, c * element);
  if (p == NULL) return -1;
  *data = p;
  *capacity = c;
  return 0;
}

int sample_mesh_read_obj(const char* path, sample_mesh* out, char* error, size_t error_size) {
  memset(out, 0, sizeof(*out));
  /* gzopen reads plain files too (transparently), so one code path serves .obj and .obj.gz. */
  gzFile file = gzopen(path, "rb");
  if (file == NULL) {
    set_error(error, error_size, path, "cannot open", 0);
    return -1;
  }
  size_t pos_cap = 0, idx_cap = 0;
  char line[4096];
  long line_number = 0;
  int failed = 0;
  while (!failed && gzgets(file, line, (int)sizeof(line)) != NULL) {
    ++line_number;
    if (line[0] == 'v' && line[1] == ' ') {
      float x, y, z;
      if (sscanf(line + 2, "%f %f %f", &x, &y, &z) != 3) {
        set_error(error, error_size, path, "malformed 'v' line", line_number);
        failed = 1;
        break;
      }
      if (grow((void**)&out->positions, &pos_cap, 3 * (out->vertex_count + 1), sizeof(float)) != 0) {
        set_error(error, error_size, path, "out of memory", line_number);
        failed = 1;
        break;
      }
      out->positions[3 * out->vertex_count + 0] = x;
      out->positions[3 * out->vertex_count + 1] = y;
      out->positions[3 * out->vertex_count + 2] = z;
      ++out->vertex_count;
    } else if (line[0] == 'f' && line[1] == ' ') {
      /* "f a b c ...", each corner "v", "v/t", "v//n" or "v/t/n"; negative = relative. */
      long corners[64];
      int n = 0;
      char* p = line + 2;
      for (;;) {
        while (*p == ' ' || *p == '\t') ++p;
        if (*p == '\0' || *p == '\n' || *p == '\r') break;
        char* end = NULL;
        long v = strtol(p, &end, 10);
        if (end == p || n == 64) {
          set_error(error, error_size, path, "malformed 'f' line", line_number);
          failed = 1;
          break;
        }
        if (v < 0) v = (long)out->vertex_count + v + 1;
        corners[n++] = v - 1;
        p = end;
        while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\n' && *p != '\r') ++p;
      }
      if (failed) break;
      if (n < 3) {
        set_error(error, error_size, path, "a face with fewer than 3 corners", line_number);
        failed = 1;
        break;
      }
      for (int k = 0; k < n; ++k)
        if (corners[k] < 0) {
          set_error(error, error_size, path, "a vertex index before the first vertex", line_number);
          failed = 1;
          break;
        }
      if (failed) break;
      /* Out-of-range indices are left for mcon_mesh_create to report (it names the triangle). */
      for (int k = 1; k + 1 < n; ++k) {
        if (grow((void**)&out->indices, &idx_cap, 3 * (out->triangle_count + 1), sizeof(uint32_t)) != 0) {
          set_error(error, error_size, path, "out of memory", line_number);
          failed = 1;
          break;
        }
        uint32_t* t = out->indices + 3 * out->triangle_count;
        t[0] = (uint32_t)corners[0];
        t[1] = (uint32_t)corners[k];
        t[2] = (uint32_t)corners[k + 1];
        ++out->triangle_count;
      }
    }
  }
  if (!failed && !gzeof(file)) {
    set_error(error, error_size, path, "read error", line_number);
    failed = 1;
  }
  gzclose(file);
  if (!failed && (out->vertex_count == 0 || out->triangle_count == 0)) {
    set_error(error, error_size, path, "no vertices or no faces", 0);
    failed = 1;
  }
  if (failed) {
    sample_mesh_free(out);
    return -1;
  }
  return 0;
}

void sample_mesh_free(sample_mesh* mesh) {
  free(mesh->positions);
  free(mesh->indices);
  memset(mesh, 0, sizeof(*mesh));
}

static int is_color(const sample_ply_attribute* a) { return a->dimension == 3 && strcmp(a->name, "color") == 0; }

static unsigned char to_byte(double x) {
  if (!(x > 0)) return 0;
  if (x >= 1) return 255;
  return (unsigned char)(x * 255.0 + 0.5);
}

int sample_ply_write(const char* path, const sample_mesh* mesh, const sample_ply_attribute* attributes,
                     size_t attribute_count) {
  FILE* f = fopen(path, "w");
  if (f == NULL) return -1;
  fprintf(f, "ply\nformat ascii 1.0\ncomment written by a Macrocon sample\nelement vertex %zu\n", mesh->vertex_count);
  fprintf(f, "property float x\nproperty float y\nproperty float z\n");
  for (size_t a = 0; a < attribute_count; ++a) {
    const sample_ply_attribute* at = &attributes[a];
    if (is_color(at)) {
      /* Viewers (MeshLab, Blender) show red/green/blue bytes as vertex colours. */
      fprintf(f, "property uchar red\nproperty uchar green\nproperty uchar blue\n");
    } else if (at->dimension == 1) {
      fprintf(f, "property float %s\n", at->name);
    } else {
      for (uint32_t c = 0; c < at->dimension; ++c) fprintf(f, "property float %s_%u\n", at->name, c);
    }
  }
  fprintf(f, "element face %zu\nproperty list uchar int vertex_indices\nend_header\n", mesh->triangle_count);
  for (size_t v = 0; v < mesh->vertex_count; ++v) {
    fprintf(f, "%.9g %.9g %.9g", mesh->positions[3 * v], mesh->positions[3 * v + 1], mesh->positions[3 * v + 2]);
    for (size_t a = 0; a < attribute_count; ++a) {
      const sample_ply_attribute* at = &attributes[a];
      const double* row = at->values + v * at->dimension;
      for (uint32_t c = 0; c < at->dimension; ++c) {
        if (is_color(at))
          fprintf(f, " %u", (unsigned)to_byte(row[c]));
        else
          fprintf(f, " %.9g", row[c]);
      }
    }
    fputc('\n', f);
  }
  for (size_t t = 0; t < mesh->triangle_count; ++t)
    fprintf(f, "3 %u %u %u\n", mesh->indices[3 * t], mesh->indices[3 * t + 1], mesh->indices[3 * t + 2]);
  const int failed = ferror(f);
  return (fclose(f) != 0 || failed) ? -1 : 0;
}
