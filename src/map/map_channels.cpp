#include "map/map_channels.h"

#include "base/error.h"
#include "descriptors/curvature_descriptors.h"
#include "map/patch_map.h"
#include "operators/heat_geodesics.h"

namespace mcon {

namespace {

constexpr double kChiralityCenterRadius = 0.3;  // normalized geodesic radius of the center normal

// Mean curvature at sigma 0.1 (thesis §4.4: smooth, orientation-blind).
Eigen::VectorXd mean_curvature_channel(const PatchCenterFrame& f) { return mean_curvature_descriptor(f.patch->mesh); }

// The geodesic distance from the patch center. Both patches are geodesic disks around
// corresponding centers (docs/design.md §1: "patches are disks with a known center"), so it pins
// every point's ring, which curvature alone cannot on parts with repeated features (fingers, toes).
Eigen::VectorXd center_distance_channel(const PatchCenterFrame& f) { return f.center_distance; }

// Arc - chord: the geodesic minus the straight 3D distance to the center (both in radius units):
// zero along straight directions, growing across bent ones, so it tells the directions of a bent
// patch apart (across vs. along a forearm, where intrinsic descriptors are blind).
Eigen::VectorXd arc_minus_chord_channel(const PatchCenterFrame& f) {
  const TriMesh& mesh = f.patch->mesh;
  Eigen::VectorXd chord(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) chord[v] = (mesh.positions[v] - f.center).norm();
  return f.center_distance - chord;
}

// Chirality: n_c . ((p - c) x n_p), with n_p the vertex normal and n_c the mean normal around the
// center. It is invariant to rigid motions and changes sign under a reflection, so unlike every
// other channel it tells a right foot from a left one (orientation-blind descriptors rate a patch
// and its mirror image alike, which made the mirror decision a coin toss on feet).
Eigen::VectorXd chirality_channel(const PatchCenterFrame& f) {
  const TriMesh& mesh = f.patch->mesh;
  const int n = mesh.num_vertices();
  Vec3 nc = Vec3::Zero();
  for (int v = 0; v < n; ++v)
    if (f.center_distance[v] < kChiralityCenterRadius) nc += f.normals[v];
  if (nc.norm() > 0) nc.normalize();
  Eigen::VectorXd c(n);
  for (int v = 0; v < n; ++v) {
    const double len = f.normals[v].norm();
    c[v] = len > 0 ? nc.dot((mesh.positions[v] - f.center).cross(f.normals[v] / len)) : 0.0;
  }
  return c;
}

double unit_weight(const PatchMapOptions&) { return 1.0; }
double center_distance_weight(const PatchMapOptions& o) { return o.center_distance_weight; }
double chord_weight(const PatchMapOptions& o) { return o.chord_weight; }
double chirality_weight(const PatchMapOptions& o) { return o.chirality_weight; }

}  // namespace

const std::vector<MapChannel>& map_channels() {
  static const std::vector<MapChannel> table = {
      {"mean_curvature", unit_weight, false, false, mean_curvature_channel},
      {"center_distance", center_distance_weight, false, true, center_distance_channel},
      {"arc_minus_chord", chord_weight, false, true, arc_minus_chord_channel},
      {"chirality", chirality_weight, true, true, chirality_channel},
  };
  return table;
}

PatchCenterFrame patch_center_frame(const Patch& patch) {
  const TriMesh& mesh = patch.mesh;
  require(patch.center.triangle >= 0 && patch.center.triangle < mesh.num_triangles(), MCON_ERROR_INVALID_ARGUMENT,
          "map_patches: the patch has no center triangle");
  PatchCenterFrame f;
  f.patch = &patch;
  const Vec3 b = patch.center.barycentric.cwiseMax(0.0) / patch.center.barycentric.cwiseMax(0.0).sum();
  f.center_distance = HeatGeodesics(mesh).from_point(patch.center.triangle, b);
  const Tri& t = mesh.triangles[patch.center.triangle];
  f.center = b[0] * mesh.positions[t[0]] + b[1] * mesh.positions[t[1]] + b[2] * mesh.positions[t[2]];
  f.normals.assign(mesh.num_vertices(), Vec3::Zero());
  for (const Tri& tr : mesh.triangles) {
    const Vec3 a = (mesh.positions[tr[1]] - mesh.positions[tr[0]]).cross(mesh.positions[tr[2]] - mesh.positions[tr[0]]);
    for (int k = 0; k < 3; ++k) f.normals[tr[k]] += a;
  }
  return f;
}

}  // namespace mcon
