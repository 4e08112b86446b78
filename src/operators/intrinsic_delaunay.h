// Intrinsic Delaunay triangulation (Bobenko & Springborn 2007; Fisher et al. 2006): the same
// vertices and the same surface metric, but edges flipped (as geodesics on the surface) until
// every interior edge is Delaunay. Its cotan Laplacian has only non-negative edge weights, so
// heat flow obeys a maximum principle even on meshes with obtuse, sliver or quad-split triangles,
// where the extrinsic cotan Laplacian produces negative heat and bad gradients.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "operators/cotan_laplacian.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"

namespace mcon {

struct IntrinsicTriangulation {
  int num_vertices = 0;
  // Triangles over the mesh's vertices, in the mesh's orientation. Unlike a TriMesh, two
  // triangles may share more than one edge and a triangle may use a vertex twice (intrinsic
  // edges are geodesic segments, not vertex pairs).
  std::vector<Tri> triangles;
  // lengths[t][i]: length of the edge from corner i to corner i + 1 of triangle t.
  std::vector<std::array<double, 3>> lengths;
  // across[t][i]: the same edge seen from the other triangle, as 3 * triangle + slot, or -1 on
  // the boundary.
  std::vector<std::array<int, 3>> across;
  int flips = 0;  // edge flips performed by make_delaunay
};

// The mesh's own triangles with their edge lengths (no flips).
IntrinsicTriangulation intrinsic_triangulation(const TriMesh& mesh, const MeshTopology& topology);

// Flips non-Delaunay interior edges (opposite angles summing to more than pi) until none is
// left. Boundary edges never move, so boundary vertices and loops stay as they are.
void make_delaunay(IntrinsicTriangulation& triangulation);

// Area of the triangle with these side lengths (Kahan's stable form of Heron's formula).
double triangle_area_from_lengths(double a, double b, double c);

// The cotan Laplacian and lumped mass of an intrinsic triangulation, with the conventions of
// cotan_laplacian / vertex_areas on a TriMesh (equal to them before any flip).
SparseMatrix cotan_laplacian(const IntrinsicTriangulation& triangulation);
Eigen::VectorXd vertex_areas(const IntrinsicTriangulation& triangulation);

}  // namespace mcon
