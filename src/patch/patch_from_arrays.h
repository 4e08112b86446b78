// A patch from a mesh that is already a normalized disk (a constraint library entry, or a patch
// cut and stored elsewhere): nothing is cut. The mesh must be one topological disk; it gets the
// same unit-disk parametrization as an extracted patch (disk_parametrization.h), and its host is
// the mesh itself (identity host links), placed in host units by a frame.
#pragma once

#include "patch/geodesic_disk_patch.h"

namespace mcon {

struct PatchFrame {
  SurfacePoint center{-1, Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3)};  // the center as a point of the mesh (required)
  Vec3 origin = Vec3::Zero();  // host = origin + scale * normalized position
  double scale = 1.0;          // > 0
};

// `mesh` must already be validated (validate_mesh). Throws NOT_A_DISK (with the reason: several
// pieces, several boundary loops, a closed surface, a handle), INVALID_ARGUMENT (bad center or
// scale), NON_FINITE (NaN in the frame), NUMERICAL (parametrization failure).
Patch patch_from_mesh(TriMesh mesh, const PatchFrame& frame);

}  // namespace mcon
