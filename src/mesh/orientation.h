// Winding repair of an input mesh: every connected component is oriented consistently (BFS across
// its manifold edges) and outward (signed volume), before anything downstream sees it, and what
// was changed is reported. docs/api.md "Input orientation" holds the rules and their reasons.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace mcon {

// How a component's orientation is chosen once it is consistent.
enum class OrientationRule {
  // Outward: a positive signed volume. Closed components use their own volume, open ones the
  // volume after closing every boundary loop with a fan around its centroid; a component whose
  // volume is negligible (flat, |V| <= 1e-6 A^1.5) keeps the majority of its input triangles.
  outward,
  // The majority of the component's input triangles (ties: its first triangle), for meshes that
  // have no inside, such as a disk patch: consistent input is never changed.
  majority,
};

struct OrientationReport {
  int components = 0;
  int closed_components = 0;
  // Components whose input triangles disagreed (some were reversed to agree with the rest).
  int inconsistent_components = 0;
  // Components that faced inward (negative volume, after the majority repair) and were turned.
  int components_turned_outward = 0;
  int reoriented_triangles = 0;
  // Per triangle: 1 if its corners 1 and 2 were swapped (barycentric weights given in the input's
  // corner order swap the same way).
  std::vector<unsigned char> reoriented;
};

// What the input path does with the defects a production mesh carries away from where the user
// works (zero-area triangles, edges of more than two triangles, pinched and isolated vertices):
// reject them (the default), or defer them to the operations, each of which validates what it
// reads (validate_mesh_part, mesh/mesh.h; docs/api.md "Local validation").
enum class DefectPolicy { reject, defer };

// Orients `mesh` in place: swaps corners 1 and 2 of the triangles that need it. Needs finite
// positions and in-range, distinct indices (validate_mesh_elements). Throws NON_MANIFOLD_EDGE for
// an edge with more than two triangles and NON_ORIENTABLE (naming a triangle of the component and
// the fix) for a component that has no consistent orientation (a Moebius strip).
// With DefectPolicy::defer an edge of more than two triangles links none of them (orientation
// does not propagate across it) instead of throwing.
OrientationReport orient_mesh(TriMesh& mesh, OrientationRule rule = OrientationRule::outward,
                              DefectPolicy defects = DefectPolicy::reject);

// validate_mesh_elements, orient_mesh, validate_mesh: the input path of every user mesh. With
// DefectPolicy::defer only validate_mesh_indices runs before orienting, and nothing after.
OrientationReport orient_and_validate(TriMesh& mesh, OrientationRule rule = OrientationRule::outward,
                                      DefectPolicy defects = DefectPolicy::reject);

}  // namespace mcon
