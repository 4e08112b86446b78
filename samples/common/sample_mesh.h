/* Sample-only file helpers shared by the samples and the starter-library generator: they are NOT
 * part of the SDK (a plugin has its host application's mesh already). Plain C99 + zlib.
 *  - sample_mesh_read_obj: an OBJ (optionally .gz) as float positions + triangles; polygons are
 *    fanned (a,b,c),(a,c,d),... so vertex numbers stay the file's (0-based).
 *  - sample_ply_write: an ASCII PLY with named per-vertex float properties. */
#ifndef MACROCON_SAMPLE_MESH_H
#define MACROCON_SAMPLE_MESH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sample_mesh {
  float* positions;    /* 3 * vertex_count */
  uint32_t* indices;   /* 3 * triangle_count */
  size_t vertex_count;
  size_t triangle_count;
} sample_mesh;

/* 0 on success; otherwise -1 with a message in `error` (error_size bytes). */
int sample_mesh_read_obj(const char* path, sample_mesh* out, char* error, size_t error_size);
void sample_mesh_free(sample_mesh* mesh);

/* A per-vertex property group written as `name` (dimension 1) or name_0, name_1, ... */
typedef struct sample_ply_attribute {
  const char* name;
  uint32_t dimension;
  const double* values; /* vertex_count * dimension, vertex-major */
} sample_ply_attribute;

/* 0 on success, -1 if the file cannot be written. */
int sample_ply_write(const char* path, const sample_mesh* mesh, const sample_ply_attribute* attributes,
                     size_t attribute_count);

#ifdef __cplusplus
}
#endif

#endif
