// Constraints of a library entry from DCC files (entry_authoring.h). A point belongs to the patch
// when the patch is as close to it as the whole host is: a point on the host surface outside the
// disk is nearer to the host than to the disk's border, one inside is equally near both.
#include "entry_authoring.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <optional>

#include "base/error.h"
#include "base/text.h"
#include "sdk_arrays.h"

namespace mcon::cli {
namespace {

// A file point snapped onto the patch: the patch point, where it lies (host units) and how far.
struct Snap {
  mcon_surface_point point;
  Vec3 position;
  double distance;
};

// Snaps file points onto the patch through the SDK's closest-point queries on the host and on
// the patch (host units), a batch of points at a time.
class PatchSnapper {
 public:
  PatchSnapper(const HostMesh& host, const macrocon::Patch& patch, double max_distance)
      : host_(host.sdk), patch_(patch), info_(patch.info()),
        in_host_units_(file_mesh(patch, info_.radius, info_.center)), max_distance_(max_distance),
        tolerance_(1e-3 * info_.radius) {}

  // Per point, the patch point nearest to it, or nothing when it lies beside the host outside the
  // patch. Throws for the first point farther than the limit from the host surface (what(i)
  // names it).
  template <typename What>
  std::vector<std::optional<Snap>> snap(const std::vector<Vec3>& points, const What& what) const {
    std::vector<double> xyz;
    xyz.reserve(3 * points.size());
    for (const Vec3& p : points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
    const macrocon::ClosestPoints on_host = host_.closest_points(xyz);
    const macrocon::ClosestPoints on_patch = patch_.closest_points(xyz);
    std::vector<std::optional<Snap>> out(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double to_host = on_host.distances[i];
      require(to_host <= max_distance_, MCON_ERROR_INVALID_ARGUMENT,
              what(i) + " is " + number_text(to_host) + " from the mesh surface, more than the limit " +
                  number_text(max_distance_) + " (--max-snap-distance, mesh units): is it drawn on this mesh?");
      if (on_patch.distances[i] > to_host + tolerance_) continue;
      Snap s{{on_patch.triangles[i], {on_patch.barycentric[3 * i], on_patch.barycentric[3 * i + 1],
                                      on_patch.barycentric[3 * i + 2]}},
             position(on_patch.triangles[i], &on_patch.barycentric[3 * i]), on_patch.distances[i]};
      out[i] = s;
    }
    return out;
  }

 private:
  // In host units (center + radius * p), as the patch's closest-point tree places it.
  Vec3 position(std::uint32_t triangle, const double* weights) const {
    const Tri& t = in_host_units_.triangles[triangle];
    Vec3 q = Vec3::Zero();
    for (int k = 0; k < 3; ++k) q += weights[k] * in_host_units_.positions[t[k]];
    return q;
  }

  const macrocon::Mesh& host_;
  const macrocon::Patch& patch_;
  mcon_patch_info info_;
  TriMesh in_host_units_;
  double max_distance_, tolerance_;
};

// The pieces of a file polyline that lie on the patch: runs of consecutive points on it (a closed
// line cut open where it leaves the patch, so a piece never jumps across the outside).
void add_polyline_pieces(const PatchSnapper& snapper, const io::FilePolyline& line, const std::string& file,
                         std::uint32_t kind, std::vector<macrocon::Polyline>& out, AuthoringReport& report,
                         std::vector<double>& distances) {
  const std::size_t n = line.points.size();
  const std::vector<std::optional<Snap>> snapped = snapper.snap(line.points, [&](std::size_t i) {
    return "'" + file + "' line " + std::to_string(line.line) + ", point " + std::to_string(i);
  });
  std::size_t first_outside = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (snapped[i]) continue;
    ++report.points_outside;
    if (first_outside == n) first_outside = i;
  }
  const bool whole_loop = line.closed && first_outside == n;
  // A closed line starts after an outside point, so a piece crossing its first point stays whole.
  const std::size_t start = line.closed && first_outside < n ? first_outside + 1 : 0;
  std::size_t pieces_before = out.size();
  macrocon::Polyline piece;
  piece.kind = kind;
  piece.closed = whole_loop;
  Vec3 position_of_last = Vec3::Zero();
  auto flush = [&] {
    if (piece.points.size() >= (piece.closed ? 3u : 2u)) out.push_back(piece);
    piece.points.clear();
  };
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (start + k) % n;
    if (!snapped[i]) {
      flush();
      continue;
    }
    const Snap& q = *snapped[i];
    // Two points snapped onto the same spot (a line doubling back at the border) add nothing.
    if (!piece.points.empty() && (position_of_last - q.position).norm() <= 1e-12) continue;
    piece.points.push_back(q.point);
    position_of_last = q.position;
    distances.push_back(q.distance);
  }
  flush();
  if (out.size() == pieces_before) ++report.lines_outside;
  for (std::size_t i = pieces_before; i < out.size(); ++i) report.points += out[i].points.size();
}

void add_singularities(const PatchSnapper& snapper, const std::string& file, macrocon::EntryData& content,
                       AuthoringReport& report) {
  const io::ValueTable table = io::read_value_table(file);
  int col[4];
  const char* names[4] = {"x", "y", "z", "index"};
  for (int k = 0; k < 4; ++k) {
    col[k] = table.column(names[k]);
    require(col[k] >= 0, MCON_ERROR_INVALID_ARGUMENT,
            "'" + file + "' has no column '" + names[k] + "' (singularities need x, y, z, index: index in quarter turns, "
            "+1 for a valence-3 vertex, -1 for valence 5)");
  }
  for (std::size_t r = 0; r < table.rows(); ++r) {
    const double index = table.at(r, col[3]);
    require(index == std::round(index) && index != 0 && std::abs(index) <= 12, MCON_ERROR_INVALID_ARGUMENT,
            "'" + file + "' row " + std::to_string(r) + ": index " + number_text(index) +
                " is not a non-zero whole number of quarter turns (+1: valence 3, -1: valence 5)");
    const Vec3 p(table.at(r, col[0]), table.at(r, col[1]), table.at(r, col[2]));
    const auto q = snapper.snap({p}, [&](std::size_t) { return "'" + file + "' row " + std::to_string(r); })[0];
    if (!q) {
      ++report.singularities_outside;
      continue;
    }
    content.singularities.push_back(mcon_singularity{q->point, static_cast<std::int32_t>(index)});
  }
  report.singularities = content.singularities.size();
}

// The --field KINDs, in the order of their names in messages.
constexpr std::uint32_t kFieldKinds[] = {MCON_FIELD_SCALAR, MCON_FIELD_VECTOR3, MCON_FIELD_TANGENT_VECTOR, MCON_FIELD_UV,
                                         MCON_FIELD_INTEGER_LABEL};

std::uint32_t kind_of(const std::string& text, const std::string& spec) {
  for (std::uint32_t k : kFieldKinds)
    if (text == field_kind_name(k)) return k;
  fail(MCON_ERROR_INVALID_ARGUMENT,
       "--field '" + spec + "': unknown kind '" + text + "' (scalar, vector3, tangent, uv or label)");
}

// Per patch vertex, the file vertex whose row it reads and the weight of the second one: a
// patch vertex on a host edge blends its two ends; one that fills a hole takes the row of the
// nearest linked vertex (breadth-first over patch edges), as no host data is under it.
struct RowBlend {
  int row0 = -1, row1 = -1;
  double t = 0;
};

std::vector<RowBlend> patch_rows(const io::LoadedMesh& host, const macrocon::Patch& patch) {
  const macrocon::HostVertices links = patch.host_vertices();
  const std::size_t n = links.v0.size();
  std::vector<RowBlend> rows(n);
  std::deque<std::size_t> queue;
  for (std::size_t w = 0; w < n; ++w) {
    if (links.v0[w] == MCON_INVALID_INDEX) continue;
    rows[w] = {host.mesh_to_file[links.v0[w]], host.mesh_to_file[links.v1[w]], links.t[w]};
    queue.push_back(w);
  }
  std::vector<std::vector<std::size_t>> neighbours(n);
  const std::vector<std::uint32_t> t = patch.triangles();
  for (std::size_t f = 0; 3 * f < t.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = t[3 * f + k], b = t[3 * f + (k + 1) % 3];
      neighbours[a].push_back(b), neighbours[b].push_back(a);
    }
  while (!queue.empty()) {
    const std::size_t w = queue.front();
    queue.pop_front();
    for (std::size_t u : neighbours[w])
      if (rows[u].row0 < 0) {
        rows[u] = rows[w];
        queue.push_back(u);
      }
  }
  return rows;
}

macrocon::VertexField field_from_table(const io::ValueTable& table, const FieldSpec& f,
                                       const std::vector<RowBlend>& rows, const std::string& file) {
  macrocon::VertexField field;
  field.name = f.name;
  field.kind = f.kind;
  field.dimension = static_cast<std::uint32_t>(f.columns.size());
  std::vector<int> cols;
  for (const std::string& c : f.columns) {
    cols.push_back(table.column(c));
    require(cols.back() >= 0, MCON_ERROR_INVALID_ARGUMENT,
            "field '" + f.name + "': '" + file + "' has no column '" + c + "'");
  }
  for (const RowBlend& r : rows)
    for (int c : cols) {
      const double a = table.at(static_cast<std::size_t>(r.row0), c), b = table.at(static_cast<std::size_t>(r.row1), c);
      if (f.kind != MCON_FIELD_INTEGER_LABEL) {
        field.values.push_back((1 - r.t) * a + r.t * b);  // the library stores it as float32
        continue;
      }
      const double label = r.t < 0.5 ? a : b;  // labels do not blend: the nearer end's
      require(label == std::round(label) && std::abs(label) <= 2147483647.0, MCON_ERROR_INVALID_ARGUMENT,
              "field '" + f.name + "' (label): '" + file + "' column '" + table.columns[c] + "' holds " +
                  number_text(label) + ", not a 32-bit whole number");
      field.labels.push_back(static_cast<std::int32_t>(label));
    }
  return field;
}

void add_fields(const io::LoadedMesh& host, const macrocon::Patch& patch, const AuthoringSpec& spec,
                macrocon::EntryData& content, AuthoringReport& report) {
  const io::ValueTable table = io::read_value_table(spec.field_file);
  require(table.rows() == host.file_to_mesh.size(), MCON_ERROR_INVALID_ARGUMENT,
          "'" + spec.field_file + "' has " + std::to_string(table.rows()) + " rows but the mesh file has " +
              std::to_string(host.file_to_mesh.size()) + " vertices: export one row per vertex, in the mesh's order");
  std::vector<FieldSpec> fields;
  for (const std::string& s : spec.field_specs) fields.push_back(parse_field_spec(s));
  if (fields.empty())  // every column but the coordinates of a PLY
    for (const std::string& c : table.columns)
      if (c != "x" && c != "y" && c != "z") fields.push_back({c, {c}, MCON_FIELD_SCALAR});
  require(!fields.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "'" + spec.field_file + "' has no column besides x, y, z: export the attributes as vertex properties");
  const std::vector<RowBlend> rows = patch_rows(host, patch);
  for (const FieldSpec& f : fields) {
    content.fields.push_back(field_from_table(table, f, rows, spec.field_file));
    report.fields.push_back(f.name);
  }
}

}  // namespace

const char* field_kind_name(std::uint32_t kind) {
  switch (kind) {
    case MCON_FIELD_SCALAR: return "scalar";
    case MCON_FIELD_VECTOR3: return "vector3";
    case MCON_FIELD_TANGENT_VECTOR: return "tangent";
    case MCON_FIELD_UV: return "uv";
    case MCON_FIELD_INTEGER_LABEL: return "label";
    default: break;
  }
  return "unknown";
}

FieldSpec parse_field_spec(const std::string& text) {
  FieldSpec f;
  std::string rest = text;
  const std::size_t colon = rest.rfind(':');
  if (colon != std::string::npos) {
    f.kind = kind_of(rest.substr(colon + 1), text);
    rest = rest.substr(0, colon);
  }
  const std::size_t equals = rest.find('=');
  f.name = rest.substr(0, equals);
  if (equals == std::string::npos) {
    f.columns = {f.name};
  } else {
    std::string cols = rest.substr(equals + 1);
    for (std::size_t at = 0; at <= cols.size();) {
      const std::size_t comma = std::min(cols.find(',', at), cols.size());
      f.columns.push_back(cols.substr(at, comma - at));
      at = comma + 1;
    }
  }
  require(!f.name.empty(), MCON_ERROR_INVALID_ARGUMENT, "--field '" + text + "' has no name (NAME[=COL,...][:KIND])");
  for (const std::string& c : f.columns)
    require(!c.empty(), MCON_ERROR_INVALID_ARGUMENT, "--field '" + text + "' has an empty column name");
  const std::size_t needed =
      f.kind == MCON_FIELD_UV ? 2 : (f.kind == MCON_FIELD_VECTOR3 || f.kind == MCON_FIELD_TANGENT_VECTOR) ? 3 : 0;
  require(needed == 0 || f.columns.size() == needed, MCON_ERROR_INVALID_ARGUMENT,
          "--field '" + text + "': this kind takes " + std::to_string(needed) + " columns (NAME=C1,C2" +
              (needed == 3 ? ",C3" : "") + ":KIND), got " + std::to_string(f.columns.size()));
  return f;
}

tools::Json AuthoringReport::json() const {
  tools::Json j = tools::Json::object();
  j.set("guides", static_cast<unsigned long>(guides));
  j.set("features", static_cast<unsigned long>(features));
  j.set("points", static_cast<unsigned long>(points));
  j.set("points_outside", static_cast<unsigned long>(points_outside));
  j.set("lines_outside", static_cast<unsigned long>(lines_outside));
  j.set("singularities", static_cast<unsigned long>(singularities));
  j.set("singularities_outside", static_cast<unsigned long>(singularities_outside));
  j.set("max_snap_distance", max_snap_distance);
  j.set("median_snap_distance", median_snap_distance);
  tools::Json names = tools::Json::array();
  for (const std::string& f : fields) names.push_back(f);
  j.set("fields", names);
  return j;
}

AuthoringReport author_constraints(const HostMesh& host, const macrocon::Patch& patch, const AuthoringSpec& spec,
                                   macrocon::EntryData& content) {
  AuthoringReport report;
  if (spec.empty()) return report;
  const double limit = spec.max_snap_distance >= 0 ? spec.max_snap_distance : 0.1 * patch.info().radius;
  const PatchSnapper snapper(host, patch, limit);
  std::vector<double> distances;
  for (const auto& [files, kind] :
       {std::pair{&spec.guide_files, MCON_POLYLINE_GUIDE}, {&spec.feature_files, MCON_POLYLINE_FEATURE}}) {
    const std::size_t before = content.polylines.size();
    for (const std::string& file : *files)
      for (const io::FilePolyline& line : io::read_obj_polylines(file))
        add_polyline_pieces(snapper, line, file, kind, content.polylines, report, distances);
    (kind == MCON_POLYLINE_GUIDE ? report.guides : report.features) = content.polylines.size() - before;
  }
  if (!distances.empty()) {
    std::sort(distances.begin(), distances.end());
    report.max_snap_distance = distances.back();
    report.median_snap_distance = distances[distances.size() / 2];
  }
  if (!spec.singularity_file.empty()) add_singularities(snapper, spec.singularity_file, content, report);
  if (!spec.field_file.empty()) add_fields(host.file, patch, spec, content, report);
  require(spec.field_specs.empty() || !spec.field_file.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "--field needs --fields FILE (the table its columns come from)");
  return report;
}

}  // namespace mcon::cli
