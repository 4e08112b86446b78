// The per-vertex descriptor channels the re-embedding map matches (thesis §4.4, docs/design.md §1),
// as one table: a channel has a name, its weight in PatchMapOptions, whether it changes sign under
// a reflection, and how it is computed on one patch. Adding a channel = one row in map_channels()
// (map_channels.cpp) plus its weight option.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "mesh/mesh.h"
#include "patch/geodesic_disk_patch.h"

namespace mcon {

struct PatchMapOptions;

// What the center-based channels of one patch share: the geodesic distance of every vertex from
// the patch center (heat method), the center point and the area-weighted vertex normals.
struct PatchCenterFrame {
  const Patch* patch = nullptr;
  Eigen::VectorXd center_distance;
  Vec3 center = Vec3::Zero();
  std::vector<Vec3> normals;
};

struct MapChannel {
  const char* name;
  double (*weight)(const PatchMapOptions& options);
  bool chiral;         // changes sign under a reflection (SurfaceMapOptions::chiral_columns)
  bool center_based;   // needs the patch center (computed only when a center channel is on)
  Eigen::VectorXd (*compute)(const PatchCenterFrame& frame);
};

// Every channel, in column order: mean_curvature, center_distance, arc_minus_chord, chirality.
const std::vector<MapChannel>& map_channels();

// The frame of one patch. Throws INVALID_ARGUMENT when the patch has no center triangle.
PatchCenterFrame patch_center_frame(const Patch& patch);

}  // namespace mcon
