// The constraints `macrocon embed` transfers (embed_constraints.h).
#include "embed_constraints.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace mcon::cli {
namespace {

// Iso-lines {d = value} of a per-vertex field as polylines of surface points (marching
// triangles: a vertex counts as above when d >= value, so every crossed triangle has exactly two
// crossed edges and the pieces chain into closed loops, or open chains ending on the boundary).
// `triangles`: 3 indices per triangle.
std::vector<macrocon::Polyline> iso_lines(const std::vector<std::uint32_t>& triangles, const std::vector<double>& d,
                                          double value) {
  using Edge = std::pair<std::uint32_t, std::uint32_t>;
  auto key = [](std::uint32_t a, std::uint32_t b) { return a < b ? Edge{a, b} : Edge{b, a}; };
  auto corner = [&](std::size_t t, int k) { return triangles[3 * t + static_cast<std::size_t>(k)]; };
  const std::size_t triangle_count = triangles.size() / 3;
  std::map<Edge, std::vector<std::size_t>> edge_triangles;  // crossed edge -> triangles that cross it
  for (std::size_t t = 0; t < triangle_count; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = corner(t, k), b = corner(t, (k + 1) % 3);
      if ((d[a] >= value) != (d[b] >= value)) edge_triangles[key(a, b)].push_back(t);
    }
  auto point_on = [&](const Edge& e, std::size_t t) {
    const double s = (value - d[e.first]) / (d[e.second] - d[e.first]);
    mcon_surface_point p{static_cast<std::uint32_t>(t), {0.0, 0.0, 0.0}};
    for (int k = 0; k < 3; ++k) {
      if (corner(t, k) == e.first) p.barycentric[k] = 1 - s;
      if (corner(t, k) == e.second) p.barycentric[k] = s;
    }
    return p;
  };
  auto other_edge = [&](std::size_t t, const Edge& e) {
    for (int k = 0; k < 3; ++k) {
      const Edge f = key(corner(t, k), corner(t, (k + 1) % 3));
      if (f != e && edge_triangles.count(f)) return f;
    }
    return e;
  };
  std::map<Edge, bool> used;
  std::vector<macrocon::Polyline> out;
  // Open chains start at boundary edges (one triangle), then closed loops anywhere.
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& [edge, tris] : edge_triangles) {
      if (used[edge] || (pass == 0 && tris.size() != 1)) continue;
      macrocon::Polyline line;
      Edge e = edge;
      std::size_t t = tris[0];
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

macrocon::VertexField real_field(std::string name, mcon_field_kind kind, std::uint32_t dimension,
                                 std::vector<double> values) {
  macrocon::VertexField f;
  f.name = std::move(name);
  f.kind = kind;
  f.dimension = dimension;
  f.values = std::move(values);
  return f;
}

}  // namespace

SourceConstraints synthetic_constraints(const macrocon::Patch& source) {
  SourceConstraints c;
  const mcon_patch_info info = source.info();
  const mcon_surface_point center{info.center_patch_triangle,
                                  {info.center_barycentric[0], info.center_barycentric[1], info.center_barycentric[2]}};
  const std::vector<double> distance = source.distance_from_point(center);
  macrocon::VertexField rings;
  rings.name = "source_ring";
  rings.kind = MCON_FIELD_INTEGER_LABEL;
  for (double d : distance) rings.labels.push_back(static_cast<std::int32_t>(std::floor(std::max(0.0, d) / 0.25)));
  c.fields.push_back(real_field("source_uv", MCON_FIELD_UV, 2, source.uv()));
  c.fields.push_back(real_field("source_mean_curvature", MCON_FIELD_SCALAR, 1,
                                source.compute_descriptors(MCON_DESCRIPTOR_MEAN_CURVATURE)));
  c.fields.push_back(real_field("source_geodesic_distance", MCON_FIELD_SCALAR, 1, distance));
  c.fields.push_back(std::move(rings));
  const std::vector<std::uint32_t> triangles = source.triangles();
  for (double r : {0.3, 0.6})
    for (macrocon::Polyline& l : iso_lines(triangles, distance, r)) c.polylines.push_back(std::move(l));
  c.guide_count = c.polylines.size();
  return c;
}

SourceConstraints entry_constraints(const macrocon::EntryData& entry) {
  SourceConstraints c;
  c.polylines = entry.polylines;  // read back guides first, then features
  c.guide_count =
      static_cast<std::size_t>(std::count_if(c.polylines.begin(), c.polylines.end(), [](const macrocon::Polyline& l) {
        return l.kind == MCON_POLYLINE_GUIDE;
      }));
  c.singularities = entry.singularities;
  c.fields = entry.fields;
  return c;
}

std::vector<macrocon::VertexField> transfer_fields(const macrocon::Map& map,
                                                   const std::vector<macrocon::VertexField>& fields) {
  std::vector<macrocon::VertexField> out;
  for (const macrocon::VertexField& f : fields) {
    macrocon::VertexField t = f;
    if (f.kind == MCON_FIELD_INTEGER_LABEL)
      t.labels = map.transfer_labels(f.dimension, f.labels, -1);
    else
      t.values = map.transfer_field(static_cast<mcon_field_kind>(f.kind), f.dimension, f.values);
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<macrocon::VertexField> carry_fields(const macrocon::CutMesh& cut, const CutHostPoints& host,
                                                const std::vector<macrocon::VertexField>& fields) {
  std::vector<macrocon::VertexField> out;
  for (const macrocon::VertexField& f : fields) {
    macrocon::VertexField c = f;
    if (f.kind == MCON_FIELD_INTEGER_LABEL)
      c.labels = carry_labels(host, f.labels, f.dimension);
    else
      c.values = cut.carry_field(f.values, f.dimension);
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<io::VertexAttribute> field_attributes(const std::vector<macrocon::VertexField>& fields) {
  std::vector<io::VertexAttribute> out;
  for (const macrocon::VertexField& f : fields) {
    const bool labels = f.kind == MCON_FIELD_INTEGER_LABEL;
    const std::size_t dimension = f.dimension;
    const std::size_t n = (labels ? f.labels.size() : f.values.size()) / dimension;
    auto value = [&](std::size_t v, std::size_t k) {
      return labels ? static_cast<double>(f.labels[v * dimension + k]) : f.values[v * dimension + k];
    };
    const bool one = dimension <= 3;
    for (std::size_t first = 0; first < dimension; first += one ? dimension : 1) {
      io::VertexAttribute a{
          one ? f.name : f.name + "_" + std::to_string(first), one ? static_cast<int>(dimension) : 1, {}};
      for (std::size_t v = 0; v < n; ++v)
        for (std::size_t k = first; k < first + static_cast<std::size_t>(a.components); ++k)
          a.values.push_back(value(v, k));
      out.push_back(std::move(a));
    }
  }
  return out;
}

}  // namespace mcon::cli
