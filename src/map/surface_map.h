// Re-embedding map between two disk patches (thesis ch. 4): Phi = g^-1 o phi o f, where f and g
// are the patches' unit-disk parametrizations and phi is a locally injective 2D deformation of
// the source disk found by (1) the best rigid (possibly mirrored) alignment of descriptors
// (rigid_alignment.h) and (2) projected Newton on a continuous descriptor + conformal distortion +
// injectivity energy (map_energy.h, map_optimization.h), coarse to fine over descriptor
// smoothness. The map is partial: source points whose image leaves the target disk have no
// correspondence.
//
// Typical use with a patch and its descriptors:
//   auto levels_s = descriptor_pyramid(src_patch.mesh, mean_curvature_descriptor(src_patch.mesh), {0.3, 0.15, 0});
//   auto levels_t = descriptor_pyramid(dst_patch.mesh, mean_curvature_descriptor(dst_patch.mesh), {0.3, 0.15, 0});
//   SurfaceMap map = compute_surface_map({src_patch.mesh, src_patch.uv, levels_s},
//                                        {dst_patch.mesh, dst_patch.uv, levels_t}, options);
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "map/map_energy.h"
#include "map/map_optimization.h"
#include "mesh/mesh.h"
#include "mesh/surface_point.h"
#include "map/rigid_alignment.h"

namespace mcon {

// One side of the map, viewed (not copied): the references must outlive the call.
struct MapDomain {
  const TriMesh& mesh;                                   // 3D patch: its area element weighs everything
  const std::vector<Vec2>& uv;                           // unit-disk parametrization, one per vertex
  const std::vector<Eigen::MatrixXd>& descriptor_levels; // smoothest first; rows = vertices, d columns
};

// Which orientations the map may take. automatic: the descriptors and energies decide (with
// alignment.allow_reflection); preserve / reverse force one, e.g. when a host lets its user flip
// a nearly mirror-symmetric patch (a forearm strip) whose orientation the geometry cannot tell.
enum class MapOrientation { automatic, preserve, reverse };

struct SurfaceMapOptions {
  MapOrientation orientation = MapOrientation::automatic;
  RigidAlignmentOptions alignment;
  MapEnergyWeights weights;
  NewtonOptions newton;        // per descriptor level
  double sigma_scale = 1.0;    // Gaussian width = sigma_scale * (descriptor std of the level)
  double rim_band = 0.05;      // width of the score's fade-out inside the unit circle (uv units)
  // Mirror decision: if the best plain and mirrored rigid starts score within this of each other,
  // both are optimized at the smoothest level and the lower energy decides; the mirrored one must
  // be lower by the relative margin (orientation-blind descriptors rate a symmetric patch and its
  // mirror image alike, and then the orientation-preserving map is the safe answer).
  double orientation_ambiguity = 0.05;
  // Descriptor columns that change sign under a reflection (chiral channels, patch_map.cpp): a
  // mirrored map compares the source's negated values with the target's.
  std::vector<int> chiral_columns;
  double mirror_energy_margin = 0.1;
  // Levels (from the smoothest) both orientations are optimized through before the energies are
  // compared; the winner continues alone.
  int compared_levels = 1;
  // Refinement after the finest level: one more Newton pass at the finest descriptors per entry,
  // with the Gaussian width scaled by it (each > 0). A continuation in the kernel width: the wide
  // kernel finds the basin, but near the optimum its pull is weak (the Welsch cost is about
  // d^2 / (2 sigma^2)), so the distortion prior holds every point off its descriptor match by a
  // bias that grows with sigma^2; the narrower kernel then pulls the map the rest of the way.
  // Measured (eval-mapping, seeds 1-7, 91 pairs, mean eps x 100 averaged over seeds) with {0.5}
  // against {}: hand 3.28 -> 2.77, foot 2.84 -> 2.69, eye 2.67 -> 2.64, face and mouth lower,
  // ear 2.21 -> 2.24, nose 2.90 -> 3.01 (its descriptors differ most between people, and a
  // narrower kernel locks onto their differences). Narrower factors (0.35, or 0.5 then 0.25)
  // help hands more and hurt noses more.
  std::vector<double> refine_sigma_factors = {0.5};
  // Newton iterations per refinement pass (also at most newton.max_iterations): the gain comes in
  // the first few (a cap of 8 or 12 gave the same eval-mapping means to within 0.05), and an
  // uncapped pass took 25 iterations on the 11.5k-vertex face (bench: about +4 s instead of +0.9 s).
  int refine_max_iterations = 10;
  // A rigid start from a world frame the patches share (PatchMapOptions::use_world_frame): when
  // set, it is the start and decides the orientation (no comparison, `orientation` must be
  // automatic); the descriptor search still runs and its scores are reported.
  std::optional<RigidTransform2D> frame_start;
  // The anchor term's positions (map_energy.h), one per source vertex; read when
  // weights.anchor > 0 (map_patches fills it from the world frame's closest points).
  MapAnchor anchor;
  // The anchor weight of stage s is weights.anchor * anchor_decay^s: a strong pull at the
  // smoothest level keeps the map in the anchor's basin, the finer stages let the descriptors
  // move it (in (0, 1]; docs/design.md §11).
  double anchor_decay = 0.25;
  // Without anchor positions (weights.anchor 0): the anchor term's weight towards each
  // candidate's own rigid start (0 = off), with the same decay; keeps the optimization in the
  // start's basin when the start is trusted (up hints, PatchMapOptions::up_start_anchor).
  double start_anchor = 0.0;
  // Coarse to fine in mesh resolution: the first coarse_stages stages (at least compared_levels,
  // at most all but the last) run on a copy of the source disk coarsened to
  // max(coarse_vertices, n / 4) vertices (coarse_source.h), whose result is prolonged to the
  // full source for the rest; only for sources of at least 2 * coarse_vertices vertices. The few
  // triangles a prolonged map folds are untangled (untangle_folds); if that fails, an earlier
  // coarse stage's map is prolonged and the later stages run again on the full source (all of
  // them if none untangles). coarse_stages 0 = off. Measured in docs/design.md §13 (3 stages,
  // all but the refinement pass: 1.6-1.9x at 11.5k vertices at the same accuracy; coarse_vertices
  // 700 cost the face class 0.02 eps x 100 in eval-mapping, 1000 nothing).
  int coarse_stages = 3;
  int coarse_vertices = 1000;
  // Progress in [0, 1] on the calling thread; returning false throws MCON_ERROR_CANCELLED.
  std::function<bool(double)> progress;
};

// One optimization stage: a descriptor level (smoothest first), then the refinement passes
// (SurfaceMapOptions::refine_sigma_factors) at the finest descriptors.
struct LevelReport {
  int iterations = 0;
  StopReason stop_reason = StopReason::iteration_cap;
  double energy_start = 0;
  double energy_end = 0;
  double sigma = 0;  // Gaussian width used at this stage
};

struct SurfaceMap {
  std::vector<Vec2> phi;                          // phi(f(v)) per source vertex, in the target disk's plane
  bool reflected = false;                         // orientation reversing (e.g. left eye onto right eye)
  RigidAlignmentResult alignment;                 // the rigid start and its scores
  bool orientation_compared = false;              // both orientations were optimized at level 0
  double level0_energy_unreflected = -1;          // their level-0 energies (-1 if not compared)
  double level0_energy_reflected = -1;
  // Which start decided the orientation and the rigid start: the world frame (frame_start given;
  // alignment.transform is then that start and alignment.score its score) or the descriptors.
  bool frame_decided = false;
  std::vector<SurfacePoint> source_to_target; // per source vertex: where Phi(v) lies on the target
  std::vector<SurfacePoint> target_to_source; // per target vertex: where Phi^-1(w) lies on the source
  double overlap_ratio = 0;                       // |S'| / |S|: source 3D area mapped into the target
  MapEnergyTerms energy;                          // final terms, with the finest level's Gaussian width
  double matching_score = 0;                      // 1 - energy.descriptor
  int iterations = 0;                             // Newton iterations over all stages
  int factorizations = 0;                         // Hessian factorizations over all stages (of the
                                                  // returned orientation, as iterations)
  int inner_iterations = 0;                       // conjugate-gradient iterations, likewise
  StopReason stop_reason = StopReason::iteration_cap;  // of the finest descriptor level
  std::vector<LevelReport> levels;                // descriptor levels, then refinement passes
  std::vector<double> energy_history;             // energy after every iterate (starts of stages included)
  std::vector<int> energy_history_level;          // stage (index into levels) of each history entry
  double alignment_seconds = 0;                   // wall time of the rigid initialization
  double optimization_seconds = 0;                // wall time of the non-rigid optimization
  int coarse_vertices = 0;                        // vertices of the coarse source (0: not used)
  int coarse_stages = 0;                          // stages whose coarse result was kept
  int coarse_folds = 0;                           // triangles the last coarse stage's prolonged map folded
  bool coarse_fallback = false;                   // they could not be untangled: an earlier stage's map
                                                  // (or the rigid start) went on at full resolution
};

// Throws mcon::Error: INVALID_ARGUMENT (sizes, dimensions, no levels, inverted uv triangles, a
// target uv boundary off the unit circle), NOT_A_DISK (target without exactly one boundary
// loop), NON_FINITE, CANCELLED (progress returned false), NUMERICAL (solver failure, or a result
// with inverted triangles, which the method is built never to return).
SurfaceMap compute_surface_map(const MapDomain& source, const MapDomain& target, const SurfaceMapOptions& options = {});

}  // namespace mcon
