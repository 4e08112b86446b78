// Guide and feature polylines, and single points (singularities), of the source patch -> the
// target patch through Phi = g^-1 o phi o f (thesis eq. 4.1, Fig. 4.3). A source point keeps its
// barycentric coordinates in phi(source triangle); its image in the target disk's plane is lifted
// by g^-1 (the target triangle containing it). A polyline is re-traced on the target: the straight
// segment between two consecutive mapped points in that plane (phi-space) is walked triangle by
// triangle through the target's uv triangulation and split at every target edge it crosses, so
// every output segment lies inside one target triangle and therefore on the target surface.
// Then each crossing slides along its edge to the shortest path through those triangles
// (polyline_straightening.h): the line of phi-space zig-zags on the surface where g is squeezed.
// Parts that leave the target disk (outside the overlap) are dropped: one input polyline may give
// several output polylines, or none.
#pragma once

#include <string>
#include <vector>

#include "mesh/surface_point.h"
#include "transfer/map_view.h"

namespace mcon {

struct PolylineInput {
  std::vector<SurfacePoint> points;  // on the source, >= 2
  bool closed = false;                     // the last point joins the first
};

struct TracedPolyline {
  // On the target. Point i carries the triangle that contains the segment (i, i+1) (for the last
  // point of an open polyline: its own triangle); a point where the walk crosses an edge is
  // expressed in the triangle the walk enters, so one barycentric weight is 0.
  std::vector<SurfacePoint> points;
  std::vector<Vec3> positions;  // the same points in the target's normalized coordinates
  bool closed = false;          // the whole closed input survived
  int input = -1;               // index of the input polyline
};

// A source point -> its target point (triangle -1 if its image lies outside the target disk).
// Throws INVALID_ARGUMENT for a triangle out of range or barycentric weights that are negative
// (below -1e-9) or do not sum to 1 (within 1e-6), NON_FINITE for NaN.
class PolylineTransfer {
 public:
  explicit PolylineTransfer(const MapView& map);
  ~PolylineTransfer();
  PolylineTransfer(const PolylineTransfer&) = delete;
  PolylineTransfer& operator=(const PolylineTransfer&) = delete;

  // The image of a source point in the target disk's plane (phi-space).
  Vec2 phi_of(const SurfacePoint& source_point) const;
  SurfacePoint map_point(const SurfacePoint& source_point) const;
  std::vector<TracedPolyline> map_polylines(const std::vector<PolylineInput>& polylines) const;

 private:
  struct Impl;
  Impl* impl_;
};


}  // namespace mcon
