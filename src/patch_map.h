// The re-embedding map between two extracted geodesic-disk patches (thesis ch. 4): the patch-level
// entry point that the C API, the CLI and the evaluation share. It chooses the map descriptor,
// builds the coarse-to-fine pyramid on each patch (descriptor_pyramid.h) and runs
// compute_surface_map (surface_map.h) on the patches' disk parametrizations.
#pragma once

#include <functional>

#include "geodesic_disk_patch.h"
#include "surface_map.h"

namespace mcon {

struct PatchMapOptions {
  SurfaceMapOptions map;  // alignment (samples, seed, reflections), weights, Newton options
  // Heat-smoothing widths of the descriptor pyramid (normalized patch units), smoothest first;
  // 0 is the unsmoothed descriptor.
  std::vector<double> pyramid_sigmas = {0.3, 0.15, 0.0};
  // Descriptor channels besides the mean curvature (each normalized to std 1 over both patches,
  // then scaled by its weight; 0 drops it): the geodesic distance from the patch center, and the
  // standardized distance minus the straight 3D chord to the center (patch_map.cpp says why not
  // the plain difference). All three 0: the thesis' mean curvature alone.
  double center_distance_weight = 1.0;
  double chord_weight = 1.0;
  // A chiral channel (changes sign under reflection; patch_map.cpp), so that mirrored and
  // same-side pairs are told apart by the descriptors themselves. 2 measured best on the default
  // eval-mapping run (1: overall mean eps x 100 10.8, forearms 26.5; 2: 7.3 and 4.9).
  double chirality_weight = 2.0;
};

// Maps `source` onto `target` (both from extract_geodesic_disk, normalized to radius 1).
// Throws what compute_surface_map throws (INVALID_ARGUMENT, NOT_A_DISK, NON_FINITE, CANCELLED,
// NUMERICAL).
SurfaceMap map_patches(const Patch& source, const Patch& target, const PatchMapOptions& options = {});

}  // namespace mcon
