// The constraints `macrocon embed` transfers (embed_constraints.h).
#include "embed_constraints.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "base/error.h"
#include "descriptors/curvature_descriptors.h"
#include "operators/heat_geodesics.h"
#include "transfer/field_transfer.h"

namespace mcon::cli {
namespace {

// Iso-lines {d = value} of a per-vertex field as polylines of surface points (marching
// triangles: a vertex counts as above when d >= value, so every crossed triangle has exactly two
// crossed edges and the pieces chain into closed loops, or open chains ending on the boundary).
std::vector<PolylineInput> iso_lines(const TriMesh& mesh, const Eigen::VectorXd& d, double value) {
  using Edge = std::pair<int, int>;
  auto key = [](int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; };
  std::map<Edge, std::vector<int>> edge_triangles;  // crossed edge -> triangles that cross it
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Tri& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      if ((d[a] >= value) != (d[b] >= value)) edge_triangles[key(a, b)].push_back(t);
    }
  }
  auto point_on = [&](const Edge& e, int t) {
    const double s = (value - d[e.first]) / (d[e.second] - d[e.first]);
    SurfacePoint p;
    p.triangle = t;
    p.barycentric = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      if (mesh.triangles[t][k] == e.first) p.barycentric[k] = 1 - s;
      if (mesh.triangles[t][k] == e.second) p.barycentric[k] = s;
    }
    return p;
  };
  auto other_edge = [&](int t, const Edge& e) {
    const Tri& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const Edge f = key(tri[k], tri[(k + 1) % 3]);
      if (f != e && edge_triangles.count(f)) return f;
    }
    return e;
  };
  std::map<Edge, bool> used;
  std::vector<PolylineInput> out;
  // Open chains start at boundary edges (one triangle), then closed loops anywhere.
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& [edge, tris] : edge_triangles) {
      if (used[edge] || (pass == 0 && tris.size() != 1)) continue;
      PolylineInput line;
      Edge e = edge;
      int t = tris[0];
      used[e] = true;
      line.points.push_back(point_on(e, t));
      while (true) {
        const Edge f = other_edge(t, e);
        if (f == e) break;
        line.points.push_back(point_on(f, t));
        if (used[f]) {  // back at the start: a closed loop
          line.points.pop_back();
          line.closed = true;
          break;
        }
        used[f] = true;
        const auto& ft = edge_triangles[f];
        if (ft.size() < 2) break;  // reached the boundary
        t = ft[0] == t ? ft[1] : ft[0];
        e = f;
      }
      if (line.points.size() >= (line.closed ? 3u : 2u)) out.push_back(std::move(line));
    }
  return out;
}

NamedField real_field(std::string name, FieldKind kind, Eigen::MatrixXd values) {
  NamedField f;
  f.name = std::move(name);
  f.kind = kind;
  f.dimension = static_cast<int>(values.cols());
  f.values = std::move(values);
  return f;
}

std::vector<PolylineInput> inputs_of(const std::vector<ConstraintPolyline>& lines) {
  std::vector<PolylineInput> out;
  for (const ConstraintPolyline& l : lines) out.push_back({l.points, l.closed});
  return out;
}

}  // namespace

SourceConstraints synthetic_constraints(const Patch& source) {
  SourceConstraints c;
  const int n = source.mesh.num_vertices();
  const Eigen::VectorXd distance =
      HeatGeodesics(source.mesh).from_point(source.center.triangle, source.center.barycentric);
  const Eigen::VectorXd mean = mean_curvature_descriptor(source.mesh);
  Eigen::MatrixXd uv(n, 2);
  NamedField rings;
  rings.name = "source_ring";
  rings.kind = FieldKind::integer_label;
  for (int v = 0; v < n; ++v) {
    uv.row(v) << source.uv[v].x(), source.uv[v].y();
    rings.labels.push_back(static_cast<std::int32_t>(std::floor(std::max(0.0, distance[v]) / 0.25)));
  }
  c.fields.push_back(real_field("source_uv", FieldKind::uv, uv));
  c.fields.push_back(real_field("source_mean_curvature", FieldKind::scalar, mean));
  c.fields.push_back(real_field("source_geodesic_distance", FieldKind::scalar, distance));
  c.fields.push_back(std::move(rings));
  for (double r : {0.3, 0.6})
    for (PolylineInput& l : iso_lines(source.mesh, distance, r)) c.polylines.push_back(std::move(l));
  c.guide_count = c.polylines.size();
  return c;
}

SourceConstraints entry_constraints(const MacroConstraint& entry) {
  SourceConstraints c;
  c.polylines = inputs_of(entry.guides);
  c.guide_count = c.polylines.size();
  for (PolylineInput& l : inputs_of(entry.features)) c.polylines.push_back(std::move(l));
  c.singularities = entry.singularities;
  const Eigen::Index n = static_cast<Eigen::Index>(entry.vertex_count());
  for (const VertexField& f : entry.fields) {
    NamedField out;
    out.name = f.name;
    out.kind = f.kind;
    out.dimension = static_cast<int>(f.dimension);
    if (f.kind == FieldKind::integer_label) {
      out.labels = f.labels;
    } else {
      out.values.resize(n, out.dimension);
      for (Eigen::Index v = 0; v < n; ++v)
        for (int k = 0; k < out.dimension; ++k)
          out.values(v, k) = f.values[static_cast<std::size_t>(v * out.dimension + k)];
    }
    c.fields.push_back(std::move(out));
  }
  return c;
}

std::vector<NamedField> transfer_fields(const MapView& view, const std::vector<NamedField>& fields) {
  std::vector<NamedField> out;
  for (const NamedField& f : fields) {
    NamedField t = f;
    if (f.kind == FieldKind::integer_label) {
      t.labels = transfer_labels(view, f.dimension, f.labels, -1);
    } else if (f.kind == FieldKind::tangent_vector) {
      std::vector<Vec3> vectors;
      for (Eigen::Index v = 0; v < f.values.rows(); ++v) vectors.emplace_back(f.values.row(v).transpose());
      const std::vector<Vec3> mapped = transfer_tangent_vectors(view, vectors);
      t.values.resize(static_cast<Eigen::Index>(mapped.size()), 3);
      for (std::size_t w = 0; w < mapped.size(); ++w) t.values.row(static_cast<Eigen::Index>(w)) = mapped[w].transpose();
    } else {
      t.values = transfer_interpolated(view, f.values);
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<NamedField> carry_fields(const CutMesh& cut, const TriMesh& input, const std::vector<NamedField>& fields) {
  std::vector<NamedField> out;
  for (const NamedField& f : fields) {
    NamedField c = f;
    if (f.kind == FieldKind::integer_label)
      c.labels = carry_labels(cut, input, f.labels, f.dimension);
    else
      c.values = carry_vertex_values(cut, input, f.values);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<io::VertexAttribute> field_attributes(const std::vector<NamedField>& fields) {
  std::vector<io::VertexAttribute> out;
  for (const NamedField& f : fields) {
    const bool labels = f.kind == FieldKind::integer_label;
    const std::size_t n = labels ? f.labels.size() / static_cast<std::size_t>(f.dimension)
                                 : static_cast<std::size_t>(f.values.rows());
    auto value = [&](std::size_t v, int k) {
      return labels ? static_cast<double>(f.labels[v * static_cast<std::size_t>(f.dimension) + k])
                    : f.values(static_cast<Eigen::Index>(v), k);
    };
    const bool one = f.dimension <= 3;
    for (int first = 0; first < f.dimension; first += one ? f.dimension : 1) {
      io::VertexAttribute a{one ? f.name : f.name + "_" + std::to_string(first), one ? f.dimension : 1, {}};
      for (std::size_t v = 0; v < n; ++v)
        for (int k = first; k < first + a.components; ++k) a.values.push_back(value(v, k));
      out.push_back(std::move(a));
    }
  }
  return out;
}

}  // namespace mcon::cli
