// Re-tessellations that keep an exact ground truth, so that the benchmark can test whether a method
// depends on the triangulation rather than the shape: (a) the quads of the source OBJ split along
// their other diagonal (same vertices, other triangles), (b) random decimation by halfedge collapse
// onto an existing vertex (the surviving vertices keep their positions and identity, so the ground
// truth is the identity on surviving original vertex indices).
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace mcon::tools {

struct Retessellation {
  TriMesh mesh;                  // validated
  std::vector<int> to_original;  // new vertex -> vertex of the input mesh
  int changed = 0;               // quads re-split (a) or vertices removed (b)
};

// Which quads get the other diagonal. The choice depends on the quad's file face index only, so a
// patch and the whole mesh agree on every quad they share.
enum class DiagonalPattern {
  All,        // every quad
  Alternate,  // quads with an odd face index
  Random,     // each quad with probability 1/2, from the seed
};

// `mesh` is triangulated as the readers do (polygon a,b,c,d -> a,b,c + a,c,d, consecutive
// triangles) and `triangle_to_face` gives each triangle's file face (io::LoadedMesh): two
// consecutive triangles of one face form a quad, which is re-split as a,b,d + b,c,d. Other faces
// (triangles, n-gons, quads cut in half by a patch boundary) stay. A quad also stays if the other
// diagonal would give a degenerate triangle or one facing away from the quad (concave or strongly
// bent quads). Works on any instance of the base mesh (same triangles, other positions).
// Throws mcon::Error(MCON_ERROR_INVALID_ARGUMENT) on inconsistent input.
Retessellation rediagonalize(const TriMesh& mesh, const std::vector<int>& triangle_to_face, DiagonalPattern pattern,
                             std::uint64_t seed = 0);

struct DecimationOptions {
  // Fraction of the vertices to remove, drawn uniformly in [min_fraction, max_fraction] from the
  // seed (equal values fix it).
  double min_fraction = 0.2;
  double max_fraction = 0.4;
  // Vertices that must survive (e.g. patch centers or a patch's boundary); they may still receive
  // collapses.
  std::vector<int> keep;
  // A collapse is rejected if a remaining triangle's normal turns by more than this ...
  double max_normal_change_degrees = 60.0;
  // ... or its shape quality 4 sqrt(3) area / (sum of squared edges) (1 = equilateral) falls below
  // min(min_quality, its quality before).
  double min_quality = 0.1;
};

// Seeded random decimation by halfedge collapse (OpenMesh): random halfedges v0 -> v1 in a seeded
// order are collapsed into v1 until the drawn fraction is removed. Rejected: collapses that fail
// OpenMesh's link condition (non-manifold results), touch a boundary vertex of the mesh (so a patch
// keeps its boundary), remove a `keep` vertex, or flip or crush a triangle (options). If the mesh
// runs out of valid collapses first, fewer vertices are removed (`changed` says how many). The
// result's vertices are the surviving input vertices in input order with their exact positions.
Retessellation decimate(const TriMesh& mesh, std::uint64_t seed, const DecimationOptions& options = {});

}  // namespace mcon::tools
