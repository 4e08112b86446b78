/*
 * Macrocon: retrieval and re-embedding of macro constraints for quad meshing.
 *
 * The stable C ABI. Conventions (docs/api.md has the reasoning):
 *  - Every function returns an mcon_status. MCON_OK is 0; anything else is an error, and a
 *    human-readable message for it is kept per thread: mcon_get_last_error().
 *  - Objects are opaque, reference-counted handles. *_create / *_extract return a handle with one
 *    reference; mcon_X_retain adds one, mcon_X_release drops one and frees at zero. Releasing a
 *    NULL handle is a no-op that returns MCON_OK; releasing more often than created and retained,
 *    or using a released handle, is MCON_ERROR_INVALID_ARGUMENT (objects that others hold, e.g. a
 *    map's patches, stay alive for them).
 *  - Coordinates: every |coordinate| <= 1e15 and a bounding-box diagonal >= 1e-15.
 *  - Options structs start with `uint32_t struct_size`; fill them with the matching *_init
 *    function, then change what you need. The library reads only the fields that fit inside
 *    struct_size, so code compiled against an older header keeps working. Each *_init is inline
 *    and passes sizeof the struct to the exported *_init_sized, which writes only that many bytes
 *    (bindings call *_init_sized with their struct's size).
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
  MCON_ERROR_UNKNOWN = 1,              /**< an internal error that has no better code */
  MCON_ERROR_INVALID_ARGUMENT = 2,     /**< an argument is out of its documented range */
  MCON_ERROR_NULL_POINTER = 3,         /**< a required pointer or handle is NULL */
  MCON_ERROR_STRUCT_SIZE = 4,          /**< struct_size is smaller than the first version's size */
  MCON_ERROR_OUT_OF_MEMORY = 5,
  MCON_ERROR_BUFFER_TOO_SMALL = 6,     /**< an output capacity is smaller than needed */
  MCON_ERROR_CANCELLED = 7,            /**< a progress callback returned 0 */
  MCON_ERROR_IO = 8,                   /**< a file could not be read or written */
  MCON_ERROR_NON_FINITE = 10,          /**< a coordinate or value is NaN or infinite */
  MCON_ERROR_INDEX_OUT_OF_RANGE = 11,  /**< a triangle index is >= vertex count */
  MCON_ERROR_REPEATED_INDEX = 12,      /**< a triangle uses the same vertex twice */
  MCON_ERROR_DEGENERATE_TRIANGLE = 13, /**< a triangle has zero area */
  MCON_ERROR_NON_MANIFOLD_EDGE = 14,   /**< an edge has more than two triangles */
  MCON_ERROR_NON_MANIFOLD_VERTEX = 15, /**< a vertex whose triangles do not form one fan */
  MCON_ERROR_ISOLATED_VERTEX = 16,     /**< a vertex used by no triangle */
  MCON_ERROR_EMPTY_MESH = 17,          /**< no vertices or no triangles */
  MCON_ERROR_NON_ORIENTABLE = 18,      /**< a component has no consistent orientation (a Moebius strip) */
  MCON_ERROR_NOT_A_DISK = 20,          /**< a patch is not a topological disk (handle, annulus...) */
  MCON_ERROR_NUMERICAL = 21,           /**< a linear solve or an optimization failed numerically */
  MCON_ERROR_INVALID_LIBRARY = 30,     /**< a constraint library file or buffer failed validation */
  MCON_ERROR_UNSUPPORTED = 31,         /**< a feature or format version this build does not know */
  MCON_ERROR_NOT_FOUND = 32            /**< an id or name does not exist */
} mcon_status;

/* ---------------------------------------------------------------------------------------------
 * Version and errors
 * ------------------------------------------------------------------------------------------- */

/** The version of the loaded library (compare with the MCON_VERSION_* macros of the header you
 * compiled against: the major versions must match). Any pointer may be NULL. */
MCON_API mcon_status mcon_get_version(uint32_t* major, uint32_t* minor, uint32_t* patch);

/** A static, never-freed name for a status code, e.g. "MCON_ERROR_NOT_A_DISK". */
MCON_API mcon_status mcon_get_status_name(mcon_status status, const char** name);

typedef struct mcon_context_t* mcon_context;

/** The status and message of the most recent failed call on the calling thread (MCON_OK and ""
 * if none). Querying does not clear it. The message stays valid until the next failing call on
 * this thread. `context` may be NULL (errors are kept per thread, not per context). Returns the
 * stored status; *message receives the text if message is not NULL. */
MCON_API mcon_status mcon_get_last_error(mcon_context context, const char** message);

/** Waits for the SDK's worker threads to finish. Call once before process exit (or before
 * unloading the library) after releasing every handle; hosts such as Mono or Python call it
 * from their exit hooks. Safe to call more than once; creating a new context afterwards works. */
MCON_API mcon_status mcon_shutdown(void);

/* ---------------------------------------------------------------------------------------------
 * Progress
 * ------------------------------------------------------------------------------------------- */

/** Called with a fraction in [0, 1]. Return nonzero to continue, 0 to cancel. May be called from
 * any thread, but never from two threads at once for the same operation. */
typedef int32_t (*mcon_progress_callback)(void* user_data, double fraction);

/* ---------------------------------------------------------------------------------------------
 * Context: owns the thread pool (an SDK-owned task arena) and the settings shared by all work.
 * ------------------------------------------------------------------------------------------- */

typedef void (*mcon_log_callback)(void* user_data, mcon_status status, const char* message);

typedef struct mcon_context_options {
  uint32_t struct_size;
  /** Maximum worker threads for this context's parallel work; 0 = all hardware threads.
   * Results never depend on this number. */
  uint32_t max_threads;
  /** Optional: called with every error message as it is raised (any thread). */
  mcon_log_callback log_callback;
  void* log_user_data;
} mcon_context_options;

MCON_API mcon_status mcon_context_options_init_sized(mcon_context_options* options, size_t struct_size);
static inline mcon_status mcon_context_options_init(mcon_context_options* options) {
  return mcon_context_options_init_sized(options, sizeof(*options));
}
/** `options` may be NULL for the defaults. */
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

/** The element type of mcon_mesh_desc.indices (as Embree's RTC_FORMAT_UINT3 and friends). */
typedef enum mcon_index_format {
  MCON_INDEX_FORMAT_UINT32 = 0, /**< uint32_t: the default and the only format before index_format */
  MCON_INDEX_FORMAT_INT32 = 1,  /**< int32_t (C# int[], Maya, USD); negative values are out of range */
  MCON_INDEX_FORMAT_INT64 = 2   /**< int64_t (numpy's default integer); negative values are out of range */
} mcon_index_format;

typedef enum mcon_mesh_flags {
  /** Accept defects no operation reads (zero-area triangles, edges of more than two triangles,
   * pinched and isolated vertices): each operation validates the part it reads (docs/api.md
   * "Local validation"). */
  MCON_MESH_VALIDATE_LOCALLY = 1u << 0
} mcon_mesh_flags;

typedef struct mcon_mesh_desc {
  uint32_t struct_size;
  /** vertex_count positions, 3 scalars each, `position_stride` bytes apart (0 = 3 * scalar size) */
  const void* positions;
  uint32_t position_type; /**< mcon_scalar_type */
  size_t position_stride;
  size_t vertex_count;
  /** triangle_count triangles, 3 indices each of type index_format (cast the pointer: it is read as
   * that type), `index_stride` bytes apart (0 = 3 * index size: 12, or 24 for INT64) */
  const uint32_t* indices;
  size_t index_stride;
  size_t triangle_count;
  /** (appended) mcon_index_format of `indices`; default UINT32 (also for an older struct_size). */
  uint32_t index_format;
  /** (appended) mcon_mesh_flags; default 0: the whole mesh is validated by mcon_mesh_create. */
  uint32_t flags;
} mcon_mesh_desc;

MCON_API mcon_status mcon_mesh_desc_init_sized(mcon_mesh_desc* desc, size_t struct_size);
static inline mcon_status mcon_mesh_desc_init(mcon_mesh_desc* desc) {
  return mcon_mesh_desc_init_sized(desc, sizeof(*desc));
}

/** Validates, copies and orients: each connected component is made consistent and outward
 * (docs/api.md "Input orientation"; mcon_mesh_get_orientation reports what changed). Errors:
 * NON_FINITE, INDEX_OUT_OF_RANGE (also a negative INT32/INT64 index), REPEATED_INDEX,
 * DEGENERATE_TRIANGLE, NON_MANIFOLD_EDGE, NON_ORIENTABLE, NON_MANIFOLD_VERTEX, ISOLATED_VERTEX,
 * EMPTY_MESH, each with a message naming the first offending vertex or triangle and counting the
 * others (with MCON_MESH_VALIDATE_LOCALLY the operations report the defects they read); an unknown
 * index_format or flag is INVALID_ARGUMENT. */
MCON_API mcon_status mcon_mesh_create(mcon_context context, const mcon_mesh_desc* desc, mcon_mesh* out_mesh);
MCON_API mcon_status mcon_mesh_retain(mcon_mesh mesh);
MCON_API mcon_status mcon_mesh_release(mcon_mesh mesh);
MCON_API mcon_status mcon_mesh_get_counts(mcon_mesh mesh, size_t* vertex_count, size_t* triangle_count);

/** What mcon_mesh_create changed to orient the input consistently and outward. */
typedef struct mcon_mesh_orientation_info {
  uint32_t struct_size;
  size_t reoriented_triangles;         /**< triangles whose corners 1 and 2 were swapped */
  uint32_t component_count;            /**< connected components (through shared edges) */
  uint32_t closed_component_count;     /**< of which without boundary */
  uint32_t inconsistent_component_count; /**< components whose triangles disagreed (repaired) */
  uint32_t outward_turned_component_count; /**< components that faced inward and were turned */
} mcon_mesh_orientation_info;

MCON_API mcon_status mcon_mesh_orientation_info_init_sized(mcon_mesh_orientation_info* info, size_t struct_size);
static inline mcon_status mcon_mesh_orientation_info_init(mcon_mesh_orientation_info* info) {
  return mcon_mesh_orientation_info_init_sized(info, sizeof(*info));
}
MCON_API mcon_status mcon_mesh_get_orientation(mcon_mesh mesh, mcon_mesh_orientation_info* info);
/** Per input triangle: 1 if its corners 1 and 2 were swapped (its normal reversed), else 0; the
 * mesh's barycentric inputs (mcon_patch_options.center_barycentric) stay in the caller's corner
 * order. capacity in triangles. */
MCON_API mcon_status mcon_mesh_get_reoriented_triangles(mcon_mesh mesh, uint8_t* out_flags, size_t capacity);
/** The oriented triangles, 3 indices each (the input with reoriented triangles' corners 1 and 2
 * swapped). capacity in indices. */
MCON_API mcon_status mcon_mesh_get_triangles(mcon_mesh mesh, uint32_t* out_indices, size_t capacity);
/** Closest surface points to count query points (3 doubles each): per point its triangle, 3
 * barycentric weights (the triangle's corner order) and distance; any output may be NULL. */
MCON_API mcon_status mcon_mesh_closest_points(mcon_mesh mesh, const double* xyz, size_t count, uint32_t* out_triangles,
                                              double* out_barycentric, double* out_distances);

/* ---------------------------------------------------------------------------------------------
 * Patches: geodesic disks cut out of a host mesh, normalized to geodesic radius 1.
 * ------------------------------------------------------------------------------------------- */

typedef struct mcon_patch_t* mcon_patch;

#define MCON_INVALID_INDEX 0xFFFFFFFFu

typedef enum mcon_patch_flags {
  /** Fill enclosed pockets (with host faces) and inner holes (with new, flagged triangles). */
  MCON_PATCH_FILL_HOLES = 1u << 0,
  /** On a host made with MCON_MESH_VALIDATE_LOCALLY: repair what the patch reads instead of refusing
   * it (zero-area triangles removed without a hole, pinched vertices split per fan); what changed
   * is in mcon_patch_get_repairs. Edges of more than two triangles are still refused. */
  MCON_PATCH_REPAIR_REGION = 1u << 1
} mcon_patch_flags;

typedef struct mcon_patch_options {
  uint32_t struct_size;
  /** The center: a host vertex, or (center_vertex = MCON_INVALID_INDEX) a point inside host
   * triangle center_triangle at barycentric coordinates center_barycentric. */
  uint32_t center_vertex;
  uint32_t center_triangle;
  double center_barycentric[3];
  /** Geodesic radius in host units; > 0. */
  double radius;
  /** mcon_patch_flags; default MCON_PATCH_FILL_HOLES. */
  uint32_t flags;
  /** Iso-line crossings closer to a vertex than this fraction of the local edge length snap onto
   * that vertex (avoids slivers). Default 0.2, range [0, 0.45]. */
  double snap_fraction;
  mcon_progress_callback progress;
  void* progress_user_data;
} mcon_patch_options;

MCON_API mcon_status mcon_patch_options_init_sized(mcon_patch_options* options, size_t struct_size);
static inline mcon_status mcon_patch_options_init(mcon_patch_options* options) {
  return mcon_patch_options_init_sized(options, sizeof(*options));
}

/** Cuts the geodesic disk exactly at the iso-line, keeps the center's component, fills inner
 * holes, verifies it is a disk (else MCON_ERROR_NOT_A_DISK with the reason), scales it so the
 * geodesic radius is 1 and computes its unit-disk parametrization. */
MCON_API mcon_status mcon_patch_extract(mcon_mesh host, const mcon_patch_options* options, mcon_patch* out_patch);
MCON_API mcon_status mcon_patch_retain(mcon_patch patch);
MCON_API mcon_status mcon_patch_release(mcon_patch patch);

typedef struct mcon_patch_info {
  uint32_t struct_size;
  size_t vertex_count;
  size_t triangle_count;
  size_t filled_triangle_count;   /**< triangles that are not from the host mesh */
  uint32_t boundary_loops;        /**< 1 for a valid patch */
  int32_t euler_characteristic;   /**< 1 for a valid patch */
  double radius;                  /**< geodesic radius in host units (the normalization scale) */
  double center[3];               /**< center in host coordinates (the normalization origin) */
  uint32_t center_patch_triangle; /**< the center as a point of the patch */
  double center_barycentric[3];
  double max_geodesic_distance;   /**< measured again on the normalized patch: about 1 */
  uint32_t param_flipped_triangles; /**< inverted triangles of the disk parametrization: 0 */
  /** The host's orientation repair (mcon_mesh_get_orientation): the host triangles reoriented, the
   * host components turned outward and made consistent, and how many of this patch's triangles lie
   * in a reoriented host triangle. */
  size_t host_reoriented_triangles;
  uint32_t host_outward_turned_components;
  uint32_t host_inconsistent_components;
  size_t reoriented_triangles;
} mcon_patch_info;

MCON_API mcon_status mcon_patch_info_init_sized(mcon_patch_info* info, size_t struct_size);
static inline mcon_status mcon_patch_info_init(mcon_patch_info* info) {
  return mcon_patch_info_init_sized(info, sizeof(*info));
}
MCON_API mcon_status mcon_patch_get_info(mcon_patch patch, mcon_patch_info* info);

/** What MCON_PATCH_REPAIR_REGION changed in the part of the host the patch read (all 0 without it). */
typedef struct mcon_patch_repair_info {
  uint32_t struct_size;
  uint32_t zero_area_triangles_removed; /**< zero-area triangles taken out (also those a merge emptied) */
  uint32_t triangles_split;             /**< neighbours of a removed cap split at its corner */
  uint32_t vertices_merged;             /**< coincident corners of a zero-area triangle made one vertex */
  uint32_t pinched_vertices_split;      /**< host vertices of the patch that joined separate fans */
} mcon_patch_repair_info;

MCON_API mcon_status mcon_patch_repair_info_init_sized(mcon_patch_repair_info* info, size_t struct_size);
static inline mcon_status mcon_patch_repair_info_init(mcon_patch_repair_info* info) {
  return mcon_patch_repair_info_init_sized(info, sizeof(*info));
}
MCON_API mcon_status mcon_patch_get_repairs(mcon_patch patch, mcon_patch_repair_info* info);

/** Normalized positions (host = center + radius * p), 3 doubles per vertex. capacity in doubles. */
MCON_API mcon_status mcon_patch_get_positions(mcon_patch patch, double* out_xyz, size_t capacity);
/** 3 indices per triangle, counter-clockwise as in the host. capacity in uint32 values. */
MCON_API mcon_status mcon_patch_get_triangles(mcon_patch patch, uint32_t* out_indices, size_t capacity);
/** Unit-disk parametrization (mean-value Tutte map, then stretch-reduced), 2 doubles per vertex. */
MCON_API mcon_status mcon_patch_get_uv(mcon_patch patch, double* out_uv, size_t capacity);
/** The link back to the host, per patch vertex: the vertex lies at
 * (1 - t) * host[v0] + t * host[v1]. A host vertex has v0 == v1 and t = 0. A vertex created to
 * fill a hole has v0 = v1 = MCON_INVALID_INDEX. Any output pointer may be NULL; capacity in
 * elements (vertices). */
MCON_API mcon_status mcon_patch_get_host_vertices(mcon_patch patch, uint32_t* out_v0, uint32_t* out_v1,
                                                  double* out_t, size_t capacity);
/** Per patch triangle: the host triangle it lies in (a cut triangle keeps its host triangle), or
 * MCON_INVALID_INDEX for a triangle made to fill a hole. capacity in triangles. */
MCON_API mcon_status mcon_patch_get_host_triangles(mcon_patch patch, uint32_t* out_host_triangle, size_t capacity);
/** As mcon_mesh_closest_points on the patch, with the query points and distances in host units. */
MCON_API mcon_status mcon_patch_closest_points(mcon_patch patch, const double* xyz, size_t count,
                                               uint32_t* out_triangles, double* out_barycentric, double* out_distances);

/** A point on a patch: triangle `face` and the weights of its three corners (each >= 0, sum 1). */
typedef struct mcon_surface_point {
  uint32_t face;
  double barycentric[3];
} mcon_surface_point;

/** Geodesic distance (heat method, normalized patch units) of every patch vertex from a point of
 * the patch; capacity in doubles (>= vertex count). The operators are factored on the first call
 * and kept with the patch. */
MCON_API mcon_status mcon_patch_compute_distance_from_point(mcon_patch patch, const mcon_surface_point* point,
                                                           double* out_distances, size_t capacity);
/** The same from the nearest of a set of patch vertices (order and repeats ignored), e.g. the
 * landmarks of map guidance channels. */
MCON_API mcon_status mcon_patch_compute_distance_from_vertices(mcon_patch patch, const uint32_t* vertices,
                                                              size_t vertex_count, double* out_distances,
                                                              size_t capacity);

/* ---------------------------------------------------------------------------------------------
 * Descriptors: per-vertex shape descriptors of a patch (thesis §3.1).
 * ------------------------------------------------------------------------------------------- */

typedef enum mcon_descriptor {
  /** Gaussian, mean and |max| curvature at sigma = 0.025, 0.05, 0.1 (9 values per vertex, in the
   * order K, H, |k|max for each sigma). */
  MCON_DESCRIPTOR_CURV9 = 1,
  /** Mean curvature at sigma = 0.1: the re-embedding descriptor (1 value per vertex). */
  MCON_DESCRIPTOR_MEAN_CURVATURE = 2
} mcon_descriptor;

MCON_API mcon_status mcon_descriptor_get_dimension(mcon_descriptor descriptor, uint32_t* out_dimension);
/** Writes vertex_count * dimension doubles, vertex-major. capacity in doubles. */
MCON_API mcon_status mcon_patch_compute_descriptors(mcon_patch patch, mcon_descriptor descriptor,
                                                    double* out_values, size_t capacity);

/* ---------------------------------------------------------------------------------------------
 * Constraint libraries and retrieval (mcon_library_*)
 * ------------------------------------------------------------------------------------------- */
/** A constraint library: macro constraints (a normalized disk patch, its metadata, its quad-meshing
 * constraints and per-vertex fields, its descriptors and bag-of-features histogram) plus the
 * retrieval configuration (descriptor, normalization, vocabulary, sigma, rings) they were computed
 * with, so a query needs nothing else. Files are FlatBuffers ("MCLB"); opening treats them as
 * hostile (MCON_ERROR_INVALID_LIBRARY with a message naming the problem, never a crash).
 *
 * Entries are addressed by index (0 .. count - 1, in insertion order; removing an entry shifts the
 * later ones down) and carry a stable 64-bit id (never 0). A library is not thread-safe for
 * modification; queries and getters on an unmodified library may run concurrently. */
typedef struct mcon_library_t* mcon_library;

/** Per-vertex descriptors a library is built on. CURV9 has the value of MCON_DESCRIPTOR_CURV9. */
typedef enum mcon_retrieval_descriptor {
  MCON_RETRIEVAL_DESCRIPTOR_CURV9 = 1,    /**< 9 curvature values per vertex (default) */
  MCON_RETRIEVAL_DESCRIPTOR_HKS = 3,      /**< heat kernel signature, 100 times */
  MCON_RETRIEVAL_DESCRIPTOR_WKS = 4,      /**< wave kernel signature, 100 energies */
  MCON_RETRIEVAL_DESCRIPTOR_CUSTOM = 256  /**< caller-supplied per-vertex values (any dimension) */
} mcon_retrieval_descriptor;

typedef enum mcon_polyline_kind {
  MCON_POLYLINE_GUIDE = 1,   /**< the quad mesh should follow it */
  MCON_POLYLINE_FEATURE = 2  /**< the quad mesh must preserve it */
} mcon_polyline_kind;

typedef struct mcon_polyline {
  uint32_t kind;   /**< mcon_polyline_kind */
  uint32_t closed; /**< nonzero: the last point joins the first (then >= 3 points, else >= 2) */
  const mcon_surface_point* points;
  size_t point_count;
} mcon_polyline;

/** A cross-field singularity; index in quarter turns (valence = 4 - index_quarters): +1 is a
 * valence-3 vertex, -1 a valence-5 vertex. Never 0. */
typedef struct mcon_singularity {
  mcon_surface_point location;
  int32_t index_quarters;
} mcon_singularity;

typedef enum mcon_field_kind {
  MCON_FIELD_SCALAR = 1,         /**< dimension >= 1 real channels */
  MCON_FIELD_VECTOR3 = 2,        /**< dimension 3, a vector in patch coordinates */
  MCON_FIELD_TANGENT_VECTOR = 3, /**< dimension 3, tangent to the patch */
  MCON_FIELD_INTEGER_LABEL = 4,  /**< dimension >= 1 integer channels (read from `labels`) */
  MCON_FIELD_UV = 5              /**< dimension 2 */
} mcon_field_kind;

/** A named per-vertex field of an entry: one value per patch vertex and channel. Values are stored
 * as float32 (labels as int32). */
typedef struct mcon_vertex_field {
  const char* name;       /**< non-empty, unique within the entry, UTF-8 */
  uint32_t kind;          /**< mcon_field_kind */
  uint32_t dimension;     /**< channels per vertex */
  const double* values;   /**< every kind but INTEGER_LABEL: vertex_count rows of `dimension` */
  const int32_t* labels;  /**< INTEGER_LABEL: vertex_count rows of `dimension` */
  size_t stride;          /**< bytes between two vertices' rows; 0 = tightly packed */
} mcon_vertex_field;

typedef struct mcon_library_entry_desc {
  uint32_t struct_size;
  /** The entry's geometry: mesh, center and normalization are taken from the patch. */
  mcon_patch patch;
  uint64_t id; /**< 0 = assign (largest id in the library + 1) */
  /** Metadata (UTF-8; NULL = ""). */
  const char* name;
  const char* class_label;
  const char* const* tags;
  size_t tag_count;
  const char* author;
  const char* licence;
  /** Constraints, located on the patch (faces of the patch's triangles). */
  const mcon_polyline* polylines;
  size_t polyline_count;
  const mcon_singularity* singularities;
  size_t singularity_count;
  const mcon_vertex_field* fields;
  size_t field_count;
  /** Caller-supplied descriptors (for a MCON_RETRIEVAL_DESCRIPTOR_CUSTOM library): patch vertex
   * count rows of descriptor_dimension doubles, descriptor_stride bytes apart (0 = packed). NULL
   * when the library computes its built-in descriptor. */
  const double* descriptors;
  uint32_t descriptor_dimension;
  size_t descriptor_stride;
  /** Nonzero: `up` is the up direction of the patch's host in its coordinates (any length, not
   * zero), stored with the entry for mcon_map_options.source_up. Default 0: none. */
  uint32_t has_up;
  double up[3];
} mcon_library_entry_desc;

MCON_API mcon_status mcon_library_entry_desc_init_sized(mcon_library_entry_desc* desc, size_t struct_size);
static inline mcon_status mcon_library_entry_desc_init(mcon_library_entry_desc* desc) {
  return mcon_library_entry_desc_init_sized(desc, sizeof(*desc));
}

/** An empty library (descriptor CURV9, no vocabulary yet). */
MCON_API mcon_status mcon_library_create(mcon_context context, mcon_library* out_library);
/** Reads and validates a library file: MCON_ERROR_IO (cannot read), MCON_ERROR_INVALID_LIBRARY
 * (corrupt, truncated or inconsistent; the message says what and where), MCON_ERROR_UNSUPPORTED
 * (a newer format version). `path` is UTF-8. */
MCON_API mcon_status mcon_library_open(mcon_context context, const char* path, mcon_library* out_library);
/** The same from a buffer in memory (copied; it may be freed when the call returns). */
MCON_API mcon_status mcon_library_open_memory(mcon_context context, const void* data, size_t size,
                                              mcon_library* out_library);
MCON_API mcon_status mcon_library_retain(mcon_library library);
MCON_API mcon_status mcon_library_release(mcon_library library);

/** Writes atomically (temporary file, flush, rename): if saving fails (MCON_ERROR_IO), the file
 * that was at `path` before is untouched. Same library, same bytes. Temporaries of crashed saves
 * of this file (their writer's pid gone) are removed. */
MCON_API mcon_status mcon_library_save(mcon_library library, const char* path);
/** The file's bytes into a caller buffer; *out_size receives the size needed. With out_data NULL
 * only the size is reported; otherwise capacity (bytes) must be >= that size. */
MCON_API mcon_status mcon_library_save_memory(mcon_library library, void* out_data, size_t capacity,
                                              size_t* out_size);

typedef struct mcon_library_info {
  uint32_t struct_size;
  size_t entry_count;
  uint32_t descriptor;           /**< mcon_retrieval_descriptor */
  uint32_t descriptor_dimension; /**< values per vertex; 0 before the first entry */
  uint32_t vocabulary_size;      /**< k; 0 = no vocabulary yet (queries need mcon_library_build_retrieval) */
  uint32_t rings;                /**< 1 = plain bag-of-features */
  uint32_t histogram_length;     /**< vocabulary_size * rings */
  double sigma_bof;
  uint64_t seed;
  uint32_t format_version;        /**< of the file or buffer it was opened from; 0 = made in memory */
  uint32_t checksum_verified;     /**< 1: its content checksum was verified; 0: none (format 1, or in memory) */
} mcon_library_info;

MCON_API mcon_status mcon_library_info_init_sized(mcon_library_info* info, size_t struct_size);
static inline mcon_status mcon_library_info_init(mcon_library_info* info) {
  return mcon_library_info_init_sized(info, sizeof(*info));
}
MCON_API mcon_status mcon_library_get_info(mcon_library library, mcon_library_info* info);
MCON_API mcon_status mcon_library_get_count(mcon_library library, size_t* out_count);

typedef enum mcon_library_string {
  MCON_LIBRARY_NAME = 1,
  MCON_LIBRARY_DESCRIPTION = 2,
  MCON_LIBRARY_DESCRIPTOR = 3 /**< the stored descriptor name: "curv9", "hks", "wks" or a custom one's */
} mcon_library_string;

/** A library string as UTF-8 with a terminating NUL; sizes as in mcon_library_get_entry_string. */
MCON_API mcon_status mcon_library_get_string(mcon_library library, mcon_library_string which, char* out_text,
                                             size_t capacity, size_t* out_size);
/** Sets the name or the description (UTF-8; NULL = ""); the descriptor is not a settable string. */
MCON_API mcon_status mcon_library_set_string(mcon_library library, mcon_library_string which, const char* text);
/** The built-in descriptor an empty library computes for its entries (default CURV9); a library with
 * entries changes descriptor through mcon_library_build_retrieval. */
MCON_API mcon_status mcon_library_set_descriptor(mcon_library library, uint32_t descriptor);
/** The mcon_retrieval_descriptor of a built-in descriptor's stored name ("curv9", "hks", "wks"). */
MCON_API mcon_status mcon_retrieval_descriptor_from_name(const char* name, uint32_t* out_descriptor);

/** Validates everything (constraint points on patch faces, barycentric weights, field sizes and
 * finite values...) and appends one entry; *out_id (may be NULL) receives its id. Computes the
 * entry's descriptors (or takes the caller's, see mcon_library_entry_desc) and, if the library
 * has a vocabulary, its histogram, so it is found by queries at once. Errors: INVALID_ARGUMENT
 * (naming the field), NON_FINITE, NULL_POINTER, STRUCT_SIZE; the library is unchanged. */
MCON_API mcon_status mcon_library_add_entry(mcon_library library, const mcon_library_entry_desc* desc,
                                            uint64_t* out_id);
/** MCON_ERROR_NOT_FOUND if no entry has this id. */
MCON_API mcon_status mcon_library_remove_entry(mcon_library library, uint64_t id);
MCON_API mcon_status mcon_library_find_entry(mcon_library library, uint64_t id, size_t* out_index);
/** Appends copies of all of `other`'s entries (other may be library itself). Ids already taken are
 * renumbered (largest id + 1, in order). Both must use the same descriptor and dimension. With
 * identical retrieval configurations the merged library is ready for queries; otherwise its
 * vocabulary is dropped and mcon_library_build_retrieval must run before the next query. */
MCON_API mcon_status mcon_library_merge(mcon_library library, mcon_library other);

typedef struct mcon_retrieval_options {
  uint32_t struct_size;
  uint32_t descriptor;       /* mcon_retrieval_descriptor; default CURV9. CUSTOM needs entries
                                that were added with caller-supplied descriptors. */
  uint32_t vocabulary_size;  /**< k, default 128 (fewer words if the library has fewer distinct values) */
  uint32_t rings;            /**< concentric geodesic rings, 1..64; the default is the measured best */
  double sigma_bof;          /**< soft-assignment width; 0 (default) = twice the median word distance */
  uint64_t seed;             /**< k-means seed; default 0. Same seed, same result on any thread count. */
  mcon_progress_callback progress;
  void* progress_user_data;
} mcon_retrieval_options;

MCON_API mcon_status mcon_retrieval_options_init_sized(mcon_retrieval_options* options, size_t struct_size);
static inline mcon_status mcon_retrieval_options_init(mcon_retrieval_options* options) {
  return mcon_retrieval_options_init_sized(options, sizeof(*options));
}
/** (Re)computes the descriptors if the descriptor changed, the normalization, the vocabulary
 * (k-means++) and every entry's histogram. Needs at least one entry. On error or cancel the
 * library is unchanged. */
MCON_API mcon_status mcon_library_build_retrieval(mcon_library library, const mcon_retrieval_options* options);

/** The min(n, entry count) entries nearest to the patch (L1 distance of bag-of-features
 * histograms), sorted by (distance, index). *out_count receives how many were written. Each of
 * out_ids, out_indices, out_distances may be NULL; capacity (elements) must be >= min(n, count).
 * The library's descriptor is computed on the patch (a CUSTOM library needs
 * mcon_library_query_descriptors). Errors: INVALID_ARGUMENT without a vocabulary or for n = 0. */
MCON_API mcon_status mcon_library_query(mcon_library library, mcon_patch patch, size_t n, uint64_t* out_ids,
                                        uint32_t* out_indices, double* out_distances, size_t capacity,
                                        size_t* out_count);
/** Up to n distinct suggestions: the ranking of mcon_library_query with entries of one class
 * (class_label, case and a side suffix _l/_r/_left/_right ignored; unlabelled entries each their
 * own) counted once. Per suggestion: its best entry's index, distance, a confidence in [0, 1]
 * (summing to 1 over the suggestions written) and how many other entries of its class follow it
 * (mcon_library_query lists them). Any output may be NULL; capacity in suggestions >= min(n, count). */
MCON_API mcon_status mcon_library_query_distinct(mcon_library library, mcon_patch patch, size_t n,
                                                 uint32_t* out_indices, double* out_distances, double* out_confidence,
                                                 uint32_t* out_alternative_counts, size_t capacity, size_t* out_count);
/** The same with the caller's per-vertex descriptors of the patch (vertex count rows of `dimension`
 * doubles, `stride` bytes apart, 0 = packed); dimension must be the library's. */
MCON_API mcon_status mcon_library_query_descriptors(mcon_library library, mcon_patch patch, const double* descriptors,
                                                    uint32_t dimension, size_t stride, size_t n, uint64_t* out_ids,
                                                    uint32_t* out_indices, double* out_distances, size_t capacity,
                                                    size_t* out_count);

/* ---- Reading entries (by index). Array getters check capacity (elements) first. ---- */

typedef struct mcon_library_entry_info {
  uint32_t struct_size;
  uint64_t id;
  size_t vertex_count;
  size_t triangle_count;
  size_t tag_count;
  size_t polyline_count;     /**< guides first, then features */
  size_t singularity_count;
  size_t field_count;
  mcon_surface_point center; /**< the patch center, a point of the entry's mesh */
  double source_scale;       /**< normalized = (source - source_origin) / source_scale */
  double source_origin[3];
  uint32_t has_up;           /**< 1 if the entry stores its host's up direction (`up`, source coordinates) */
  double up[3];
} mcon_library_entry_info;

MCON_API mcon_status mcon_library_entry_info_init_sized(mcon_library_entry_info* info, size_t struct_size);
static inline mcon_status mcon_library_entry_info_init(mcon_library_entry_info* info) {
  return mcon_library_entry_info_init_sized(info, sizeof(*info));
}
MCON_API mcon_status mcon_library_get_entry_info(mcon_library library, size_t index, mcon_library_entry_info* info);

typedef enum mcon_entry_string {
  MCON_ENTRY_NAME = 1,
  MCON_ENTRY_CLASS_LABEL = 2,
  MCON_ENTRY_AUTHOR = 3,
  MCON_ENTRY_LICENCE = 4,
  MCON_ENTRY_TAG = 5,       /**< tag number `item` */
  MCON_ENTRY_FIELD_NAME = 6 /**< name of field number `item` */
} mcon_entry_string;

/** A metadata string as UTF-8 with a terminating NUL. *out_size (may be NULL) receives the bytes
 * needed including the NUL; with out_text NULL only the size is reported, otherwise capacity
 * (bytes) must be >= it. `item` is ignored for the first four. */
MCON_API mcon_status mcon_library_get_entry_string(mcon_library library, size_t index, mcon_entry_string which,
                                                   size_t item, char* out_text, size_t capacity, size_t* out_size);
/** Normalized positions, 3 doubles per vertex; capacity in doubles. */
MCON_API mcon_status mcon_library_get_entry_positions(mcon_library library, size_t index, double* out_xyz,
                                                      size_t capacity);
/** 3 indices per triangle; capacity in indices. */
MCON_API mcon_status mcon_library_get_entry_triangles(mcon_library library, size_t index, uint32_t* out_indices,
                                                      size_t capacity);
/** Polyline number `polyline`: kind, closed flag and point count (each pointer may be NULL), and
 * with out_points non-NULL its points (capacity in points). */
MCON_API mcon_status mcon_library_get_entry_polyline(mcon_library library, size_t index, size_t polyline,
                                                     uint32_t* out_kind, uint32_t* out_closed, size_t* out_point_count,
                                                     mcon_surface_point* out_points, size_t capacity);
/** capacity in singularities. */
MCON_API mcon_status mcon_library_get_entry_singularities(mcon_library library, size_t index,
                                                          mcon_singularity* out_singularities, size_t capacity);
/** Field number `field`: kind and dimension (each may be NULL); with out_values (real kinds) or
 * out_labels (INTEGER_LABEL) non-NULL, vertex_count * dimension values (capacity in values).
 * Asking for the wrong one of the two is MCON_ERROR_INVALID_ARGUMENT. */
MCON_API mcon_status mcon_library_get_entry_field(mcon_library library, size_t index, size_t field,
                                                  uint32_t* out_kind, uint32_t* out_dimension, double* out_values,
                                                  int32_t* out_labels, size_t capacity);
/** The stored descriptors (vertex_count * descriptor_dimension) and histogram (histogram_length)
 * of an entry; either may be NULL; capacities in values. */
MCON_API mcon_status mcon_library_get_entry_retrieval(mcon_library library, size_t index, double* out_descriptors,
                                                      size_t descriptor_capacity, float* out_histogram,
                                                      size_t histogram_capacity);

/* ---------------------------------------------------------------------------------------------
 * Re-embedding maps and constraint transfer (mcon_map_*)
 * ------------------------------------------------------------------------------------------- */
/** Patches from plain arrays: a disk mesh that is already normalized (a constraint library entry:
 * geodesic radius about 1 around its center). Nothing is cut; the mesh must be one topological
 * disk. The frame says where the patch sits in its own host units (host = origin + scale * p),
 * which is where 3D outputs of transfers onto this patch are expressed. */
typedef struct mcon_patch_frame {
  uint32_t struct_size;
  /** The center as a point of the mesh (required: the default MCON_INVALID_INDEX is rejected). */
  uint32_t center_triangle;
  double center_barycentric[3];
  /** host = origin + scale * normalized position; default origin 0, scale 1 (> 0). */
  double origin[3];
  double scale;
} mcon_patch_frame;

MCON_API mcon_status mcon_patch_frame_init_sized(mcon_patch_frame* frame, size_t struct_size);
static inline mcon_status mcon_patch_frame_init(mcon_patch_frame* frame) {
  return mcon_patch_frame_init_sized(frame, sizeof(*frame));
}
/** Validates and copies the mesh (errors as mcon_mesh_create; triangles that disagree are reversed
 * to agree with the majority, frame.center_barycentric stays in the caller's corner order),
 * requires one disk (else MCON_ERROR_NOT_A_DISK naming the reason: several pieces, a closed
 * surface, holes or a handle) and computes its unit-disk parametrization. The patch's host is the
 * mesh itself: host vertices are the identity (t = 0), host triangles the identity. Center and
 * scale: INVALID_ARGUMENT (NON_FINITE for NaN). */
MCON_API mcon_status mcon_patch_create_from_arrays(mcon_context context, const mcon_mesh_desc* mesh,
                                                   const mcon_patch_frame* frame, mcon_patch* out_patch);

typedef struct mcon_map_t* mcon_map;

/** Why the optimization of the finest coarse-to-fine level stopped (the refinement pass after it
 * ends at its own short iteration cap by design and is not reported here). */
typedef enum mcon_map_stop_reason {
  MCON_MAP_STOP_CONVERGED = 1,     /**< the decrease fell below the tolerance */
  MCON_MAP_STOP_STALLED = 2,       /**< the line search found no acceptable step */
  MCON_MAP_STOP_ITERATION_CAP = 3, /**< max_iterations reached */
  MCON_MAP_STOP_CANCELLED = 4      /**< (never returned by a successful mcon_map_compute) */
} mcon_map_stop_reason;

/** Which orientation the map takes (mcon_map_options.orientation). */
typedef enum mcon_map_orientation {
  /** The descriptors decide; when both orientations' best rigid starts score alike (a nearly
   * mirror-symmetric patch) both are optimized at the smoothest level and the lower energy wins
   * (see mcon_map_info.orientation_compared). allow_reflection = 0 rules reflections out. */
  MCON_MAP_ORIENTATION_AUTOMATIC = 0,
  /** Forced: the best orientation-preserving rigid candidate, no comparison. */
  MCON_MAP_ORIENTATION_PRESERVE = 1,
  /** Forced: the best orientation-reversing (mirrored) rigid candidate, no comparison. */
  MCON_MAP_ORIENTATION_REVERSE = 2
} mcon_map_orientation;

typedef struct mcon_map_options {
  uint32_t struct_size;
  /** Seed of the rigid initialization's candidates; results are bit-identical for any thread
   * count. Default 0. */
  uint64_t seed;
  /** Random rigid candidates scored at initialization (half mirrored); default 10000, >= 1. */
  uint32_t alignment_samples;
  /** Nonzero (default): orientation-reversing maps (a left eye onto a right eye) may win. */
  uint32_t allow_reflection;
  /** Newton iterations per coarse-to-fine level; default 100, >= 1 (the refinement pass after the
   * finest level runs at most min(this, 10)). */
  uint32_t max_iterations;
  mcon_progress_callback progress;
  void* progress_user_data;
  /** An mcon_map_orientation, default AUTOMATIC (allow_reflection restricts only AUTOMATIC). */
  uint32_t orientation;
  /** Optional guidance channels (docs/api.md): guidance_dimension doubles per patch vertex that
   * must agree between corresponding points; rows `*_stride` bytes apart (0 = packed), copied.
   * guidance_dimension 0 (default): none, both pointers NULL. guidance_weight default 1. */
  const double* source_guidance;
  size_t source_guidance_stride;
  const double* target_guidance;
  size_t target_guidance_stride;
  uint32_t guidance_dimension;
  double guidance_weight;
  /** Gaussian width factor of the refinement pass after the finest level: in (0, 1], 0 = no
   * pass; default 0.5 (docs/api.md). */
  double refine_sigma_factor;
  /** Nonzero: the patches share a world frame (two meshes of one scene, host units as given at
   * patch creation); the similarity ICP of the source onto the target in 3D, expressed in the two
   * disk parametrizations, becomes the rigid start and decides orientation and reflection
   * (mcon_map_info.frame_decided). Needs orientation AUTOMATIC. Default 0: frame-free.
   * world_frame_mirror nonzero: mirror the source x -> -x in the world first (a left part onto a
   * right one). */
  uint32_t use_world_frame;
  uint32_t world_frame_mirror;
  /** With use_world_frame: weight of the anchor term pulling every source point towards the target
   * point closest to it in 3D after that ICP (docs/api.md); finite, >= 0, 0 = no anchor. Ignored
   * without use_world_frame. Default 10. */
  double world_frame_anchor;
  /** Nonzero: source_up / target_up are the up directions of the patches' hosts, each in its own
   * host coordinates (any length); they become a prior of the rigid start, so an upside-down map
   * is not chosen (docs/api.md). INVALID_ARGUMENT for a zero or non-finite vector or one (nearly)
   * normal to its patch at the center. Default 0: no hints. */
  uint32_t use_up_hints;
  double source_up[3];
  double target_up[3];
  /** Coarse to fine in mesh resolution (docs/api.md): the first coarse_stages optimization stages
   * run on a copy of the source coarsened to max(coarse_vertices, n / 4) vertices when the source
   * has n >= 2 * coarse_vertices (the last stage always runs on the full source); default 3 and
   * 1000, coarse_stages in [0, 8] (0 = off), coarse_vertices >= 100. */
  uint32_t coarse_stages;
  uint32_t coarse_vertices;
} mcon_map_options;

MCON_API mcon_status mcon_map_options_init_sized(mcon_map_options* options, size_t struct_size);
static inline mcon_status mcon_map_options_init(mcon_map_options* options) {
  return mcon_map_options_init_sized(options, sizeof(*options));
}

/** The re-embedding map Phi from `source` onto `target` (both patches of any tessellation; the
 * source is typically a library entry made with mcon_patch_create_from_arrays). Locally
 * injective by construction; partial: source points whose image leaves the target have no
 * correspondence. The map keeps a reference on both patches and runs in the source's context.
 * `options` may be NULL for the defaults. Before returning, phi's triangles are counted again:
 * any inverted one is MCON_ERROR_NUMERICAL. A cancelled call (CANCELLED) allocates nothing and
 * leaves *out_map NULL. Errors: NULL_POINTER, INVALID_ARGUMENT (bad handles or options),
 * STRUCT_SIZE, CANCELLED, NUMERICAL. */
MCON_API mcon_status mcon_map_compute(mcon_patch source, mcon_patch target, const mcon_map_options* options,
                                      mcon_map* out_map);
MCON_API mcon_status mcon_map_retain(mcon_map map);
MCON_API mcon_status mcon_map_release(mcon_map map);

typedef struct mcon_map_info {
  uint32_t struct_size;
  size_t source_vertex_count;
  size_t target_vertex_count;
  size_t source_vertices_inside;  /**< source vertices whose image lies on the target */
  size_t target_vertices_inside;  /**< target vertices with a source preimage */
  double overlap_ratio;           /**< source 3D area mapped into the target / source area */
  double matching_score;          /**< area-weighted Gaussian matching score in [0, 1] */
  /** Final energy terms (unweighted) and the weighted total, measured with the finest descriptor
   * level's Gaussian width (the refinement passes use a narrower one; matching_score likewise). */
  double energy_total;
  double energy_descriptor;
  double energy_distortion;
  double energy_area;
  double energy_injectivity;
  uint32_t iterations;            /**< Newton iterations over all stages */
  uint32_t stop_reason;           /**< mcon_map_stop_reason of the finest coarse-to-fine level */
  uint32_t reflected;             /**< 1 if the map reverses orientation */
  /** Optimization stages: the coarse-to-fine descriptor levels, then the refinement passes at the
   * finest level with a narrower Gaussian (by default 3 levels + 1 pass = 4). */
  uint32_t levels;
  uint32_t flipped_triangles;     /**< inverted triangles of phi: always 0 (checked) */
  double alignment_score;         /**< score of the rigid initialization */
  double alignment_seconds;
  double optimization_seconds;
  /** Rigid scores of the best orientation-preserving and best mirrored start (-1: not tried). */
  double alignment_score_unreflected;
  double alignment_score_reflected;
  /** 1 if both orientations were optimized at the smoothest level and compared (automatic mode and
   * rigid scores within the ambiguity margin); 0 for a clear call or a forced orientation. */
  uint32_t orientation_compared;
  /** The two level-0 energies of that comparison (lower is better); -1 if not compared. */
  double level0_energy_unreflected;
  double level0_energy_reflected;
  /** 1 if the world-frame start decided the orientation and the rigid start (use_world_frame), 0
   * if the descriptors did. */
  uint32_t frame_decided;
  /** Vertices of the coarse source (0: not used; see mcon_map_options.coarse_stages), the stages
   * whose coarse result was kept, the triangles the last coarse stage's prolonged map folded, and
   * 1 if those could not be untangled (an earlier stage's map, or the rigid start, went on). */
  uint32_t coarse_vertices;
  uint32_t coarse_stages;
  uint32_t coarse_folds;
  uint32_t coarse_fallback;
} mcon_map_info;

MCON_API mcon_status mcon_map_info_init_sized(mcon_map_info* info, size_t struct_size);
static inline mcon_status mcon_map_info_init(mcon_map_info* info) {
  return mcon_map_info_init_sized(info, sizeof(*info));
}
MCON_API mcon_status mcon_map_get_info(mcon_map map, mcon_map_info* info);
/** The map's energy terms in evaluation order (descriptor, distortion, area, injectivity, then any
 * later term): their number, and term `index`'s name (static storage) and final unweighted value. */
MCON_API mcon_status mcon_map_get_energy_term_count(mcon_map map, uint32_t* out_count);
MCON_API mcon_status mcon_map_get_energy_term(mcon_map map, uint32_t index, const char** out_name,
                                              double* out_value);

typedef enum mcon_map_direction {
  MCON_MAP_SOURCE_TO_TARGET = 1, /**< per source vertex: a point of the target */
  MCON_MAP_TARGET_TO_SOURCE = 2  /**< per target vertex: a point of the source */
} mcon_map_direction;

/** Per vertex of the direction's domain: the triangle of the other patch (int32, -1 = outside the
 * overlap) and 3 barycentric doubles (0 when outside). Either output may be NULL; capacity in
 * vertices. */
MCON_API mcon_status mcon_map_get_correspondences(mcon_map map, mcon_map_direction direction,
                                                  int32_t* out_triangle, double* out_barycentric, size_t capacity);
/** phi: the deformed source disk in the target disk's plane, 2 doubles per source vertex.
 * capacity in doubles. */
MCON_API mcon_status mcon_map_get_phi(mcon_map map, double* out_xy, size_t capacity);
/** Per target vertex: 1 if it lies outside the overlap (no source preimage), else 0. capacity in
 * vertices. */
MCON_API mcon_status mcon_map_get_outside_mask(mcon_map map, uint8_t* out_mask, size_t capacity);

/** Points (e.g. singularities, whose index the map keeps) of the source -> points of the target.
 * Input: count points as triangle indices and 3 barycentric weights each (>= 0, summing to 1).
 * Output, one per input point: target triangle (MCON_INVALID_INDEX if outside the overlap),
 * barycentric weights (3 per point) and the 3D position in the target's host units (3 per
 * point); any output may be NULL; capacity in points. */
MCON_API mcon_status mcon_map_transfer_points(mcon_map map, const uint32_t* triangles, const double* barycentric,
                                              size_t count, uint32_t* out_triangles, double* out_barycentric,
                                              double* out_xyz, size_t capacity);

/** Polylines on a patch: the result of a transfer, queried with counts then arrays. */
typedef struct mcon_polyline_set_t* mcon_polyline_set;

/** Guide or feature polylines of the source, mapped through Phi and re-traced on the target: every
 * segment lies inside one target triangle (polylines are split at target edges), parts outside
 * the overlap are dropped (so one input polyline may give several or none). Input: point_count
 * points (triangles + 3 barycentric each), grouped in polyline_count polylines of
 * polyline_sizes[i] >= 2 consecutive points (>= 3 if closed); polyline_closed (may be NULL = all
 * open) marks polylines whose last point joins the first. Between two consecutive points the trace
 * is the shortest path on the target through the triangles that phi-space's straight segment
 * crosses. The set keeps a reference on the target patch. */
MCON_API mcon_status mcon_map_transfer_polylines(mcon_map map, const uint32_t* triangles, const double* barycentric,
                                                 size_t point_count, const uint32_t* polyline_sizes,
                                                 const uint8_t* polyline_closed, size_t polyline_count,
                                                 mcon_polyline_set* out_polylines);
MCON_API mcon_status mcon_polyline_set_retain(mcon_polyline_set polylines);
MCON_API mcon_status mcon_polyline_set_release(mcon_polyline_set polylines);
MCON_API mcon_status mcon_polyline_set_get_counts(mcon_polyline_set polylines, size_t* polyline_count,
                                                  size_t* point_count);
/** Per polyline: its point count, whether it is closed (1/0) and the input polyline it came from.
 * Any output may be NULL; capacity in polylines. */
MCON_API mcon_status mcon_polyline_set_get_polylines(mcon_polyline_set polylines, uint32_t* out_sizes,
                                                     uint8_t* out_closed, uint32_t* out_input_polyline,
                                                     size_t capacity);
/** All points, polyline after polyline: target triangle, 3 barycentric weights, 3D position in the
 * target's host units. Point i's triangle contains the segment from point i to point i + 1 (a
 * point where the trace crosses an edge is given in the triangle it enters; the last point of an
 * open polyline in its own triangle). Any output may be NULL; capacity in points. */
MCON_API mcon_status mcon_polyline_set_get_points(mcon_polyline_set polylines, uint32_t* out_triangles,
                                                  double* out_barycentric, double* out_xyz, size_t capacity);

/* Field kinds: mcon_field_kind (declared with the library API). Integer labels go through
 * mcon_map_transfer_labels; tangent vectors are pushed forward by the map's Jacobian
 * J_g^-1 J_phi J_f and projected onto the target vertex's tangent plane, keeping the source
 * vector's (interpolated) length; the other kinds are interpolated. Dimensions: SCALAR >= 1,
 * VECTOR3 and TANGENT_VECTOR 3, UV 2 (else INVALID_ARGUMENT); NaN is NON_FINITE. */

/** A per-vertex field of the source (source_vertex_count * dimension doubles, vertex-major)
 * -> target vertices (target_vertex_count * dimension doubles). Vertices outside the overlap get
 * 0 (see mcon_map_get_outside_mask). value_count and capacity in doubles. */
MCON_API mcon_status mcon_map_transfer_field(mcon_map map, mcon_field_kind kind, uint32_t dimension,
                                             const double* source_values, size_t value_count, double* out_values,
                                             size_t capacity);
/** mcon_map_transfer_field with float32 values in and out (computed in double, rounded once at the
 * end: equal to the double call on the widened values, then cast). Counts and capacity in floats. */
MCON_API mcon_status mcon_map_transfer_field_f32(mcon_map map, mcon_field_kind kind, uint32_t dimension,
                                                 const float* source_values, size_t value_count, float* out_values,
                                                 size_t capacity);
/** Integer labels, never blended: each target vertex takes the label of the source corner with the
 * largest barycentric weight; vertices outside the overlap get outside_label. Counts in int32. */
MCON_API mcon_status mcon_map_transfer_labels(mcon_map map, uint32_t dimension, const int32_t* source_labels,
                                              size_t label_count, int32_t outside_label, int32_t* out_labels,
                                              size_t capacity);

typedef struct mcon_cross_field_options {
  uint32_t struct_size;
  /** Strength of the guide alignment against smoothness; default 10, > 0. */
  double alignment_weight;
  /** Nonzero: also align with the patch boundary (weight boundary_weight, default 1); default 0. */
  uint32_t align_to_boundary;
  double boundary_weight;
} mcon_cross_field_options;

MCON_API mcon_status mcon_cross_field_options_init_sized(mcon_cross_field_options* options, size_t struct_size);
static inline mcon_status mcon_cross_field_options_init(mcon_cross_field_options* options) {
  return mcon_cross_field_options_init_sized(options, sizeof(*options));
}
/* (`options` may be NULL for the defaults.) */
/** A smooth per-face 4-RoSy cross field on `patch` that follows the polylines (e.g. the guides of
 * mcon_map_transfer_polylines onto this patch; NULL or an empty set gives the smoothest field).
 * Per triangle one unit direction of the cross (3 doubles, normalized patch coordinates) and,
 * optionally, a confidence in [0, 1]. capacity in triangles. INVALID_ARGUMENT if the polylines
 * belong to another patch. */
MCON_API mcon_status mcon_patch_compute_cross_field(mcon_patch patch, mcon_polyline_set guides,
                                                    const mcon_cross_field_options* options, double* out_directions,
                                                    double* out_confidence, size_t capacity);
/** Writes a QuadWild `.rosy` file (one direction per triangle, as mcon_patch_compute_cross_field
 * gives them; triangle_count must equal the patch's); a `.gz` path is refused (INVALID_ARGUMENT:
 * QuadWild reads a compressed `.rosy` as zeros). IO on failure. */
MCON_API mcon_status mcon_patch_write_rosy(mcon_patch patch, const double* directions, size_t triangle_count,
                                           const char* path);

/** Guides cut into a patch: a new mesh of the patch's surface in which every guide is a chain of
 * edges, what a quad mesher's feature edges need (QuadWild `.sharp`; docs/design.md §14). */
typedef struct mcon_cut_mesh_t* mcon_cut_mesh;

typedef struct mcon_guide_cut_options {
  uint32_t struct_size;
  /** Crossings closer than this fraction of their edge to a vertex snap to it, and crossings of
   * one edge closer than that merge; default 0.25, in [0, 0.45]. */
  double snap_fraction;
  /** Guide points inside a triangle closer than this fraction of an edge to their chord are
   * dropped; default 0.05, in [0, 1]. */
  double simplify_fraction;
  /** Passes of chain fairing after the cut (each chain vertex halfway to its neighbours' midpoint,
   * on the surface); default 3, in [0, 100], 0 = off. */
  uint32_t fair_passes;
  /** How far fairing may move a chain vertex, in edge lengths; default 0.1, in [0, 0.5]. */
  double fair_max_shift;
} mcon_guide_cut_options;

MCON_API mcon_status mcon_guide_cut_options_init_sized(mcon_guide_cut_options* options, size_t struct_size);
static inline mcon_status mcon_guide_cut_options_init(mcon_guide_cut_options* options) {
  return mcon_guide_cut_options_init_sized(options, sizeof(*options));
}

typedef struct mcon_cut_mesh_info {
  uint32_t struct_size;
  size_t vertex_count;
  size_t triangle_count;
  size_t guide_count;            /**< one chain per polyline of the set (empty if it collapsed) */
  size_t guide_vertex_count;     /**< all chains' vertices together */
  size_t guide_edge_count;       /**< distinct guide edges */
  size_t cut_triangle_count;     /**< patch triangles that were retriangulated */
  double min_angle_created;      /**< degrees: the smallest angle of a triangle the cut made or moved */
  double min_angle_of_cut_input; /**< degrees: the smallest angle of the patch triangles it cut */
  uint32_t snapped_to_vertices;  /**< crossings moved onto a patch vertex */
  uint32_t merged_crossings;     /**< crossings merged with another of the same edge */
  uint32_t dropped_points;       /**< guide points dropped as adding no shape */
  uint32_t shortcuts;            /**< steps through a snapped vertex replaced by the edge across */
  uint32_t moved_vertices;       /**< snapped patch vertices moved onto their guide */
  /** mcon_mesh_cut_guides only: guide points on patch triangles that fill a hole of the host
   * (dropped), and the guides split into pieces there. */
  uint32_t unplaced_points;
  uint32_t split_guides;
  uint32_t faired_vertices;      /**< chain vertices moved by fairing (mcon_guide_cut_options.fair_passes) */
} mcon_cut_mesh_info;

MCON_API mcon_status mcon_cut_mesh_info_init_sized(mcon_cut_mesh_info* info, size_t struct_size);
static inline mcon_status mcon_cut_mesh_info_init(mcon_cut_mesh_info* info) {
  return mcon_cut_mesh_info_init_sized(info, sizeof(*info));
}
/** Cuts `guides` (polylines transferred onto `patch`) into the patch. `options` may be NULL.
 * INVALID_ARGUMENT if the guides lie on another patch or a guide crosses itself. The cut mesh keeps
 * a reference on the patch. */
MCON_API mcon_status mcon_patch_cut_guides(mcon_patch patch, mcon_polyline_set guides,
                                           const mcon_guide_cut_options* options, mcon_cut_mesh* out_cut);
/** Cuts the guides of one or several macro constraints into the whole host: `guide_sets[i]` lie on
 * patches extracted from `mesh` (e.g. both eyes and the mouth), and the result covers every face of
 * `mesh`, so its cross field and QuadWild files cover the whole model (docs/design.md §15).
 * Positions are the mesh's; host points are mesh triangles. INVALID_ARGUMENT if a set lies on a
 * patch that was not extracted from `mesh` or a guide crosses itself. The cut mesh keeps a
 * reference on the mesh. */
MCON_API mcon_status mcon_mesh_cut_guides(mcon_mesh mesh, const mcon_polyline_set* guide_sets, size_t set_count,
                                          const mcon_guide_cut_options* options, mcon_cut_mesh* out_cut);
MCON_API mcon_status mcon_cut_mesh_retain(mcon_cut_mesh cut);
MCON_API mcon_status mcon_cut_mesh_release(mcon_cut_mesh cut);
MCON_API mcon_status mcon_cut_mesh_get_info(mcon_cut_mesh cut, mcon_cut_mesh_info* info);
/** Vertex positions in the patch's host units (3 doubles each); capacity in doubles. */
MCON_API mcon_status mcon_cut_mesh_get_positions(mcon_cut_mesh cut, double* out_xyz, size_t capacity);
/** Triangles (3 indices each, the patch's winding); capacity in indices. */
MCON_API mcon_status mcon_cut_mesh_get_triangles(mcon_cut_mesh cut, uint32_t* out_indices, size_t capacity);
/** Per vertex its point on the patch (on the mesh for mcon_mesh_cut_guides): triangle and 3 weights.
 * Either may be NULL; capacity in vertices. */
MCON_API mcon_status mcon_cut_mesh_get_host_points(mcon_cut_mesh cut, uint32_t* out_patch_triangles,
                                                   double* out_barycentric, size_t capacity);
/** The distinct guide edges as vertex pairs (2 indices each); capacity in indices. */
MCON_API mcon_status mcon_cut_mesh_get_guide_edges(mcon_cut_mesh cut, uint32_t* out_edges, size_t capacity);
/** Per guide its chain length (capacity in guides) and the chains' vertices one after the other
 * (capacity in vertices; a closed guide repeats its first vertex at its end). Either may be NULL. */
MCON_API mcon_status mcon_cut_mesh_get_guides(mcon_cut_mesh cut, uint32_t* out_sizes, size_t size_capacity,
                                              uint32_t* out_vertices, size_t vertex_capacity);
/** Per guide chain the guide set (0 for mcon_patch_cut_guides) and the polyline of that set it comes
 * from (a polyline split at a filled hole gives several chains). Either may be NULL; capacity in guides. */
MCON_API mcon_status mcon_cut_mesh_get_guide_origins(mcon_cut_mesh cut, uint32_t* out_sets, uint32_t* out_polylines,
                                                     size_t capacity);
/** A per-vertex field of the patch (of the mesh for mcon_mesh_cut_guides; vertices x dimension
 * doubles) at the cut mesh's vertices, interpolated at their host points; counts and capacity in doubles. */
MCON_API mcon_status mcon_cut_mesh_carry_field(mcon_cut_mesh cut, uint32_t dimension, const double* patch_values,
                                               size_t value_count, double* out_values, size_t capacity);
/** A per-face 4-RoSy cross field on the cut mesh that lies exactly along the guide edges on their
 * faces and is smooth elsewhere (3 doubles per triangle); capacity in triangles. */
MCON_API mcon_status mcon_cut_mesh_compute_cross_field(mcon_cut_mesh cut, double* out_directions, size_t capacity);
/** Writes QuadWild's inputs side by side: `<path_prefix>.obj` (host units, exact doubles),
 * `<path_prefix>.rosy` (mcon_cut_mesh_compute_cross_field) and `<path_prefix>.sharp` (the guide
 * edges; convex/concave from the dihedral angle), and `<path_prefix>.quadwild.json` (face count,
 * the OBJ's FNV-1a 64 hash, QuadWild's command lines). IO on failure. */
MCON_API mcon_status mcon_cut_mesh_write_quadwild(mcon_cut_mesh cut, const char* path_prefix);

#ifdef __cplusplus
}
#endif

#endif /* MACROCON_H */
