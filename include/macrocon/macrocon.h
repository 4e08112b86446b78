/*
 * Macrocon: retrieval and re-embedding of macro constraints for quad meshing.
 *
 * The stable C ABI. Conventions (see README "C API conventions"):
 *  - Every function returns an mcon_status. MCON_OK is 0; anything else is an error, and a
 *    human-readable message for it is kept per thread: mcon_get_last_error().
 *  - Objects are opaque, reference-counted handles. *_create / *_extract return a handle with one
 *    reference; mcon_X_retain adds one, mcon_X_release drops one and frees at zero. Releasing a
 *    NULL handle is a no-op that returns MCON_OK.
 *  - Options structs start with `uint32_t struct_size`; fill them with the matching *_init
 *    function, then change what you need. The library reads only the fields that fit inside
 *    struct_size, so code compiled against an older header keeps working.
 *  - Input arrays are pointer + byte stride + count and are copied: the caller may free them
 *    as soon as the call returns. A stride of 0 means tightly packed.
 *  - Output arrays are caller-owned; the caller passes their capacity in elements and gets
 *    MCON_ERROR_BUFFER_TOO_SMALL (and nothing written) if it is too small.
 *  - Progress callbacks may be called from any thread; returning 0 cancels the operation,
 *    which then returns MCON_ERROR_CANCELLED and leaves every object valid.
 *  - No C++ exception crosses this boundary. Handles may be used from several threads as long as
 *    a single handle is not modified concurrently; read-only queries are thread-safe.
 */
#ifndef MACROCON_H
#define MACROCON_H

#include <stddef.h>
#include <stdint.h>

#define MCON_VERSION_MAJOR 0
#define MCON_VERSION_MINOR 1
#define MCON_VERSION_PATCH 0
/* Encoded as major * 10000 + minor * 100 + patch. */
#define MCON_VERSION (MCON_VERSION_MAJOR * 10000 + MCON_VERSION_MINOR * 100 + MCON_VERSION_PATCH)

#if defined(_WIN32)
#  if defined(MACROCON_BUILDING_LIBRARY)
#    define MCON_API __declspec(dllexport)
#  else
#    define MCON_API __declspec(dllimport)
#  endif
#else
#  define MCON_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Status codes (a 32-bit signed integer in every binding).
 * ------------------------------------------------------------------------------------------- */
typedef enum mcon_status {
  MCON_OK = 0,
  MCON_ERROR_UNKNOWN = 1,              /* an internal error that has no better code */
  MCON_ERROR_INVALID_ARGUMENT = 2,     /* an argument is out of its documented range */
  MCON_ERROR_NULL_POINTER = 3,         /* a required pointer or handle is NULL */
  MCON_ERROR_STRUCT_SIZE = 4,          /* struct_size is smaller than the first version's size */
  MCON_ERROR_OUT_OF_MEMORY = 5,
  MCON_ERROR_BUFFER_TOO_SMALL = 6,     /* an output capacity is smaller than needed */
  MCON_ERROR_CANCELLED = 7,            /* a progress callback returned 0 */
  MCON_ERROR_IO = 8,                   /* a file could not be read or written */
  MCON_ERROR_NON_FINITE = 10,          /* a coordinate or value is NaN or infinite */
  MCON_ERROR_INDEX_OUT_OF_RANGE = 11,  /* a triangle index is >= vertex count */
  MCON_ERROR_REPEATED_INDEX = 12,      /* a triangle uses the same vertex twice */
  MCON_ERROR_DEGENERATE_TRIANGLE = 13, /* a triangle has zero area */
  MCON_ERROR_NON_MANIFOLD_EDGE = 14,   /* an edge has more than two triangles, or they disagree in orientation */
  MCON_ERROR_NON_MANIFOLD_VERTEX = 15, /* a vertex whose triangles do not form one fan */
  MCON_ERROR_ISOLATED_VERTEX = 16,     /* a vertex used by no triangle */
  MCON_ERROR_EMPTY_MESH = 17,          /* no vertices or no triangles */
  MCON_ERROR_NOT_A_DISK = 20,          /* a patch is not a topological disk (handle, annulus...) */
  MCON_ERROR_NUMERICAL = 21,           /* a linear solve or an optimization failed numerically */
  MCON_ERROR_INVALID_LIBRARY = 30,     /* a constraint library file or buffer failed validation */
  MCON_ERROR_UNSUPPORTED = 31,         /* a feature or format version this build does not know */
  MCON_ERROR_NOT_FOUND = 32            /* an id or name does not exist */
} mcon_status;

/* ---------------------------------------------------------------------------------------------
 * Version and errors
 * ------------------------------------------------------------------------------------------- */

/* The version of the loaded library (compare with the MCON_VERSION_* macros of the header you
 * compiled against: the major versions must match). Any pointer may be NULL. */
MCON_API mcon_status mcon_get_version(uint32_t* major, uint32_t* minor, uint32_t* patch);

/* A static, never-freed name for a status code, e.g. "MCON_ERROR_NOT_A_DISK". */
MCON_API mcon_status mcon_get_status_name(mcon_status status, const char** name);

typedef struct mcon_context_t* mcon_context;

/* The status and message of the most recent failed call on the calling thread (MCON_OK and ""
 * if none). Querying does not clear it. The message stays valid until the next failing call on
 * this thread. `context` may be NULL (errors are kept per thread, not per context). Returns the
 * stored status; *message receives the text if message is not NULL. */
MCON_API mcon_status mcon_get_last_error(mcon_context context, const char** message);

/* Waits for the SDK's worker threads to finish. Call once before process exit (or before
 * unloading the library) after releasing every handle; hosts such as Mono or Python call it
 * from their exit hooks. Safe to call more than once; creating a new context afterwards works. */
MCON_API mcon_status mcon_shutdown(void);

/* ---------------------------------------------------------------------------------------------
 * Progress
 * ------------------------------------------------------------------------------------------- */

/* Called with a fraction in [0, 1]. Return nonzero to continue, 0 to cancel. May be called from
 * any thread, but never from two threads at once for the same operation. */
typedef int32_t (*mcon_progress_callback)(void* user_data, double fraction);

/* ---------------------------------------------------------------------------------------------
 * Context: owns the thread pool (an SDK-owned task arena) and the settings shared by all work.
 * ------------------------------------------------------------------------------------------- */

typedef void (*mcon_log_callback)(void* user_data, mcon_status status, const char* message);

typedef struct mcon_context_options {
  uint32_t struct_size;
  /* Maximum worker threads for this context's parallel work; 0 = all hardware threads.
   * Results never depend on this number. */
  uint32_t max_threads;
  /* Optional: called with every error message as it is raised (any thread). */
  mcon_log_callback log_callback;
  void* log_user_data;
} mcon_context_options;

MCON_API mcon_status mcon_context_options_init(mcon_context_options* options);
/* `options` may be NULL for the defaults. */
MCON_API mcon_status mcon_context_create(const mcon_context_options* options, mcon_context* out_context);
MCON_API mcon_status mcon_context_retain(mcon_context context);
MCON_API mcon_status mcon_context_release(mcon_context context);

/* ---------------------------------------------------------------------------------------------
 * Meshes: validated, manifold triangle meshes built from plain arrays (copied).
 * ------------------------------------------------------------------------------------------- */

typedef struct mcon_mesh_t* mcon_mesh;

typedef enum mcon_scalar_type {
  MCON_SCALAR_FLOAT32 = 1,
  MCON_SCALAR_FLOAT64 = 2
} mcon_scalar_type;

typedef struct mcon_mesh_desc {
  uint32_t struct_size;
  /* vertex_count positions, 3 scalars each, `position_stride` bytes apart (0 = 3 * scalar size) */
  const void* positions;
  uint32_t position_type; /* mcon_scalar_type */
  size_t position_stride;
  size_t vertex_count;
  /* triangle_count triangles, 3 uint32 indices each, `index_stride` bytes apart (0 = 12) */
  const uint32_t* indices;
  size_t index_stride;
  size_t triangle_count;
} mcon_mesh_desc;

MCON_API mcon_status mcon_mesh_desc_init(mcon_mesh_desc* desc);

/* Validates and copies. Errors: NON_FINITE, INDEX_OUT_OF_RANGE, REPEATED_INDEX,
 * DEGENERATE_TRIANGLE, NON_MANIFOLD_EDGE, NON_MANIFOLD_VERTEX, ISOLATED_VERTEX, EMPTY_MESH, each
 * with a message naming the first offending vertex or triangle. */
MCON_API mcon_status mcon_mesh_create(mcon_context context, const mcon_mesh_desc* desc, mcon_mesh* out_mesh);
MCON_API mcon_status mcon_mesh_retain(mcon_mesh mesh);
MCON_API mcon_status mcon_mesh_release(mcon_mesh mesh);
MCON_API mcon_status mcon_mesh_get_counts(mcon_mesh mesh, size_t* vertex_count, size_t* triangle_count);

/* ---------------------------------------------------------------------------------------------
 * Patches: geodesic disks cut out of a host mesh, normalized to geodesic radius 1.
 * ------------------------------------------------------------------------------------------- */

typedef struct mcon_patch_t* mcon_patch;

#define MCON_INVALID_INDEX 0xFFFFFFFFu

typedef enum mcon_patch_flags {
  /* Fill enclosed pockets (with host faces) and inner holes (with new, flagged triangles). */
  MCON_PATCH_FILL_HOLES = 1u << 0
} mcon_patch_flags;

typedef struct mcon_patch_options {
  uint32_t struct_size;
  /* The center: a host vertex, or (center_vertex = MCON_INVALID_INDEX) a point inside host
   * triangle center_triangle at barycentric coordinates center_barycentric. */
  uint32_t center_vertex;
  uint32_t center_triangle;
  double center_barycentric[3];
  /* Geodesic radius in host units; > 0. */
  double radius;
  /* mcon_patch_flags; default MCON_PATCH_FILL_HOLES. */
  uint32_t flags;
  /* Iso-line crossings closer to a vertex than this fraction of the local edge length snap onto
   * that vertex (avoids slivers). Default 0.2, range [0, 0.45]. */
  double snap_fraction;
  mcon_progress_callback progress;
  void* progress_user_data;
} mcon_patch_options;

MCON_API mcon_status mcon_patch_options_init(mcon_patch_options* options);

/* Cuts the geodesic disk exactly at the iso-line, keeps the center's component, fills inner
 * holes, verifies it is a disk (else MCON_ERROR_NOT_A_DISK with the reason), scales it so the
 * geodesic radius is 1 and computes its unit-disk parametrization. */
MCON_API mcon_status mcon_patch_extract(mcon_mesh host, const mcon_patch_options* options, mcon_patch* out_patch);
MCON_API mcon_status mcon_patch_retain(mcon_patch patch);
MCON_API mcon_status mcon_patch_release(mcon_patch patch);

typedef struct mcon_patch_info {
  uint32_t struct_size;
  size_t vertex_count;
  size_t triangle_count;
  size_t filled_triangle_count;   /* triangles that are not from the host mesh */
  uint32_t boundary_loops;        /* 1 for a valid patch */
  int32_t euler_characteristic;   /* 1 for a valid patch */
  double radius;                  /* geodesic radius in host units (the normalization scale) */
  double center[3];               /* center in host coordinates (the normalization origin) */
  uint32_t center_patch_triangle; /* the center as a point of the patch */
  double center_barycentric[3];
  double max_geodesic_distance;   /* measured again on the normalized patch: about 1 */
  uint32_t param_flipped_triangles; /* inverted triangles of the disk parametrization: 0 */
} mcon_patch_info;

MCON_API mcon_status mcon_patch_info_init(mcon_patch_info* info);
MCON_API mcon_status mcon_patch_get_info(mcon_patch patch, mcon_patch_info* info);

/* Normalized positions (host = center + radius * p), 3 doubles per vertex. capacity in doubles. */
MCON_API mcon_status mcon_patch_get_positions(mcon_patch patch, double* out_xyz, size_t capacity);
/* 3 indices per triangle, counter-clockwise as in the host. capacity in uint32 values. */
MCON_API mcon_status mcon_patch_get_triangles(mcon_patch patch, uint32_t* out_indices, size_t capacity);
/* Unit-disk parametrization (Tutte, mean-value weights), 2 doubles per vertex. */
MCON_API mcon_status mcon_patch_get_uv(mcon_patch patch, double* out_uv, size_t capacity);
/* The link back to the host, per patch vertex: the vertex lies at
 * (1 - t) * host[v0] + t * host[v1]. A host vertex has v0 == v1 and t = 0. A vertex created to
 * fill a hole has v0 = v1 = MCON_INVALID_INDEX. Any output pointer may be NULL; capacity in
 * elements (vertices). */
MCON_API mcon_status mcon_patch_get_host_vertices(mcon_patch patch, uint32_t* out_v0, uint32_t* out_v1,
                                                  double* out_t, size_t capacity);
/* Per patch triangle: the host triangle it lies in (a cut triangle keeps its host triangle), or
 * MCON_INVALID_INDEX for a triangle made to fill a hole. capacity in triangles. */
MCON_API mcon_status mcon_patch_get_host_triangles(mcon_patch patch, uint32_t* out_host_triangle, size_t capacity);

/* ---------------------------------------------------------------------------------------------
 * Descriptors: per-vertex shape descriptors of a patch (thesis §3.1).
 * ------------------------------------------------------------------------------------------- */

typedef enum mcon_descriptor {
  /* Gaussian, mean and |max| curvature at sigma = 0.025, 0.05, 0.1 (9 values per vertex, in the
   * order K, H, |k|max for each sigma). */
  MCON_DESCRIPTOR_CURV9 = 1,
  /* Mean curvature at sigma = 0.1: the re-embedding descriptor (1 value per vertex). */
  MCON_DESCRIPTOR_MEAN_CURVATURE = 2
} mcon_descriptor;

MCON_API mcon_status mcon_descriptor_get_dimension(mcon_descriptor descriptor, uint32_t* out_dimension);
/* Writes vertex_count * dimension doubles, vertex-major. capacity in doubles. */
MCON_API mcon_status mcon_patch_compute_descriptors(mcon_patch patch, mcon_descriptor descriptor,
                                                    double* out_values, size_t capacity);

/* ---------------------------------------------------------------------------------------------
 * Constraint libraries and retrieval (mcon_library_*)
 * ------------------------------------------------------------------------------------------- */
/* @@library-api@@ (insertion point; keep this line) */

/* ---------------------------------------------------------------------------------------------
 * Re-embedding maps and constraint transfer (mcon_map_*)
 * ------------------------------------------------------------------------------------------- */
/* @@map-api@@ (insertion point; keep this line) */

#ifdef __cplusplus
}
#endif

#endif /* MACROCON_H */
