// Macrocon C++17 wrapper: header-only RAII classes over the C ABI of macrocon.h (and nothing
// else, so it works with any build of the library whose major version matches).
//  - Every failing C call throws macrocon::Error (status + the message of mcon_get_last_error).
//  - Context, Mesh, Patch own one reference to their handle: copy = retain, move = steal,
//    destructor = release. A moved-from object holds no handle (operator bool is false); using
//    it throws Error(MCON_ERROR_NULL_POINTER).
//  - Arrays come back as std::vector; inputs are copied by the library, as in C.
#ifndef MACROCON_HPP
#define MACROCON_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "macrocon.h"

namespace macrocon {

/// A failed call: the C status and the library's message.
class Error : public std::runtime_error {
 public:
  Error(mcon_status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  mcon_status status() const noexcept { return status_; }

 private:
  mcon_status status_;
};

/// "MCON_ERROR_NOT_A_DISK" etc.; "unknown status N" for a code this library does not know.
inline std::string status_name(mcon_status status) {
  const char* name = nullptr;
  if (mcon_get_status_name(status, &name) != MCON_OK || name == nullptr)
    return "unknown status " + std::to_string(static_cast<int>(status));
  return name;
}

/// Throws Error for anything but MCON_OK, with the calling thread's last error message.
inline void check(mcon_status status) {
  if (status == MCON_OK) return;
  const char* message = nullptr;
  const mcon_status stored = mcon_get_last_error(nullptr, &message);
  std::string text = (stored == status && message != nullptr && message[0] != '\0') ? message : status_name(status);
  throw Error(status, text);
}

struct Version {
  std::uint32_t major = 0, minor = 0, patch = 0;
  std::uint32_t encoded() const { return major * 10000 + minor * 100 + patch; }
  std::string to_string() const {
    return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
  }
};

/// The version of the loaded library.
inline Version library_version() {
  Version v;
  check(mcon_get_version(&v.major, &v.minor, &v.patch));
  return v;
}

/// The version of the header this code was compiled against.
inline constexpr Version header_version() {
  return Version{MCON_VERSION_MAJOR, MCON_VERSION_MINOR, MCON_VERSION_PATCH};
}

/// True if the loaded library can be used with this header (same major version).
inline bool is_compatible() { return library_version().major == header_version().major; }

/// Waits for the SDK's worker threads (mcon_shutdown): call after every object is destroyed.
inline void shutdown() { check(mcon_shutdown()); }

namespace detail {

/// One counted reference to a C handle.
template <typename Handle, mcon_status (*Retain)(Handle), mcon_status (*Release)(Handle)>
class Ref {
 public:
  Ref() noexcept = default;
  /// Takes over a reference the caller owns (e.g. fresh from a *_create call).
  explicit Ref(Handle handle) noexcept : handle_(handle) {}
  Ref(const Ref& other) : handle_(other.handle_) {
    if (handle_) check(Retain(handle_));
  }
  Ref(Ref&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Ref& operator=(const Ref& other) {
    if (this != &other) {
      if (other.handle_) check(Retain(other.handle_));
      reset();
      handle_ = other.handle_;
    }
    return *this;
  }
  Ref& operator=(Ref&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  ~Ref() { reset(); }

  void reset() noexcept {
    if (handle_) Release(std::exchange(handle_, nullptr));
  }
  Handle get() const noexcept { return handle_; }
  /// Gives up ownership without releasing: the caller now owns the reference.
  Handle detach() noexcept { return std::exchange(handle_, nullptr); }

 private:
  Handle handle_ = nullptr;
};

/// Throws for a default-constructed or moved-from object instead of passing NULL to C.
template <typename Handle>
Handle require(Handle handle, const char* what) {
  if (handle == nullptr)
    throw Error(MCON_ERROR_NULL_POINTER, std::string("macrocon::") + what + " holds no handle (moved from?)");
  return handle;
}

}  // namespace detail

/// The root object: thread pool and settings. Every Mesh and Patch keeps its context alive.
/// `Context ctx;` makes a working context with default options; `Context ctx(nullptr);` an empty one.
class Context {
 public:
  struct Options {
    /// 0 = all hardware threads. Results never depend on it.
    std::uint32_t max_threads = 0;
    /// Optional error log (any thread). user_data must outlive every object of this context.
    mcon_log_callback log_callback = nullptr;
    void* log_user_data = nullptr;
  };

  Context() : Context(Options{}) {}
  explicit Context(const Options& options) : Context(to_c(options)) {}
  explicit Context(const mcon_context_options& options) {
    mcon_context handle = nullptr;
    check(mcon_context_create(&options, &handle));
    ref_ = Ref(handle);
  }
  explicit Context(std::nullptr_t) noexcept {}
  /// Takes over a reference the caller owns.
  static Context adopt(mcon_context handle) noexcept {
    Context c(nullptr);
    c.ref_ = Ref(handle);
    return c;
  }

  mcon_context get() const noexcept { return ref_.get(); }
  mcon_context detach() noexcept { return ref_.detach(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  using Ref = detail::Ref<mcon_context, mcon_context_retain, mcon_context_release>;
  static mcon_context_options to_c(const Options& options) {
    mcon_context_options c;
    check(mcon_context_options_init(&c));
    c.max_threads = options.max_threads;
    c.log_callback = options.log_callback;
    c.log_user_data = options.log_user_data;
    return c;
  }

  Ref ref_;
};

/// Closest surface points (Mesh::closest_points, Patch::closest_points), one per query point.
struct ClosestPoints {
  std::vector<std::uint32_t> triangles;
  std::vector<double> barycentric;  ///< 3 per point, in the triangle's corner order
  std::vector<double> distances;    ///< host units
  std::size_t size() const { return triangles.size(); }
};

namespace detail {
template <typename Handle, typename Call>
ClosestPoints closest_points(Handle handle, const std::vector<double>& xyz, const Call& call) {
  if (xyz.size() % 3 != 0)
    throw Error(MCON_ERROR_INVALID_ARGUMENT,
                "closest_points: " + std::to_string(xyz.size()) + " coordinates are not a multiple of 3");
  const std::size_t n = xyz.size() / 3;
  ClosestPoints c;
  c.triangles.resize(n);
  c.barycentric.resize(3 * n);
  c.distances.resize(n);
  check(call(handle, xyz.data(), n, c.triangles.data(), c.barycentric.data(), c.distances.data()));
  return c;
}

/// A string out of the C convention: call(text, capacity, &size) once for the size (text NULL),
/// then into a buffer; size counts the terminating NUL.
template <typename Call>
std::string read_string(const Call& call) {
  std::size_t size = 0;
  check(call(nullptr, 0, &size));
  std::string s(size, '\0');
  check(call(&s[0], s.size(), &size));
  s.resize(size > 0 ? size - 1 : 0);
  return s;
}

/// Carries a std::function through a C progress callback; an exception becomes "cancel" and is
/// rethrown by the call that took the callback (no exception may cross the C boundary).
struct ProgressForward {
  const std::function<bool(double)>* function;
  std::exception_ptr exception;
  static std::int32_t call(void* user, double fraction) {
    auto* self = static_cast<ProgressForward*>(user);
    try {
      return (*self->function)(fraction) ? 1 : 0;
    } catch (...) {
      self->exception = std::current_exception();
      return 0;
    }
  }
};
}  // namespace detail

/// A validated, manifold triangle mesh (the library keeps its own copy of the arrays).
class Mesh {
 public:
  /// Flat arrays: positions = x0 y0 z0 x1 ..., indices = a0 b0 c0 a1 ...; flags: mcon_mesh_flags
  /// (MCON_MESH_VALIDATE_LOCALLY).
  template <typename Scalar>
  static Mesh from_arrays(const Context& context, const std::vector<Scalar>& positions,
                          const std::vector<std::uint32_t>& indices, std::uint32_t flags = 0) {
    return from_indices(context, positions, indices.data(), indices.size(), MCON_INDEX_FORMAT_UINT32, flags);
  }
  /// int32 (MCON_INDEX_FORMAT_INT32) or int64 (INT64) indices, read as they are.
  template <typename Scalar>
  static Mesh from_arrays(const Context& context, const std::vector<Scalar>& positions,
                          const std::vector<std::int32_t>& indices, std::uint32_t flags = 0) {
    return from_indices(context, positions, indices.data(), indices.size(), MCON_INDEX_FORMAT_INT32, flags);
  }
  template <typename Scalar>
  static Mesh from_arrays(const Context& context, const std::vector<Scalar>& positions,
                          const std::vector<std::int64_t>& indices, std::uint32_t flags = 0) {
    return from_indices(context, positions, indices.data(), indices.size(), MCON_INDEX_FORMAT_INT64, flags);
  }
  /// Strided arrays: strides in bytes, 0 = tightly packed.
  static Mesh from_arrays(const Context& context, const float* positions, std::size_t position_stride,
                          std::size_t vertex_count, const std::uint32_t* indices, std::size_t index_stride,
                          std::size_t triangle_count) {
    return from_desc(context, desc(positions, MCON_SCALAR_FLOAT32, position_stride, vertex_count, indices,
                                   index_stride, triangle_count));
  }
  static Mesh from_arrays(const Context& context, const double* positions, std::size_t position_stride,
                          std::size_t vertex_count, const std::uint32_t* indices, std::size_t index_stride,
                          std::size_t triangle_count) {
    return from_desc(context, desc(positions, MCON_SCALAR_FLOAT64, position_stride, vertex_count, indices,
                                   index_stride, triangle_count));
  }
  static Mesh from_desc(const Context& context, const mcon_mesh_desc& d) {
    mcon_mesh handle = nullptr;
    check(mcon_mesh_create(detail::require(context.get(), "Context"), &d, &handle));
    return adopt(handle);
  }

  /// An empty mesh object (no handle).
  Mesh() noexcept = default;
  /// Takes over a reference the caller owns.
  static Mesh adopt(mcon_mesh handle) noexcept {
    Mesh m;
    m.ref_ = detail::Ref<mcon_mesh, mcon_mesh_retain, mcon_mesh_release>(handle);
    return m;
  }

  std::size_t vertex_count() const { return counts().first; }
  std::size_t triangle_count() const { return counts().second; }

  /// What creating the mesh changed to orient it consistently and outward.
  mcon_mesh_orientation_info orientation() const {
    mcon_mesh_orientation_info i;
    check(mcon_mesh_orientation_info_init(&i));
    check(mcon_mesh_get_orientation(detail::require(get(), "Mesh"), &i));
    return i;
  }
  /// Per input triangle: 1 if its corners 1 and 2 were swapped.
  std::vector<std::uint8_t> reoriented_triangles() const {
    std::vector<std::uint8_t> out(triangle_count());
    check(mcon_mesh_get_reoriented_triangles(detail::require(get(), "Mesh"), out.data(), out.size()));
    return out;
  }
  /// The oriented triangles, 3 indices each.
  std::vector<std::uint32_t> triangles() const {
    std::vector<std::uint32_t> out(3 * triangle_count());
    check(mcon_mesh_get_triangles(detail::require(get(), "Mesh"), out.data(), out.size()));
    return out;
  }
  /// The closest surface point to each of the points (x0 y0 z0 x1 ...).
  ClosestPoints closest_points(const std::vector<double>& xyz) const {
    return detail::closest_points(detail::require(get(), "Mesh"), xyz, mcon_mesh_closest_points);
  }

  mcon_mesh get() const noexcept { return ref_.get(); }
  mcon_mesh detach() noexcept { return ref_.detach(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  static void check_flat(std::size_t positions, std::size_t indices) {
    if (positions % 3 != 0 || indices % 3 != 0)
      throw Error(MCON_ERROR_INVALID_ARGUMENT, "macrocon::Mesh::from_arrays: array sizes " +
                                                   std::to_string(positions) + " and " + std::to_string(indices) +
                                                   " are not multiples of 3");
  }
  static mcon_mesh_desc desc(const void* positions, mcon_scalar_type type, std::size_t position_stride,
                             std::size_t vertex_count, const std::uint32_t* indices, std::size_t index_stride,
                             std::size_t triangle_count) {
    mcon_mesh_desc d;
    check(mcon_mesh_desc_init(&d));
    d.positions = positions;
    d.position_type = type;
    d.position_stride = position_stride;
    d.vertex_count = vertex_count;
    d.indices = indices;
    d.index_stride = index_stride;
    d.triangle_count = triangle_count;
    return d;
  }
  template <typename Scalar>
  static Mesh from_indices(const Context& context, const std::vector<Scalar>& positions, const void* indices,
                           std::size_t index_count, mcon_index_format format, std::uint32_t flags) {
    static_assert(std::is_same<Scalar, float>::value || std::is_same<Scalar, double>::value,
                  "positions are float or double");
    check_flat(positions.size(), index_count);
    mcon_mesh_desc d = desc(positions.data(),
                            std::is_same<Scalar, float>::value ? MCON_SCALAR_FLOAT32 : MCON_SCALAR_FLOAT64, 0,
                            positions.size() / 3, static_cast<const std::uint32_t*>(indices), 0, index_count / 3);
    d.index_format = format;
    d.flags = flags;
    return from_desc(context, d);
  }
  std::pair<std::size_t, std::size_t> counts() const {
    std::size_t v = 0, t = 0;
    check(mcon_mesh_get_counts(detail::require(get(), "Mesh"), &v, &t));
    return {v, t};
  }

  detail::Ref<mcon_mesh, mcon_mesh_retain, mcon_mesh_release> ref_;
};

/// Options of Patch::extract; the C struct mcon_patch_options works too.
struct PatchOptions {
  /// A host vertex, or (MCON_INVALID_INDEX) a point in center_triangle at center_barycentric.
  std::uint32_t center_vertex = MCON_INVALID_INDEX;
  std::uint32_t center_triangle = MCON_INVALID_INDEX;
  std::array<double, 3> center_barycentric{{1.0 / 3, 1.0 / 3, 1.0 / 3}};
  double radius = 0;  ///< geodesic radius in host units, > 0
  bool fill_holes = true;
  /// MCON_PATCH_REPAIR_REGION: on a host made with MCON_MESH_VALIDATE_LOCALLY, repair what the patch
  /// reads (zero-area triangles, pinched vertices) instead of refusing it; Patch::repairs says what.
  bool repair_region = false;
  double snap_fraction = 0.2;
  /// Fraction in [0, 1]; return false to cancel (Error with MCON_ERROR_CANCELLED). Exceptions it
  /// throws cancel the extraction and are rethrown from Patch::extract.
  std::function<bool(double)> progress;

  static PatchOptions at_vertex(std::uint32_t vertex, double radius) {
    PatchOptions o;
    o.center_vertex = vertex;
    o.radius = radius;
    return o;
  }
  static PatchOptions at_point(std::uint32_t triangle, const std::array<double, 3>& barycentric, double radius) {
    PatchOptions o;
    o.center_triangle = triangle;
    o.center_barycentric = barycentric;
    o.radius = radius;
    return o;
  }
};

/// Where one patch vertex lies on the host: (1 - t) * host[v0] + t * host[v1].
struct HostVertices {
  std::vector<std::uint32_t> v0, v1;
  std::vector<double> t;
};

/// A geodesic disk of a host mesh, normalized to geodesic radius 1 (host = center + radius * p).
class Patch {
 public:
  static Patch extract(const Mesh& host, const PatchOptions& options) {
    mcon_patch_options c;
    check(mcon_patch_options_init(&c));
    c.center_vertex = options.center_vertex;
    c.center_triangle = options.center_triangle;
    for (int i = 0; i < 3; ++i) c.center_barycentric[i] = options.center_barycentric[static_cast<std::size_t>(i)];
    c.radius = options.radius;
    c.flags = (options.fill_holes ? static_cast<std::uint32_t>(MCON_PATCH_FILL_HOLES) : 0u) |
              (options.repair_region ? static_cast<std::uint32_t>(MCON_PATCH_REPAIR_REGION) : 0u);
    c.snap_fraction = options.snap_fraction;
    detail::ProgressForward forward{&options.progress, nullptr};
    if (options.progress) {
      c.progress = &detail::ProgressForward::call;
      c.progress_user_data = &forward;
    }
    mcon_patch handle = nullptr;
    const mcon_status status = mcon_patch_extract(detail::require(host.get(), "Mesh"), &c, &handle);
    if (forward.exception) std::rethrow_exception(forward.exception);
    check(status);
    return adopt(handle);
  }
  static Patch extract(const Mesh& host, const mcon_patch_options& options) {
    mcon_patch handle = nullptr;
    check(mcon_patch_extract(detail::require(host.get(), "Mesh"), &options, &handle));
    return adopt(handle);
  }

  /// An empty patch object (no handle).
  Patch() noexcept = default;
  /// Takes over a reference the caller owns.
  static Patch adopt(mcon_patch handle) noexcept {
    Patch p;
    p.ref_ = detail::Ref<mcon_patch, mcon_patch_retain, mcon_patch_release>(handle);
    return p;
  }

  mcon_patch_info info() const {
    mcon_patch_info i;
    check(mcon_patch_info_init(&i));
    check(mcon_patch_get_info(handle(), &i));
    return i;
  }
  std::size_t vertex_count() const { return info().vertex_count; }
  std::size_t triangle_count() const { return info().triangle_count; }
  /// What PatchOptions::repair_region changed (all 0 without it).
  mcon_patch_repair_info repairs() const {
    mcon_patch_repair_info r;
    check(mcon_patch_repair_info_init(&r));
    check(mcon_patch_get_repairs(handle(), &r));
    return r;
  }

  /// 3 doubles per vertex, normalized.
  std::vector<double> positions() const {
    std::vector<double> out(3 * vertex_count());
    check(mcon_patch_get_positions(handle(), out.data(), out.size()));
    return out;
  }
  /// 3 indices per triangle.
  std::vector<std::uint32_t> triangles() const {
    std::vector<std::uint32_t> out(3 * triangle_count());
    check(mcon_patch_get_triangles(handle(), out.data(), out.size()));
    return out;
  }
  /// 2 doubles per vertex in the unit disk.
  std::vector<double> uv() const {
    std::vector<double> out(2 * vertex_count());
    check(mcon_patch_get_uv(handle(), out.data(), out.size()));
    return out;
  }
  HostVertices host_vertices() const {
    const std::size_t n = vertex_count();
    HostVertices h;
    h.v0.resize(n);
    h.v1.resize(n);
    h.t.resize(n);
    check(mcon_patch_get_host_vertices(handle(), h.v0.data(), h.v1.data(), h.t.data(), n));
    return h;
  }
  /// The host triangle of each patch triangle (MCON_INVALID_INDEX for hole fillers).
  std::vector<std::uint32_t> host_triangles() const {
    std::vector<std::uint32_t> out(triangle_count());
    check(mcon_patch_get_host_triangles(handle(), out.data(), out.size()));
    return out;
  }
  /// The closest point of the patch to each of the points, given in host units (x0 y0 z0 x1 ...).
  ClosestPoints closest_points(const std::vector<double>& xyz) const {
    return detail::closest_points(handle(), xyz, mcon_patch_closest_points);
  }
  /// Geodesic distance (normalized units) of every vertex from a point of the patch.
  std::vector<double> distance_from_point(const mcon_surface_point& point) const {
    std::vector<double> out(vertex_count());
    check(mcon_patch_compute_distance_from_point(handle(), &point, out.data(), out.size()));
    return out;
  }
  /// The same from the nearest of a set of patch vertices.
  std::vector<double> distance_from_vertices(const std::vector<std::uint32_t>& vertices) const {
    std::vector<double> out(vertex_count());
    check(mcon_patch_compute_distance_from_vertices(handle(), vertices.data(), vertices.size(), out.data(), out.size()));
    return out;
  }
  /// vertex_count * descriptor_dimension(d) values, vertex-major.
  std::vector<double> compute_descriptors(mcon_descriptor descriptor) const {
    std::vector<double> out(vertex_count() * descriptor_dimension(descriptor));
    check(mcon_patch_compute_descriptors(handle(), descriptor, out.data(), out.size()));
    return out;
  }
  static std::uint32_t descriptor_dimension(mcon_descriptor descriptor) {
    std::uint32_t d = 0;
    check(mcon_descriptor_get_dimension(descriptor, &d));
    return d;
  }

  mcon_patch get() const noexcept { return ref_.get(); }
  mcon_patch detach() noexcept { return ref_.detach(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  mcon_patch handle() const { return detail::require(get(), "Patch"); }

  detail::Ref<mcon_patch, mcon_patch_retain, mcon_patch_release> ref_;
};

/// ---- Libraries and retrieval ----
/// One polyline of an entry (points on the entry's patch triangles).
struct Polyline {
  std::uint32_t kind = MCON_POLYLINE_GUIDE;  ///< mcon_polyline_kind
  bool closed = false;
  std::vector<mcon_surface_point> points;
};

/// A named per-vertex field: `values` for real kinds, `labels` for MCON_FIELD_INTEGER_LABEL,
/// vertex_count * dimension of them (vertex-major).
struct VertexField {
  std::string name;
  std::uint32_t kind = MCON_FIELD_SCALAR;  ///< mcon_field_kind
  std::uint32_t dimension = 1;
  std::vector<double> values;
  std::vector<std::int32_t> labels;
};

/// What an entry carries besides its patch; also what Library::entry reads back.
struct EntryData {
  std::uint64_t id = 0;  ///< 0 = assign
  std::string name, class_label, author, licence;
  std::vector<std::string> tags;
  std::vector<Polyline> polylines;  ///< read back: guides first, then features
  std::vector<mcon_singularity> singularities;
  std::vector<VertexField> fields;
  /// Caller-supplied descriptors (custom libraries): vertex_count * descriptor_dimension values.
  std::vector<double> descriptors;
  std::uint32_t descriptor_dimension = 0;
  /// The up direction of the patch's host in its coordinates (mcon_library_entry_desc.up), if any.
  std::optional<std::array<double, 3>> up;
};

struct QueryHit {
  std::uint64_t id = 0;
  std::uint32_t index = 0;
  double distance = 0;
};

/// The mcon_retrieval_descriptor of a built-in descriptor's stored name ("curv9", "hks", "wks").
inline std::uint32_t retrieval_descriptor_from_name(const std::string& name) {
  std::uint32_t code = 0;
  check(mcon_retrieval_descriptor_from_name(name.c_str(), &code));
  return code;
}

/// A constraint library (mcon_library_*): copy = retain (the same library), move = steal.
class Library {
 public:
  static Library create(const Context& context) {
    mcon_library handle = nullptr;
    check(mcon_library_create(detail::require(context.get(), "Context"), &handle));
    return adopt(handle);
  }
  static Library open(const Context& context, const std::string& path) {
    mcon_library handle = nullptr;
    check(mcon_library_open(detail::require(context.get(), "Context"), path.c_str(), &handle));
    return adopt(handle);
  }
  static Library open_memory(const Context& context, const void* data, std::size_t size) {
    mcon_library handle = nullptr;
    check(mcon_library_open_memory(detail::require(context.get(), "Context"), data, size, &handle));
    return adopt(handle);
  }
  Library() noexcept = default;
  static Library adopt(mcon_library handle) noexcept {
    Library l;
    l.ref_ = Ref(handle);
    return l;
  }

  void save(const std::string& path) const { check(mcon_library_save(handle(), path.c_str())); }
  std::vector<std::uint8_t> save_memory() const {
    std::size_t size = 0;
    check(mcon_library_save_memory(handle(), nullptr, 0, &size));
    std::vector<std::uint8_t> bytes(size);
    check(mcon_library_save_memory(handle(), bytes.data(), bytes.size(), &size));
    return bytes;
  }

  mcon_library_info info() const {
    mcon_library_info i;
    check(mcon_library_info_init(&i));
    check(mcon_library_get_info(handle(), &i));
    return i;
  }
  std::size_t size() const {
    std::size_t n = 0;
    check(mcon_library_get_count(handle(), &n));
    return n;
  }

  /// Adds the patch with `data`'s metadata, constraints and fields; returns the entry's id.
  std::uint64_t add(const Patch& patch, const EntryData& data) {
    mcon_library_entry_desc d;
    check(mcon_library_entry_desc_init(&d));
    d.patch = detail::require(patch.get(), "Patch");
    d.id = data.id;
    d.name = data.name.c_str();
    d.class_label = data.class_label.c_str();
    d.author = data.author.c_str();
    d.licence = data.licence.c_str();
    std::vector<const char*> tags;
    for (const std::string& t : data.tags) tags.push_back(t.c_str());
    d.tags = tags.data();
    d.tag_count = tags.size();
    std::vector<mcon_polyline> lines;
    for (const Polyline& p : data.polylines)
      lines.push_back(mcon_polyline{p.kind, p.closed ? 1u : 0u, p.points.data(), p.points.size()});
    d.polylines = lines.data();
    d.polyline_count = lines.size();
    d.singularities = data.singularities.data();
    d.singularity_count = data.singularities.size();
    std::vector<mcon_vertex_field> fields;
    for (const VertexField& f : data.fields)
      fields.push_back(mcon_vertex_field{f.name.c_str(), f.kind, f.dimension,
                                         f.kind == MCON_FIELD_INTEGER_LABEL ? nullptr : f.values.data(),
                                         f.kind == MCON_FIELD_INTEGER_LABEL ? f.labels.data() : nullptr, 0});
    d.fields = fields.data();
    d.field_count = fields.size();
    if (!data.descriptors.empty()) {
      d.descriptors = data.descriptors.data();
      d.descriptor_dimension = data.descriptor_dimension;
    }
    if (data.up) {
      d.has_up = 1u;
      for (std::size_t k = 0; k < 3; ++k) d.up[k] = (*data.up)[k];
    }
    std::uint64_t id = 0;
    check(mcon_library_add_entry(handle(), &d, &id));
    return id;
  }
  void remove(std::uint64_t id) { check(mcon_library_remove_entry(handle(), id)); }
  std::size_t find(std::uint64_t id) const {
    std::size_t index = 0;
    check(mcon_library_find_entry(handle(), id, &index));
    return index;
  }
  void merge(const Library& other) { check(mcon_library_merge(handle(), other.handle())); }

  /// mcon_retrieval_options_init's defaults (CURV9, k = 128, the measured best rings).
  static mcon_retrieval_options default_retrieval_options() {
    mcon_retrieval_options o;
    check(mcon_retrieval_options_init(&o));
    return o;
  }
  void build_retrieval() { build_retrieval(default_retrieval_options()); }
  void build_retrieval(const mcon_retrieval_options& options) { check(mcon_library_build_retrieval(handle(), &options)); }
  /// With a progress function (fraction in [0, 1]; false cancels); its exceptions are rethrown.
  void build_retrieval(mcon_retrieval_options options, const std::function<bool(double)>& progress) {
    detail::ProgressForward forward{&progress, nullptr};
    if (progress) {
      options.progress = &detail::ProgressForward::call;
      options.progress_user_data = &forward;
    }
    const mcon_status status = mcon_library_build_retrieval(handle(), &options);
    if (forward.exception) std::rethrow_exception(forward.exception);
    check(status);
  }

  /// An empty library's built-in descriptor (mcon_retrieval_descriptor).
  void set_descriptor(std::uint32_t descriptor) { check(mcon_library_set_descriptor(handle(), descriptor)); }
  /// MCON_LIBRARY_NAME, MCON_LIBRARY_DESCRIPTION or MCON_LIBRARY_DESCRIPTOR (its stored name).
  std::string string(mcon_library_string which) const {
    return detail::read_string([&](char* text, std::size_t capacity, std::size_t* size) {
      return mcon_library_get_string(handle(), which, text, capacity, size);
    });
  }
  void set_string(mcon_library_string which, const std::string& text) {
    if (text.find('\0') != std::string::npos)
      throw Error(MCON_ERROR_INVALID_ARGUMENT, "Library::set_string: the text contains a NUL byte");
    check(mcon_library_set_string(handle(), which, text.c_str()));
  }

  std::vector<QueryHit> query(const Patch& patch, std::size_t n) const {
    return run_query(n, [&](std::uint64_t* ids, std::uint32_t* indices, double* distances, std::size_t cap,
                            std::size_t* count) {
      return mcon_library_query(handle(), detail::require(patch.get(), "Patch"), n, ids, indices, distances, cap,
                                count);
    });
  }
  /// For a custom library: the patch's own descriptors, vertex_count * dimension values.
  std::vector<QueryHit> query(const Patch& patch, const std::vector<double>& descriptors, std::uint32_t dimension,
                              std::size_t n) const {
    return run_query(n, [&](std::uint64_t* ids, std::uint32_t* indices, double* distances, std::size_t cap,
                            std::size_t* count) {
      return mcon_library_query_descriptors(handle(), detail::require(patch.get(), "Patch"), descriptors.data(),
                                            dimension, 0, n, ids, indices, distances, cap, count);
    });
  }

  mcon_library_entry_info entry_info(std::size_t index) const {
    mcon_library_entry_info i;
    check(mcon_library_entry_info_init(&i));
    check(mcon_library_get_entry_info(handle(), index, &i));
    return i;
  }
  std::vector<double> entry_positions(std::size_t index) const {
    std::vector<double> out(3 * entry_info(index).vertex_count);
    check(mcon_library_get_entry_positions(handle(), index, out.data(), out.size()));
    return out;
  }
  std::vector<std::uint32_t> entry_triangles(std::size_t index) const {
    std::vector<std::uint32_t> out(3 * entry_info(index).triangle_count);
    check(mcon_library_get_entry_triangles(handle(), index, out.data(), out.size()));
    return out;
  }
  std::vector<float> entry_histogram(std::size_t index) const {
    std::vector<float> out(info().histogram_length);
    check(mcon_library_get_entry_retrieval(handle(), index, nullptr, 0, out.data(), out.size()));
    return out;
  }
  /// Everything but the geometry, read back (descriptors included).
  EntryData entry(std::size_t index) const {
    const mcon_library_entry_info ei = entry_info(index);
    EntryData e;
    e.id = ei.id;
    if (ei.has_up) e.up = std::array<double, 3>{{ei.up[0], ei.up[1], ei.up[2]}};
    e.name = entry_string(index, MCON_ENTRY_NAME, 0);
    e.class_label = entry_string(index, MCON_ENTRY_CLASS_LABEL, 0);
    e.author = entry_string(index, MCON_ENTRY_AUTHOR, 0);
    e.licence = entry_string(index, MCON_ENTRY_LICENCE, 0);
    for (std::size_t t = 0; t < ei.tag_count; ++t) e.tags.push_back(entry_string(index, MCON_ENTRY_TAG, t));
    for (std::size_t p = 0; p < ei.polyline_count; ++p) {
      Polyline line;
      std::uint32_t closed = 0;
      std::size_t count = 0;
      check(mcon_library_get_entry_polyline(handle(), index, p, &line.kind, &closed, &count, nullptr, 0));
      line.closed = closed != 0;
      line.points.resize(count);
      check(mcon_library_get_entry_polyline(handle(), index, p, nullptr, nullptr, nullptr, line.points.data(), count));
      e.polylines.push_back(std::move(line));
    }
    e.singularities.resize(ei.singularity_count);
    check(mcon_library_get_entry_singularities(handle(), index, e.singularities.data(), e.singularities.size()));
    for (std::size_t f = 0; f < ei.field_count; ++f) {
      VertexField field;
      field.name = entry_string(index, MCON_ENTRY_FIELD_NAME, f);
      check(mcon_library_get_entry_field(handle(), index, f, &field.kind, &field.dimension, nullptr, nullptr, 0));
      const std::size_t count = ei.vertex_count * field.dimension;
      if (field.kind == MCON_FIELD_INTEGER_LABEL) {
        field.labels.resize(count);
        check(mcon_library_get_entry_field(handle(), index, f, nullptr, nullptr, nullptr, field.labels.data(), count));
      } else {
        field.values.resize(count);
        check(mcon_library_get_entry_field(handle(), index, f, nullptr, nullptr, field.values.data(), nullptr, count));
      }
      e.fields.push_back(std::move(field));
    }
    e.descriptor_dimension = info().descriptor_dimension;
    e.descriptors.resize(ei.vertex_count * e.descriptor_dimension);
    check(mcon_library_get_entry_retrieval(handle(), index, e.descriptors.data(), e.descriptors.size(), nullptr, 0));
    return e;
  }
  std::string entry_string(std::size_t index, mcon_entry_string which, std::size_t item) const {
    return detail::read_string([&](char* text, std::size_t capacity, std::size_t* size) {
      return mcon_library_get_entry_string(handle(), index, which, item, text, capacity, size);
    });
  }

  mcon_library get() const noexcept { return ref_.get(); }
  mcon_library detach() noexcept { return ref_.detach(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  using Ref = detail::Ref<mcon_library, mcon_library_retain, mcon_library_release>;
  mcon_library handle() const { return detail::require(get(), "Library"); }
  template <typename Call>
  std::vector<QueryHit> run_query(std::size_t n, const Call& call) const {
    const std::size_t cap = n < size() ? n : size();
    std::vector<std::uint64_t> ids(cap);
    std::vector<std::uint32_t> indices(cap);
    std::vector<double> distances(cap);
    std::size_t count = 0;
    check(call(ids.data(), indices.data(), distances.data(), cap, &count));
    std::vector<QueryHit> hits(count);
    for (std::size_t i = 0; i < count; ++i) hits[i] = QueryHit{ids[i], indices[i], distances[i]};
    return hits;
  }

  Ref ref_;
};

// ---- Re-embedding maps and constraint transfer ----

/// A patch made from a normalized disk mesh (e.g. a constraint library entry): flat arrays
/// positions = x0 y0 z0 ..., indices = a0 b0 c0 ...; the center is a point of the mesh; host
/// coordinates are origin + scale * p. Throws Error (NOT_A_DISK, validation errors, ...).
inline Patch patch_from_arrays(const Context& context, const std::vector<double>& positions,
                               const std::vector<std::uint32_t>& indices, std::uint32_t center_triangle,
                               const std::array<double, 3>& center_barycentric = {{1.0 / 3, 1.0 / 3, 1.0 / 3}},
                               const std::array<double, 3>& origin = {{0, 0, 0}}, double scale = 1.0) {
  if (positions.size() % 3 != 0 || indices.size() % 3 != 0)
    throw Error(MCON_ERROR_INVALID_ARGUMENT, "macrocon::patch_from_arrays: array sizes are not multiples of 3");
  mcon_mesh_desc d;
  check(mcon_mesh_desc_init(&d));
  d.positions = positions.data();
  d.position_type = MCON_SCALAR_FLOAT64;
  d.vertex_count = positions.size() / 3;
  d.indices = indices.data();
  d.triangle_count = indices.size() / 3;
  mcon_patch_frame f;
  check(mcon_patch_frame_init(&f));
  f.center_triangle = center_triangle;
  for (std::size_t i = 0; i < 3; ++i) {
    f.center_barycentric[i] = center_barycentric[i];
    f.origin[i] = origin[i];
  }
  f.scale = scale;
  mcon_patch handle = nullptr;
  check(mcon_patch_create_from_arrays(detail::require(context.get(), "Context"), &d, &f, &handle));
  return Patch::adopt(handle);
}

/// Points on a patch: triangle, 3 barycentric weights and the 3D position (host units) each.
struct SurfacePoints {
  std::vector<std::uint32_t> triangles;  ///< MCON_INVALID_INDEX: no image (outside the overlap)
  std::vector<double> barycentric;       ///< 3 per point
  std::vector<double> xyz;               ///< 3 per point
  std::size_t size() const { return triangles.size(); }
};

/// Polylines re-traced on a target patch (Map::transfer_polylines).
class PolylineSet {
 public:
  PolylineSet() noexcept = default;
  static PolylineSet adopt(mcon_polyline_set handle) noexcept {
    PolylineSet p;
    p.ref_ = Ref(handle);
    return p;
  }
  std::size_t polyline_count() const { return counts().first; }
  std::size_t point_count() const { return counts().second; }
  /// Per polyline: point count, closed flag, index of the input polyline it came from.
  std::vector<std::uint32_t> sizes() const { return polylines().sizes; }
  std::vector<std::uint8_t> closed() const { return polylines().closed; }
  std::vector<std::uint32_t> input_polylines() const { return polylines().input; }
  /// All points, polyline after polyline.
  SurfacePoints points() const {
    const std::size_t n = point_count();
    SurfacePoints s;
    s.triangles.resize(n);
    s.barycentric.resize(3 * n);
    s.xyz.resize(3 * n);
    check(mcon_polyline_set_get_points(handle(), s.triangles.data(), s.barycentric.data(), s.xyz.data(), n));
    return s;
  }
  mcon_polyline_set get() const noexcept { return ref_.get(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  using Ref = detail::Ref<mcon_polyline_set, mcon_polyline_set_retain, mcon_polyline_set_release>;
  struct Lists {
    std::vector<std::uint32_t> sizes;
    std::vector<std::uint8_t> closed;
    std::vector<std::uint32_t> input;
  };
  std::pair<std::size_t, std::size_t> counts() const {
    std::size_t p = 0, n = 0;
    check(mcon_polyline_set_get_counts(handle(), &p, &n));
    return {p, n};
  }
  Lists polylines() const {
    const std::size_t n = polyline_count();
    Lists l;
    l.sizes.resize(n);
    l.closed.resize(n);
    l.input.resize(n);
    check(mcon_polyline_set_get_polylines(handle(), l.sizes.data(), l.closed.data(), l.input.data(), n));
    return l;
  }
  mcon_polyline_set handle() const { return detail::require(get(), "PolylineSet"); }
  Ref ref_;
};

/// Options of Map::compute; the C struct mcon_map_options works too. Members left empty keep
/// mcon_map_options_init's defaults.
struct MapOptions {
  std::uint64_t seed = 0;
  std::optional<std::uint32_t> alignment_samples;
  bool allow_reflection = true;  ///< restricts automatic only
  std::optional<std::uint32_t> max_iterations;
  /// Fraction in [0, 1]; return false to cancel (Error with MCON_ERROR_CANCELLED). An exception it
  /// throws cancels the computation and is rethrown from Map::compute.
  std::function<bool(double)> progress;
  /// Automatic, or force one orientation (a "flip" recomputes with the one opposite to info().reflected).
  mcon_map_orientation orientation = MCON_MAP_ORIENTATION_AUTOMATIC;
  /// Optional guidance channels (see mcon_map_options): guidance_dimension doubles per vertex,
  /// packed, source_vertex_count rows in source_guidance and target_vertex_count in
  /// target_guidance; both empty: none.
  std::uint32_t guidance_dimension = 0;
  std::vector<double> source_guidance, target_guidance;
  std::optional<double> guidance_weight;
  /// Gaussian width factor of the refinement pass after the finest level (0: no pass; (0, 1]).
  std::optional<double> refine_sigma_factor;
  /// Up directions of the two hosts, each in its own host coordinates (mcon_map_options.use_up_hints):
  /// both or neither.
  std::optional<std::array<double, 3>> source_up, target_up;
};

/// The re-embedding map Phi of a source patch onto a target patch, and transfers through it.
class Map {
 public:
  static Map compute(const Patch& source, const Patch& target, const MapOptions& options = {}) {
    mcon_map_options c;
    check(mcon_map_options_init(&c));
    c.seed = options.seed;
    if (options.alignment_samples) c.alignment_samples = *options.alignment_samples;
    c.allow_reflection = options.allow_reflection ? 1u : 0u;
    if (options.max_iterations) c.max_iterations = *options.max_iterations;
    c.orientation = static_cast<std::uint32_t>(options.orientation);
    c.guidance_dimension = options.guidance_dimension;
    c.source_guidance = options.source_guidance.empty() ? nullptr : options.source_guidance.data();
    c.target_guidance = options.target_guidance.empty() ? nullptr : options.target_guidance.data();
    if (options.guidance_weight) c.guidance_weight = *options.guidance_weight;
    if (options.refine_sigma_factor) c.refine_sigma_factor = *options.refine_sigma_factor;
    if (options.source_up.has_value() != options.target_up.has_value())
      throw Error(MCON_ERROR_INVALID_ARGUMENT, "MapOptions: source_up and target_up go together");
    if (options.source_up) {
      c.use_up_hints = 1u;
      for (std::size_t k = 0; k < 3; ++k) {
        c.source_up[k] = (*options.source_up)[k];
        c.target_up[k] = (*options.target_up)[k];
      }
    }
    if (options.guidance_dimension != 0 &&
        (options.source_guidance.size() != source.vertex_count() * options.guidance_dimension ||
         options.target_guidance.size() != target.vertex_count() * options.guidance_dimension))
      throw Error(MCON_ERROR_INVALID_ARGUMENT,
                  "MapOptions: guidance needs guidance_dimension values per source and per target vertex");
    detail::ProgressForward forward{&options.progress, nullptr};
    if (options.progress) {
      c.progress = &detail::ProgressForward::call;
      c.progress_user_data = &forward;
    }
    mcon_map handle = nullptr;
    const mcon_status status = mcon_map_compute(detail::require(source.get(), "Patch"),
                                                detail::require(target.get(), "Patch"), &c, &handle);
    if (forward.exception) std::rethrow_exception(forward.exception);
    check(status);
    return adopt(handle);
  }
  Map() noexcept = default;
  static Map adopt(mcon_map handle) noexcept {
    Map m;
    m.ref_ = Ref(handle);
    return m;
  }

  mcon_map_info info() const {
    mcon_map_info i;
    check(mcon_map_info_init(&i));
    check(mcon_map_get_info(handle(), &i));
    return i;
  }
  /// The energy terms in evaluation order: name and final unweighted value.
  std::vector<std::pair<std::string, double>> energy_terms() const {
    std::uint32_t n = 0;
    check(mcon_map_get_energy_term_count(handle(), &n));
    std::vector<std::pair<std::string, double>> out(n);
    for (std::uint32_t k = 0; k < n; ++k) {
      const char* name = nullptr;
      check(mcon_map_get_energy_term(handle(), k, &name, &out[k].second));
      out[k].first = name;
    }
    return out;
  }
  /// Per vertex of the direction's domain: triangle of the other patch (-1 outside) and 3 weights.
  std::pair<std::vector<std::int32_t>, std::vector<double>> correspondences(mcon_map_direction direction) const {
    const mcon_map_info i = info();
    const std::size_t n = direction == MCON_MAP_SOURCE_TO_TARGET ? i.source_vertex_count : i.target_vertex_count;
    std::pair<std::vector<std::int32_t>, std::vector<double>> out;
    out.first.resize(n);
    out.second.resize(3 * n);
    check(mcon_map_get_correspondences(handle(), direction, out.first.data(), out.second.data(), n));
    return out;
  }
  /// 2 doubles per source vertex.
  std::vector<double> phi() const {
    std::vector<double> out(2 * info().source_vertex_count);
    check(mcon_map_get_phi(handle(), out.data(), out.size()));
    return out;
  }
  /// 1 per target vertex outside the overlap.
  std::vector<std::uint8_t> outside_mask() const {
    std::vector<std::uint8_t> out(info().target_vertex_count);
    check(mcon_map_get_outside_mask(handle(), out.data(), out.size()));
    return out;
  }
  SurfacePoints transfer_points(const std::vector<std::uint32_t>& triangles, const std::vector<double>& barycentric) const {
    if (barycentric.size() != 3 * triangles.size())
      throw Error(MCON_ERROR_INVALID_ARGUMENT, "macrocon::Map::transfer_points: need 3 weights per point");
    const std::size_t n = triangles.size();
    SurfacePoints s;
    s.triangles.resize(n);
    s.barycentric.resize(3 * n);
    s.xyz.resize(3 * n);
    check(mcon_map_transfer_points(handle(), triangles.data(), barycentric.data(), n, s.triangles.data(),
                                   s.barycentric.data(), s.xyz.data(), n));
    return s;
  }
  /// Points grouped by `sizes` into polylines; `closed` empty = all open.
  PolylineSet transfer_polylines(const std::vector<std::uint32_t>& triangles, const std::vector<double>& barycentric,
                                 const std::vector<std::uint32_t>& sizes,
                                 const std::vector<std::uint8_t>& closed = {}) const {
    if (barycentric.size() != 3 * triangles.size() || (!closed.empty() && closed.size() != sizes.size()))
      throw Error(MCON_ERROR_INVALID_ARGUMENT, "macrocon::Map::transfer_polylines: inconsistent array sizes");
    mcon_polyline_set handle_out = nullptr;
    check(mcon_map_transfer_polylines(handle(), triangles.data(), barycentric.data(), triangles.size(), sizes.data(),
                                      closed.empty() ? nullptr : closed.data(), sizes.size(), &handle_out));
    return PolylineSet::adopt(handle_out);
  }
  /// source_vertex_count * dimension values -> target_vertex_count * dimension values.
  std::vector<double> transfer_field(mcon_field_kind kind, std::uint32_t dimension,
                                     const std::vector<double>& source_values) const {
    std::vector<double> out(info().target_vertex_count * dimension);
    check(mcon_map_transfer_field(handle(), kind, dimension, source_values.data(), source_values.size(), out.data(),
                                  out.size()));
    return out;
  }
  /// The same in float32 (mcon_map_transfer_field_f32: computed in double, rounded once).
  std::vector<float> transfer_field(mcon_field_kind kind, std::uint32_t dimension,
                                    const std::vector<float>& source_values) const {
    std::vector<float> out(info().target_vertex_count * dimension);
    check(mcon_map_transfer_field_f32(handle(), kind, dimension, source_values.data(), source_values.size(),
                                      out.data(), out.size()));
    return out;
  }
  std::vector<std::int32_t> transfer_labels(std::uint32_t dimension, const std::vector<std::int32_t>& labels,
                                            std::int32_t outside_label = -1) const {
    std::vector<std::int32_t> out(info().target_vertex_count * dimension);
    check(mcon_map_transfer_labels(handle(), dimension, labels.data(), labels.size(), outside_label, out.data(),
                                   out.size()));
    return out;
  }

  mcon_map get() const noexcept { return ref_.get(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  using Ref = detail::Ref<mcon_map, mcon_map_retain, mcon_map_release>;
  mcon_map handle() const { return detail::require(get(), "Map"); }
  Ref ref_;
};

/// A guide-aligned cross field: one unit direction (3 doubles) and a confidence per triangle.
struct CrossField {
  std::vector<double> directions;
  std::vector<double> confidence;
};

/// `guides` may be an empty PolylineSet (the smoothest field); they must lie on `patch`.
inline CrossField compute_cross_field(const Patch& patch, const PolylineSet& guides, double alignment_weight = 10.0,
                                      bool align_to_boundary = false, double boundary_weight = 1.0) {
  mcon_cross_field_options o;
  check(mcon_cross_field_options_init(&o));
  o.alignment_weight = alignment_weight;
  o.align_to_boundary = align_to_boundary ? 1u : 0u;
  o.boundary_weight = boundary_weight;
  const std::size_t n = patch.triangle_count();
  CrossField f;
  f.directions.resize(3 * n);
  f.confidence.resize(n);
  check(mcon_patch_compute_cross_field(detail::require(patch.get(), "Patch"), guides.get(), &o, f.directions.data(),
                                       f.confidence.data(), n));
  return f;
}

/// QuadWild `.rosy` (a `.gz` path is refused: QuadWild reads it as zeros).
inline void write_rosy(const Patch& patch, const std::vector<double>& directions, const std::string& path) {
  check(mcon_patch_write_rosy(detail::require(patch.get(), "Patch"), directions.data(), directions.size() / 3,
                              path.c_str()));
}

/// Guides cut into a patch (mcon_patch_cut_guides): every guide a chain of edges. Positions in the
/// patch's host units. Options left empty keep mcon_guide_cut_options_init's defaults.
class CutMesh {
 public:
  CutMesh() noexcept = default;
  static CutMesh cut(const Patch& patch, const PolylineSet& guides, std::optional<double> snap_fraction = {},
                     std::optional<double> simplify_fraction = {}, std::optional<std::uint32_t> fair_passes = {}) {
    mcon_guide_cut_options o;
    check(mcon_guide_cut_options_init(&o));
    if (snap_fraction) o.snap_fraction = *snap_fraction;
    if (simplify_fraction) o.simplify_fraction = *simplify_fraction;
    if (fair_passes) o.fair_passes = *fair_passes;
    mcon_cut_mesh out = nullptr;
    check(mcon_patch_cut_guides(detail::require(patch.get(), "Patch"), detail::require(guides.get(), "PolylineSet"),
                                &o, &out));
    CutMesh c;
    c.ref_ = Ref(out);
    return c;
  }
  /// The guides of several macro constraints cut into the whole host (mcon_mesh_cut_guides): each
  /// set lies on a patch extracted from `mesh`; the result covers every face of `mesh`.
  static CutMesh cut_whole_host(const Mesh& mesh, const std::vector<PolylineSet>& guide_sets,
                                std::optional<double> snap_fraction = {}, std::optional<double> simplify_fraction = {},
                                std::optional<std::uint32_t> fair_passes = {}) {
    mcon_guide_cut_options o;
    check(mcon_guide_cut_options_init(&o));
    if (snap_fraction) o.snap_fraction = *snap_fraction;
    if (simplify_fraction) o.simplify_fraction = *simplify_fraction;
    if (fair_passes) o.fair_passes = *fair_passes;
    std::vector<mcon_polyline_set> sets;
    for (const PolylineSet& s : guide_sets) sets.push_back(detail::require(s.get(), "PolylineSet"));
    mcon_cut_mesh out = nullptr;
    check(mcon_mesh_cut_guides(detail::require(mesh.get(), "Mesh"), sets.data(), sets.size(), &o, &out));
    CutMesh c;
    c.ref_ = Ref(out);
    return c;
  }
  mcon_cut_mesh_info info() const {
    mcon_cut_mesh_info i;
    check(mcon_cut_mesh_info_init(&i));
    check(mcon_cut_mesh_get_info(handle(), &i));
    return i;
  }
  std::vector<double> positions() const {
    std::vector<double> out(3 * info().vertex_count);
    check(mcon_cut_mesh_get_positions(handle(), out.data(), out.size()));
    return out;
  }
  std::vector<std::uint32_t> triangles() const {
    std::vector<std::uint32_t> out(3 * info().triangle_count);
    check(mcon_cut_mesh_get_triangles(handle(), out.data(), out.size()));
    return out;
  }
  /// Per vertex its point on the patch (on the mesh for cut_whole_host): triangle and 3 weights.
  std::pair<std::vector<std::uint32_t>, std::vector<double>> host_points() const {
    const std::size_t n = info().vertex_count;
    std::pair<std::vector<std::uint32_t>, std::vector<double>> out;
    out.first.resize(n);
    out.second.resize(3 * n);
    check(mcon_cut_mesh_get_host_points(handle(), out.first.data(), out.second.data(), n));
    return out;
  }
  std::vector<std::uint32_t> guide_edges() const {
    std::vector<std::uint32_t> out(2 * info().guide_edge_count);
    check(mcon_cut_mesh_get_guide_edges(handle(), out.data(), out.size()));
    return out;
  }
  /// One vertex chain per guide (a closed guide repeats its first vertex at its end).
  std::vector<std::vector<std::uint32_t>> guides() const {
    const mcon_cut_mesh_info i = info();
    std::vector<std::uint32_t> sizes(i.guide_count), all(i.guide_vertex_count);
    check(mcon_cut_mesh_get_guides(handle(), sizes.data(), sizes.size(), all.data(), all.size()));
    std::vector<std::vector<std::uint32_t>> out;
    std::size_t at = 0;
    for (std::uint32_t n : sizes) {
      out.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(at), all.begin() + static_cast<std::ptrdiff_t>(at + n));
      at += n;
    }
    return out;
  }
  /// Per chain: {guide set, polyline of that set}.
  std::vector<std::array<std::uint32_t, 2>> guide_origins() const {
    const std::size_t n = info().guide_count;
    std::vector<std::uint32_t> sets(n), lines(n);
    check(mcon_cut_mesh_get_guide_origins(handle(), sets.data(), lines.data(), n));
    std::vector<std::array<std::uint32_t, 2>> out;
    for (std::size_t g = 0; g < n; ++g) out.push_back({sets[g], lines[g]});
    return out;
  }
  /// A per-vertex field of the patch (of the mesh for cut_whole_host; vertices x dimension) at the
  /// cut mesh's vertices.
  std::vector<double> carry_field(const std::vector<double>& patch_values, std::uint32_t dimension) const {
    std::vector<double> out(static_cast<std::size_t>(dimension) * info().vertex_count);
    check(mcon_cut_mesh_carry_field(handle(), dimension, patch_values.data(), patch_values.size(), out.data(),
                                    out.size()));
    return out;
  }
  std::vector<double> cross_field() const {
    const std::size_t n = info().triangle_count;
    std::vector<double> out(3 * n);
    check(mcon_cut_mesh_compute_cross_field(handle(), out.data(), n));
    return out;
  }
  void write_quadwild(const std::string& path_prefix) const {
    check(mcon_cut_mesh_write_quadwild(handle(), path_prefix.c_str()));
  }
  mcon_cut_mesh get() const noexcept { return ref_.get(); }
  explicit operator bool() const noexcept { return ref_.get() != nullptr; }

 private:
  using Ref = detail::Ref<mcon_cut_mesh, mcon_cut_mesh_retain, mcon_cut_mesh_release>;
  mcon_cut_mesh handle() const { return detail::require(get(), "CutMesh"); }
  Ref ref_;
};

}  // namespace macrocon

#endif  // MACROCON_HPP
