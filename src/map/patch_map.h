// The re-embedding map between two extracted geodesic-disk patches (thesis ch. 4): the patch-level
// entry point that the C API, the CLI and the evaluation share. It chooses the map descriptor,
// builds the coarse-to-fine pyramid on each patch (descriptor_pyramid.h) and runs
// compute_surface_map (surface_map.h) on the patches' disk parametrizations.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <optional>

#include "patch/geodesic_disk_patch.h"
#include "map/surface_map.h"

namespace mcon {

struct PatchMapOptions {
  SurfaceMapOptions map;  // alignment (samples, seed, reflections), weights, Newton options
  // Heat-smoothing widths of the descriptor pyramid (normalized patch units), smoothest first;
  // 0 is the unsmoothed descriptor.
  std::vector<double> pyramid_sigmas = {0.3, 0.15, 0.0};
  // Descriptor channels besides the mean curvature (each normalized to std 1 over both patches,
  // then scaled by its weight; 0 drops it): the geodesic distance from the patch center, and the
  // difference between that arc and the straight 3D chord to the center. All three 0: the
  // thesis' mean curvature alone.
  double center_distance_weight = 1.0;
  double chord_weight = 1.0;
  // A chiral channel (changes sign under reflection; patch_map.cpp), so that mirrored and
  // same-side pairs are told apart by the descriptors themselves. Weight 1 with the arc - chord
  // channel measured best on eval-mapping seeds 1-7 (91 pairs; per-class mean eps x 100 averaged
  // over the seeds, against weight 2 with the earlier chord channel built from the standardized
  // arc): nose 2.9 vs 3.2, ear 2.2 vs 2.7, hand 3.3 vs 3.4, foot 2.9 vs 3.0, eye and face equal,
  // mouth better on 5 of 7 seeds; 0.5 was no better. Forearm strips are nearly mirror-symmetric:
  // a plain map that swaps their sides fits about as well, and ties go to the plain orientation
  // (the mirrored forearm pair stays plain on 5 of 7 seeds, 4 of 7 with the earlier channel;
  // same-side pairs are right on all 7), which is why hosts can force it
  // (SurfaceMapOptions::orientation).
  double chirality_weight = 1.0;
  // Optional guidance channels from the host, one row per vertex of the source / target patch
  // and the same columns on both (e.g. painted region labels, landmark distances): appended to
  // the geometric channels, each column normalized jointly like them, then scaled by
  // guidance_weight. Both null: none. The matrices are read during the call only. The benchmark's
  // `oracle` method feeds ground-truth correspondents through here to measure what the
  // optimizer reaches when the descriptors are unambiguous.
  const Eigen::MatrixXd* source_guidance = nullptr;
  const Eigen::MatrixXd* target_guidance = nullptr;
  double guidance_weight = 1.0;
  // The 3D-aligned start, for patches that share a world frame (two meshes in one DCC scene; not
  // a library entry from another asset): the similarity ICP of the source onto the target in host
  // coordinates (map/similarity_icp.h), expressed in the two disk parametrizations as a 2D rigid
  // motion (world_frame_start below), becomes the rigid start and decides orientation and
  // reflection (SurfaceMap::frame_decided). world_frame_mirror: mirror the source x -> -x in the
  // world first (mapping a left part onto a right one, +x the subject's left). Default off: the
  // frame-free behaviour. Requires map.orientation automatic.
  bool use_world_frame = false;
  bool world_frame_mirror = false;
  // With use_world_frame: the weight of the anchor term (map_energy.h) pulling every source
  // vertex towards the target uv of its 3D closest point after the ICP (WorldFrame::anchor); 0
  // turns it off. Ignored without use_world_frame. 10 (with SurfaceMapOptions::anchor_decay
  // 0.25): chosen among five settings on eval-mapping, in-family and --cross-family (docs/design.md §11).
  double world_frame_anchor = 10.0;
  // Up hints: the up direction of each patch's host in its own coordinates (a DCC's up axis; the
  // two need not share a world frame). Both or neither. Each is projected onto its patch's tangent
  // plane at the center and carried into the patch's uv (up_direction_in_uv); the rotation taking
  // the source's onto the target's becomes a prior of the rigid search (RigidAlignmentOptions::
  // use_up_prior: no candidate turned more than 60 degrees from it), so an upside-down start is
  // never chosen. INVALID_ARGUMENT for a zero or non-finite vector, or one within about 11
  // degrees of the patch normal at the center (no direction in the patch).
  std::optional<Vec3> source_up;
  std::optional<Vec3> target_up;
  // With up hints (and no world-frame anchor): SurfaceMapOptions::start_anchor, the pull towards
  // the hint-respecting rigid start that keeps the optimization from turning away from it
  // (docs/design.md §12). 0 turns it off.
  double up_start_anchor = 1.0;
};

// The unit direction in the patch's uv of the 3D direction `up` at the patch's center: `up`
// projected onto the tangent plane (area-weighted normal of the triangles within 0.3 of the
// center, normalized units) and mapped by the least-squares linear map from 3D edge vectors to uv
// edge vectors of those triangles. `what` names the argument in errors.
Vec2 up_direction_in_uv(const Patch& patch, const Vec3& up, const char* what);

// The world frame's view of a pair: the rigid start and, per source vertex, the target uv of its
// closest point after the ICP (weight 0 where that point lies on the target's rim: the source
// reaches beyond the target there, and the rim is not its correspondent).
struct WorldFrame {
  RigidTransform2D start;
  MapAnchor anchor;
};

// ICP of source onto target in host coordinates, then the area-weighted 2D Procrustes fit
// (rotation + translation, plain or mirrored, whichever leaves the smaller residual) taking each
// source vertex's uv to the target uv of its closest point.
WorldFrame world_frame(const Patch& source, const Patch& target, bool mirror_x);

// The world-frame start alone (world_frame(...).start).
RigidTransform2D world_frame_start(const Patch& source, const Patch& target, bool mirror_x);

// Maps `source` onto `target` (both from extract_geodesic_disk, normalized to radius 1).
// Throws what compute_surface_map throws (INVALID_ARGUMENT, NOT_A_DISK, NON_FINITE, CANCELLED,
// NUMERICAL).
SurfaceMap map_patches(const Patch& source, const Patch& target, const PatchMapOptions& options = {});

}  // namespace mcon
