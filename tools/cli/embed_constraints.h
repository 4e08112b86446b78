// What `macrocon embed` transfers: the source's constraints (guide and feature polylines,
// singularities, named per-vertex fields), either those of a library entry (--source LIB --entry)
// or, for a plain mesh source, synthetic ones that show the map (uv, mean curvature, geodesic
// distance and a ring label per vertex, iso-distance guide loops), and the fields on the target.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/mesh_io.h"
#include "library/constraint_library.h"
#include "patch/geodesic_disk_patch.h"
#include "transfer/guide_cutting.h"
#include "transfer/map_view.h"
#include "transfer/polyline_transfer.h"

namespace mcon::cli {

// A per-vertex field: real channels (blended; tangent vectors pushed through the map's Jacobian)
// or integer labels (the nearest corner's, never blended).
struct NamedField {
  std::string name;
  FieldKind kind = FieldKind::scalar;
  int dimension = 1;
  Eigen::MatrixXd values;            // vertices x dimension (every kind but integer_label)
  std::vector<std::int32_t> labels;  // vertex-major, vertices * dimension (integer_label)
};

struct SourceConstraints {
  std::vector<PolylineInput> polylines;  // the guides, then the features
  std::size_t guide_count = 0;
  std::vector<Singularity> singularities;
  std::vector<NamedField> fields;
};

// Synthetic constraints of a mesh source: source_uv, source_mean_curvature,
// source_geodesic_distance (from the center), source_ring (distance in steps of 0.25, a label) and
// guide loops at geodesic distance 0.3 and 0.6.
SourceConstraints synthetic_constraints(const Patch& source);
// A library entry's own guides, features, singularities and fields (its patch is the source).
SourceConstraints entry_constraints(const MacroConstraint& entry);

// Source fields -> target vertices (outside the overlap: zeros, labels -1).
std::vector<NamedField> transfer_fields(const MapView& view, const std::vector<NamedField>& fields);
// Target fields -> the vertices of the target cut along the guides (labels: the host corner
// with the largest weight).
std::vector<NamedField> carry_fields(const CutMesh& cut, const TriMesh& input, const std::vector<NamedField>& fields);

// PLY vertex attributes: a field of 1-3 channels is one attribute (write_ply adds _x/_y/_z), a
// wider one a scalar per channel (NAME_0, NAME_1, ...).
std::vector<io::VertexAttribute> field_attributes(const std::vector<NamedField>& fields);

// A label at a cut-mesh vertex: the label of its host triangle's corner with the largest weight.
template <typename T>
std::vector<T> carry_labels(const CutMesh& cut, const TriMesh& input, const std::vector<T>& labels, int dimension = 1) {
  std::vector<T> out;
  out.reserve(cut.host.size() * static_cast<std::size_t>(dimension));
  for (const SurfacePoint& h : cut.host) {
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (h.barycentric[j] > h.barycentric[k]) k = j;
    const std::size_t v = static_cast<std::size_t>(input.triangles[h.triangle][k]);
    for (int c = 0; c < dimension; ++c) out.push_back(labels[v * static_cast<std::size_t>(dimension) + c]);
  }
  return out;
}

}  // namespace mcon::cli
