// What `macrocon embed` transfers: the source's constraints (guide and feature polylines,
// singularities, named per-vertex fields), either those of a library entry (--source LIB --entry)
// or, for a plain mesh source, synthetic ones that show the map (uv, mean curvature, geodesic
// distance and a ring label per vertex, iso-distance guide loops), and the fields on the target.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/mesh_io.h"
#include "macrocon/macrocon.hpp"

namespace mcon::cli {

struct SourceConstraints {
  std::vector<macrocon::Polyline> polylines;  // the guides, then the features
  std::size_t guide_count = 0;
  std::vector<mcon_singularity> singularities;
  std::vector<macrocon::VertexField> fields;
};

// Synthetic constraints of a mesh source: source_uv, source_mean_curvature,
// source_geodesic_distance (from the center), source_ring (distance in steps of 0.25, a label) and
// guide loops at geodesic distance 0.3 and 0.6.
SourceConstraints synthetic_constraints(const macrocon::Patch& source);
// A library entry's own guides, features, singularities and fields (its patch is the source).
SourceConstraints entry_constraints(const macrocon::EntryData& entry);

// Source fields -> target vertices (outside the overlap: zeros, labels -1).
std::vector<macrocon::VertexField> transfer_fields(const macrocon::Map& map,
                                                   const std::vector<macrocon::VertexField>& fields);

// Where each vertex of a cut patch lies on the patch it was cut from.
struct CutHostPoints {
  std::vector<std::uint32_t> triangles;        // patch triangle per cut vertex
  std::vector<double> barycentric;             // 3 per cut vertex
  std::vector<std::uint32_t> patch_triangles;  // the patch's triangles, 3 indices each
};

// Target fields -> the vertices of the target cut along the guides (labels: the patch corner with
// the largest weight).
std::vector<macrocon::VertexField> carry_fields(const macrocon::CutMesh& cut, const CutHostPoints& host,
                                                const std::vector<macrocon::VertexField>& fields);

// PLY vertex attributes: a field of 1-3 channels is one attribute (write_ply adds _x/_y/_z), a
// wider one a scalar per channel (NAME_0, NAME_1, ...).
std::vector<io::VertexAttribute> field_attributes(const std::vector<macrocon::VertexField>& fields);

// A label at a cut-mesh vertex: the label of its host triangle's corner with the largest weight.
template <typename T>
std::vector<T> carry_labels(const CutHostPoints& host, const std::vector<T>& labels, std::size_t dimension = 1) {
  std::vector<T> out;
  out.reserve(host.triangles.size() * dimension);
  for (std::size_t v = 0; v < host.triangles.size(); ++v) {
    const double* b = &host.barycentric[3 * v];
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (b[j] > b[k]) k = j;
    const std::size_t corner = host.patch_triangles[3 * static_cast<std::size_t>(host.triangles[v]) + k];
    for (std::size_t c = 0; c < dimension; ++c) out.push_back(labels[corner * dimension + c]);
  }
  return out;
}

}  // namespace mcon::cli
