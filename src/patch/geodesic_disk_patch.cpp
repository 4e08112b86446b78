#include "patch/geodesic_disk_patch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>

#include "patch/disk_parametrization.h"
#include "base/error.h"
#include "base/text.h"
#include "mesh/edge_key.h"
#include "operators/heat_geodesics.h"
#include "mesh/mesh_region.h"
#include "patch/region_repair.h"
#include "mesh/mesh_topology.h"

namespace mcon {
namespace {

// Work only within this multiple of the radius (edge-graph distance) around the center.
constexpr double kRegionFactor = 3.0;
// An enclosed part beyond a second cut loop is a pocket (mouth cavity, eye socket) if it is a
// cavity: its outward normals face its own centroid (normalized concavity > 0; measured +0.25 on
// the mouth and face pockets of both benchmark models). The far side of a limb that the disk
// wrapped around is a protrusion (measured -0.08 to -0.10 for a hand): then the disk is an annulus.
constexpr double kMinPocketConcavity = 0.05;

enum class Side : std::uint8_t { kIn, kOn, kOut };

void check_options(const TriMesh& host, const PatchOptions& o) {
  require(std::isfinite(o.radius) && o.radius > 0, MCON_ERROR_INVALID_ARGUMENT,
          "radius must be finite and > 0 (got " + number_text(o.radius) + ")");
  require(std::isfinite(o.snap_fraction) && o.snap_fraction >= 0 && o.snap_fraction <= 0.45,
          MCON_ERROR_INVALID_ARGUMENT, "snap_fraction must lie in [0, 0.45]");
  const PatchCenter& c = o.center;
  if (c.vertex >= 0) {
    require(c.vertex < host.num_vertices(), MCON_ERROR_INVALID_ARGUMENT,
            "center vertex " + std::to_string(c.vertex) + " is out of range (mesh has " +
                std::to_string(host.num_vertices()) + " vertices)");
    return;
  }
  require(c.triangle >= 0 && c.triangle < host.num_triangles(), MCON_ERROR_INVALID_ARGUMENT,
          "center triangle " + std::to_string(c.triangle) + " is out of range (mesh has " +
              std::to_string(host.num_triangles()) + " triangles)");
  const Vec3& b = c.barycentric;
  require(b.allFinite() && b.minCoeff() >= -1e-9 && std::abs(b.sum() - 1.0) < 1e-6, MCON_ERROR_INVALID_ARGUMENT,
          "center barycentric coordinates must be finite, >= 0 and sum to 1");
}


// 0. Where the center lies on the host.
Vec3 center_point_on_host(const TriMesh& host, const PatchCenter& c) {
  if (c.vertex >= 0) return host.positions[c.vertex];
  const Tri& tri = host.triangles[c.triangle];
  const Vec3 b = c.barycentric / c.barycentric.sum();
  return b[0] * host.positions[tri[0]] + b[1] * host.positions[tri[1]] + b[2] * host.positions[tri[2]];
}

// 1. A bounded region around the center, and geodesic distance on it.
MeshRegion region_around_center(const TriMesh& host, const PatchCenter& c, const Vec3& center_point, double r) {
  std::vector<std::vector<int>> host_vertex_triangles(host.num_vertices());
  for (int t = 0; t < host.num_triangles(); ++t)
    for (int v : host.triangles[t]) host_vertex_triangles[v].push_back(t);
  return mesh_region_around(host, host_vertex_triangles, c.vertex, c.triangle, center_point, kRegionFactor * r);
}

// Local validation (PatchOptions::validate_region): the region's triangles, and the fans of the
// vertices whose every triangle is in it; defects farther out are never read.
// With `repair`, zero-area triangles and pinched vertices are returned instead of refused.
PartDefects validate_region(const TriMesh& host, const MeshRegion& region, bool repair) {
  std::vector<int> whole;
  for (std::size_t v = 0; v < region.vertex_to_host.size(); ++v)
    if (!region.vertex_on_cut[v]) whole.push_back(region.vertex_to_host[v]);
  return validate_mesh_part(host, region.triangle_to_host, whole,
                            "within " + number_text(kRegionFactor) +
                                " radii of the center, the part of the host this patch reads (defects farther out "
                                "are accepted): fix the mesh there, pick another center or radius" +
                                (repair ? "" : ", or ask for the repair (MCON_PATCH_REPAIR_REGION)"),
                            repair);
}

// The repair's region part: zero-area triangles out; the center must survive it.
RegionRepairs repair_region(MeshRegion& region, const PatchCenter& c, const PartDefects& defects) {
  RegionRepairs r;
  if (!defects.zero_area_triangles.empty()) r = remove_zero_area_triangles(region);
  if (!defects.pinched_vertices.empty()) separate_pinched_fans(region, c.vertex, c.triangle);
  require(c.vertex < 0 || region.host_to_vertex[c.vertex] >= 0, MCON_ERROR_DEGENERATE_TRIANGLE,
          "the center vertex " + std::to_string(c.vertex) + " lies only in zero-area triangles: pick another center");
  require(c.vertex >= 0 || std::find(region.triangle_to_host.begin(), region.triangle_to_host.end(), c.triangle) !=
                               region.triangle_to_host.end(),
          MCON_ERROR_DEGENERATE_TRIANGLE,
          "the center triangle " + std::to_string(c.triangle) + " has zero area: pick another center");
  return r;
}

// Host vertices that joined separate fans and are vertices of the patch (stage 6 split them).
int pinched_in_patch(const Patch& patch, const std::vector<int>& pinched) {
  std::vector<int> sorted = pinched;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> found;
  for (const HostPoint& h : patch.host_vertex)
    if (h.v0 >= 0 && h.v0 == h.v1 && std::binary_search(sorted.begin(), sorted.end(), h.v0)) found.push_back(h.v0);
  std::sort(found.begin(), found.end());
  return static_cast<int>(std::unique(found.begin(), found.end()) - found.begin());
}

// Of the triangles of `m` that lie in host triangle `host_t` (`host_of` per triangle), the piece
// that holds `point` best (largest smallest barycentric weight of its projection), with the point's
// weights in it, clamped to >= 0. Used where a host triangle was cut into pieces: by the patch cut
// (stage 8) and by the repair's split of a cap's neighbour (the center's region triangle).
std::pair<int, Vec3> piece_holding(const TriMesh& m, const std::vector<int>& host_of, int host_t, const Vec3& point) {
  double best = -1e300;
  std::pair<int, Vec3> out{-1, Vec3::Zero()};
  for (int t = 0; t < m.num_triangles(); ++t) {
    if (host_of[t] != host_t) continue;
    const Tri& tri = m.triangles[t];
    const Vec3 a = m.positions[tri[0]], e1 = m.positions[tri[1]] - a, e2 = m.positions[tri[2]] - a;
    const Vec3 p = point - a;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2), p1 = p.dot(e1), p2 = p.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    const double u = (d22 * p1 - d12 * p2) / det, v = (d11 * p2 - d12 * p1) / det;
    const Vec3 b(1 - u - v, u, v);
    if (b.minCoeff() > best) {
      best = b.minCoeff();
      out = {t, b.cwiseMax(0.0) / b.cwiseMax(0.0).sum()};
    }
  }
  return out;
}

// The center's region triangle and weights: the host triangle itself with the caller's weights,
// unless a repair split it (then the piece holding the center point).
std::pair<int, Vec3> center_piece(const MeshRegion& region, const PatchCenter& c, const Vec3& center_point) {
  const auto first = std::find(region.triangle_to_host.begin(), region.triangle_to_host.end(), c.triangle);
  if (std::count(first, region.triangle_to_host.end(), c.triangle) == 1)
    return {static_cast<int>(first - region.triangle_to_host.begin()), c.barycentric / c.barycentric.sum()};
  return piece_holding(region.mesh, region.triangle_to_host, c.triangle, center_point);
}

Eigen::VectorXd distance_from_center(const MeshRegion& region, const PatchCenter& c, const Vec3& center_point) {
  HeatGeodesics heat(region.mesh);
  if (c.vertex >= 0) return heat.from_vertices({region.host_to_vertex[c.vertex]});
  const auto [piece, weights] = center_piece(region, c, center_point);
  return heat.from_point(piece, weights);
}

// The region cut by the geodesic circle d = r: what stages 3 to 5 read.
struct IsoRegion {
  const MeshRegion& region;
  MeshTopology topo;
  Eigen::VectorXd d;       // geodesic distance from the center, snapped (stage 2)
  std::vector<Side> side;  // each vertex's side of the circle
  double r = 0;
  int center_vertex = -1;  // the center's region vertex, -1 if it lies inside a triangle

  bool has(int t, Side s) const {
    for (int v : region.mesh.triangles[t])
      if (side[v] == s) return true;
    return false;
  }
  bool edge_has(int e, Side s) const { return side[topo.edges[e][0]] == s || side[topo.edges[e][1]] == s; }
};

// 2. Snap iso-line crossings that fall close to a vertex onto that vertex (no slivers).
IsoRegion cut_at_radius(const MeshRegion& region, Eigen::VectorXd d, const PatchCenter& c, double r,
                        double snap_fraction) {
  const TriMesh& rm = region.mesh;
  IsoRegion iso{region, build_topology(rm), {}, {}, r, -1};
  std::vector<char> snap(rm.num_vertices(), 0);
  for (const auto& e : iso.topo.edges) {
    const double da = d[e[0]], db = d[e[1]];
    if ((da < r) == (db < r) || !std::isfinite(da) || !std::isfinite(db)) continue;
    const double t = (r - da) / (db - da);
    if (t < snap_fraction) snap[e[0]] = 1;
    if (t > 1.0 - snap_fraction) snap[e[1]] = 1;
  }
  for (int v = 0; v < rm.num_vertices(); ++v)
    if (snap[v]) d[v] = r;
  iso.side.resize(rm.num_vertices());
  for (int v = 0; v < rm.num_vertices(); ++v)
    iso.side[v] = d[v] < r ? Side::kIn : (d[v] == r ? Side::kOn : Side::kOut);
  iso.d = std::move(d);
  iso.center_vertex = c.vertex >= 0 ? region.host_to_vertex[c.vertex] : -1;
  require(iso.center_vertex < 0 || iso.side[iso.center_vertex] == Side::kIn, MCON_ERROR_INVALID_ARGUMENT,
          "radius " + number_text(r) + " is too small for the mesh resolution at the center");
  return iso;
}

// A radius beyond every distance makes the "disk" the whole part of the mesh, bounded by the
// mesh's own border rather than the geodesic circle, and its normalization meaningless. (A whole
// closed surface is reported as NOT_A_DISK before this.)
void require_radius_within_reach(const IsoRegion& iso) {
  double reach = 0;
  for (int v = 0; v < iso.region.mesh.num_vertices(); ++v)
    if (std::isfinite(iso.d[v])) reach = std::max(reach, iso.d[v]);
  require(reach >= iso.r, MCON_ERROR_INVALID_ARGUMENT,
          "radius " + number_text(iso.r) + " is larger than the whole part of the mesh around the center (its "
          "farthest point is at geodesic distance " + number_text(reach) + "); use a radius below that");
}

// 3. The disk's triangles: those with an inside corner, connected to the center through
//    edges that are (partly) inside.
std::vector<char> disk_triangles(const IsoRegion& iso, const PatchCenter& c) {
  const TriMesh& rm = iso.region.mesh;
  const MeshTopology& rt = iso.topo;
  const int nt = rm.num_triangles();
  std::vector<char> kept(nt, 0);
  std::vector<int> stack;
  for (int t = 0; t < nt; ++t) {
    const bool seed = c.vertex >= 0
                          ? std::find(rm.triangles[t].begin(), rm.triangles[t].end(), iso.center_vertex) !=
                                rm.triangles[t].end()
                          : iso.region.triangle_to_host[t] == c.triangle;
    if (seed && iso.has(t, Side::kIn)) {
      kept[t] = 1;
      stack.push_back(t);
    }
  }
  require(!stack.empty(), MCON_ERROR_INVALID_ARGUMENT,
          "radius " + number_text(iso.r) + " is too small for the mesh resolution at the center");
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    for (int e : rt.triangle_edges[t]) {
      if (iso.edge_has(e, Side::kOut) && !iso.edge_has(e, Side::kIn)) continue;  // touches the disk in a point
      for (int u : rt.edge_triangles[e])
        if (u >= 0 && !kept[u] && iso.has(u, Side::kIn)) {
          kept[u] = 1;
          stack.push_back(u);
        }
    }
  }
  return kept;
}

// One connected part of what lies outside the disk.
struct PartInfo {
  bool touches_cut = false;  // reaches beyond the region, or the host's own boundary
  double area = 0;
  Vec3 weighted_centroid = Vec3::Zero();
  std::vector<int> triangles;  // whole triangles of the part
};

// The connected parts of the complement of the kept triangles (plus the kept triangles that
// reach outside); `part` gets each triangle's part, -1 for none.
std::vector<PartInfo> flood_outside_parts(const IsoRegion& iso, const std::vector<char>& kept, std::vector<int>& part) {
  const TriMesh& rm = iso.region.mesh;
  const MeshTopology& rt = iso.topo;
  const int nt = rm.num_triangles();
  part.assign(nt, -1);
  std::vector<char> in_complement(nt, 0);
  for (int t = 0; t < nt; ++t) in_complement[t] = !kept[t] || iso.has(t, Side::kOut);
  std::vector<PartInfo> parts;
  std::vector<int> stack;
  for (int seed = 0; seed < nt; ++seed) {
    if (!in_complement[seed] || part[seed] >= 0) continue;
    const int id = static_cast<int>(parts.size());
    parts.emplace_back();
    part[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      PartInfo& info = parts[id];
      if (!kept[t]) {
        info.area += triangle_area(rm, t);
        info.triangles.push_back(t);
        const Tri& tt = rm.triangles[t];
        info.weighted_centroid += triangle_area(rm, t) *
                                  (rm.positions[tt[0]] + rm.positions[tt[1]] + rm.positions[tt[2]]) / 3.0;
      }
      for (int v : rm.triangles[t])
        info.touches_cut |= iso.region.vertex_on_cut[v] != 0 || iso.region.vertex_on_host_boundary[v] != 0;
      for (int e : rt.triangle_edges[t])
        for (int u : rt.edge_triangles[e]) {
          if (u < 0 || u == t || !in_complement[u] || part[u] >= 0) continue;
          if (kept[t] && kept[u] && !iso.edge_has(e, Side::kOut)) continue;  // an edge inside the disk
          part[u] = id;
          stack.push_back(u);
        }
    }
  }
  return parts;
}

// How much a part's outward normals face its own centroid, scale-free (see kMinPocketConcavity).
double part_concavity(const TriMesh& rm, const PartInfo& p) {
  double concavity = 0;
  if (p.area > 0) {
    const Vec3 c0 = p.weighted_centroid / p.area;
    for (int t : p.triangles) {
      const Tri& tt = rm.triangles[t];
      const Vec3 x = (rm.positions[tt[0]] + rm.positions[tt[1]] + rm.positions[tt[2]]) / 3.0;
      concavity += triangle_area(rm, t) * triangle_normal(rm, t).dot(c0 - x);
    }
    concavity /= p.area * std::sqrt(p.area);  // scale-free
  }
  return concavity;
}

// Per region triangle its outside part (-1: none), and per part whether it is a pocket.
struct OutsideParts {
  std::vector<int> part;
  std::vector<char> is_pocket;
};

// 4. What lies outside the disk, in connected parts. Exactly one part reaches beyond the
//    region (or, on a closed surface seen whole, is the largest); the others are enclosed
//    pockets. A second big outer part means the disk wrapped around into an annulus.
OutsideParts outside_parts(const IsoRegion& iso, const std::vector<char>& kept) {
  OutsideParts out;
  const std::vector<PartInfo> parts = flood_outside_parts(iso, kept, out.part);
  out.is_pocket.assign(parts.size(), 0);
  int largest = -1;
  for (int i = 0; i < static_cast<int>(parts.size()); ++i)
    if (largest < 0 || parts[i].area > parts[largest].area) largest = i;
  int outer_parts = 0;
  for (int i = 0; i < static_cast<int>(parts.size()); ++i) {
    const PartInfo& p = parts[i];
    const bool enclosed = !p.touches_cut && !(iso.region.is_whole_component && i == largest);
    const double concavity = part_concavity(iso.region.mesh, p);
    out.is_pocket[i] = enclosed && concavity > kMinPocketConcavity;
    if (!out.is_pocket[i]) ++outer_parts;
  }
  if (outer_parts > 1)
    fail(MCON_ERROR_NOT_A_DISK,
         "not a disk: the geodesic disk wraps around into an annulus (its outside falls apart into " +
             std::to_string(outer_parts) + " parts that are not cavities, e.g. around a limb); use a smaller radius");
  return out;
}

// The patch while it is assembled, and what the later stages need to know about its vertices.
struct PatchDraft {
  Patch patch;
  std::vector<int> vertex_of_region;  // per region vertex: its patch vertex, -1 if none yet
  std::unordered_map<std::uint64_t, int> vertex_of_crossing;  // per cut region edge: its patch vertex
  std::vector<char> is_cut_vertex;    // per patch vertex: it lies on the geodesic circle
};

int region_vertex(PatchDraft& draft, const IsoRegion& iso, int v) {
  if (draft.vertex_of_region[v] < 0) {
    draft.vertex_of_region[v] = draft.patch.mesh.num_vertices();
    draft.patch.mesh.positions.push_back(iso.region.mesh.positions[v]);
    const int hv = iso.region.vertex_to_host[v];
    draft.patch.host_vertex.push_back({hv, hv, 0.0});
    draft.is_cut_vertex.push_back(iso.side[v] == Side::kOn);
  }
  return draft.vertex_of_region[v];
}

int crossing_vertex(PatchDraft& draft, const IsoRegion& iso, int a, int b) {
  const MeshRegion& region = iso.region;
  const Eigen::VectorXd& d = iso.d;
  const auto key = edge_key(a, b);
  auto it = draft.vertex_of_crossing.find(key);
  if (it != draft.vertex_of_crossing.end()) return it->second;
  if (region.vertex_to_host[a] > region.vertex_to_host[b]) std::swap(a, b);  // t from the lower host index
  const double t = (iso.r - d[a]) / (d[b] - d[a]);
  TriMesh& pm = draft.patch.mesh;
  const int id = pm.num_vertices();
  pm.positions.push_back((1 - t) * region.mesh.positions[a] + t * region.mesh.positions[b]);
  draft.patch.host_vertex.push_back({region.vertex_to_host[a], region.vertex_to_host[b], t});
  draft.is_cut_vertex.push_back(1);
  draft.vertex_of_crossing.emplace(key, id);
  return id;
}

// Clip against d <= r (Sutherland-Hodgman on one triangle): 3 or 4 corners.
void add_clipped_triangle(PatchDraft& draft, const IsoRegion& iso, int t) {
  const std::vector<Side>& side = iso.side;
  const Tri& tri = iso.region.mesh.triangles[t];
  const int host_t = iso.region.triangle_to_host[t];
  TriMesh& pm = draft.patch.mesh;
  int poly[4];
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    const int a = tri[k], b = tri[(k + 1) % 3];
    if (side[a] != Side::kOut) poly[count++] = region_vertex(draft, iso, a);
    if ((side[a] == Side::kIn && side[b] == Side::kOut) || (side[a] == Side::kOut && side[b] == Side::kIn))
      poly[count++] = crossing_vertex(draft, iso, a, b);
  }
  if (count == 3) {
    pm.triangles.push_back({poly[0], poly[1], poly[2]});
    draft.patch.host_triangle.push_back(host_t);
  } else if (count == 4) {
    // Split the quad along its shorter diagonal.
    const double d02 = (pm.positions[poly[0]] - pm.positions[poly[2]]).squaredNorm();
    const double d13 = (pm.positions[poly[1]] - pm.positions[poly[3]]).squaredNorm();
    if (d02 <= d13) {
      pm.triangles.push_back({poly[0], poly[1], poly[2]});
      pm.triangles.push_back({poly[0], poly[2], poly[3]});
    } else {
      pm.triangles.push_back({poly[0], poly[1], poly[3]});
      pm.triangles.push_back({poly[1], poly[2], poly[3]});
    }
    draft.patch.host_triangle.push_back(host_t);
    draft.patch.host_triangle.push_back(host_t);
  }
}

// 5. Assemble: whole triangles inside (and pockets, if filling), clipped triangles on the cut.
PatchDraft assemble_patch(const IsoRegion& iso, const std::vector<char>& kept, const OutsideParts& outside,
                          bool fill_holes) {
  const TriMesh& rm = iso.region.mesh;
  PatchDraft draft;
  draft.vertex_of_region.assign(rm.num_vertices(), -1);
  for (int t = 0; t < rm.num_triangles(); ++t) {
    const bool pocket = outside.part[t] >= 0 && outside.is_pocket[outside.part[t]] && fill_holes;
    if (!kept[t] && !pocket) continue;
    const Tri& tri = rm.triangles[t];
    if (pocket || !iso.has(t, Side::kOut)) {
      draft.patch.mesh.triangles.push_back(
          {region_vertex(draft, iso, tri[0]), region_vertex(draft, iso, tri[1]), region_vertex(draft, iso, tri[2])});
      draft.patch.host_triangle.push_back(iso.region.triangle_to_host[t]);
      continue;
    }
    add_clipped_triangle(draft, iso, t);
  }
  return draft;
}

// 6. Pinch points become separate vertices, then the boundary loops decide.
MeshTopology split_pinch_points(PatchDraft& draft) {
  Patch& patch = draft.patch;
  const std::vector<int> origin = split_nonmanifold_vertices(patch.mesh);
  for (std::size_t v = patch.host_vertex.size(); v < origin.size(); ++v) {
    patch.host_vertex.push_back(patch.host_vertex[origin[v]]);
    draft.is_cut_vertex.push_back(draft.is_cut_vertex[origin[v]]);
  }
  return build_topology(patch.mesh);
}

// The boundary loops other than the outer one (on the geodesic circle, else the longest): the
// holes to fill. Throws NOT_A_DISK for an annulus, a whole closed surface or unfilled holes.
std::vector<int> holes_inside(const MeshTopology& pt, const std::vector<char>& is_cut_vertex, bool fill_holes) {
  std::vector<int> cut_loops, other_loops;
  for (int i = 0; i < static_cast<int>(pt.boundary_loops.size()); ++i) {
    bool on_cut = false;
    for (int v : pt.boundary_loops[i]) on_cut |= is_cut_vertex[v] != 0;
    (on_cut ? cut_loops : other_loops).push_back(i);
  }
  if (pt.boundary_loops.empty())
    fail(MCON_ERROR_NOT_A_DISK, "not a disk: the geodesic disk covers a whole closed surface; use a smaller radius");
  if (cut_loops.size() > 1)
    fail(MCON_ERROR_NOT_A_DISK,
         "not a disk: " + std::to_string(cut_loops.size()) + " boundary loops on the geodesic circle" +
             (fill_holes ? std::string(" (the disk wraps around into an annulus)")
                         : std::string(" (enclosed pockets: enable hole filling)")));
  int outer = cut_loops.empty() ? -1 : cut_loops[0];
  if (outer < 0) {  // the disk reaches the host's own boundary all round: take the longest loop
    for (int i : other_loops)
      if (outer < 0 || pt.boundary_loops[i].size() > pt.boundary_loops[outer].size()) outer = i;
  }
  std::vector<int> holes;
  for (int i = 0; i < static_cast<int>(pt.boundary_loops.size()); ++i)
    if (i != outer) holes.push_back(i);
  if (!holes.empty() && !fill_holes)
    fail(MCON_ERROR_NOT_A_DISK, "not a disk: " + std::to_string(holes.size()) +
                                    " holes of the host mesh inside the geodesic disk (enable hole filling)");
  return holes;
}

// 7. Cap each inner hole with a fan around its centroid, flagged as filled (host triangle -1).
void cap_holes(PatchDraft& draft, const MeshTopology& pt, const std::vector<int>& holes) {
  Patch& patch = draft.patch;
  TriMesh& pm = patch.mesh;
  for (int h : holes) {
    const std::vector<int>& loop = pt.boundary_loops[h];
    const int m = static_cast<int>(loop.size());
    if (m == 3) {
      pm.triangles.push_back({loop[2], loop[1], loop[0]});
      patch.host_triangle.push_back(-1);
      continue;
    }
    Vec3 centroid = Vec3::Zero();
    for (int v : loop) centroid += pm.positions[v];
    centroid /= m;
    const int cv = pm.num_vertices();
    pm.positions.push_back(centroid);
    patch.host_vertex.push_back({-1, -1, 0.0});
    draft.is_cut_vertex.push_back(0);
    for (int i = 0; i < m; ++i) {  // the loop has the mesh on its left: the cap runs the other way
      pm.triangles.push_back({loop[(i + 1) % m], loop[i], cv});
      patch.host_triangle.push_back(-1);
    }
  }
}

// The capped patch must be one disk (one piece, one boundary loop, Euler characteristic 1);
// its boundary loop is the patch's.
void require_one_disk(Patch& patch, const MeshTopology& pt) {
  const TriMesh& pm = patch.mesh;
  const int chi = euler_characteristic(pm, pt);
  {
    std::vector<int> comp;
    const int components = triangle_components(pm, pt, comp);
    require(components == 1, MCON_ERROR_NOT_A_DISK,
            "not a disk: " + std::to_string(components) + " separate pieces");
  }
  require(pt.boundary_loops.size() == 1 && chi == 1, MCON_ERROR_NOT_A_DISK,
          "not a disk: the geodesic disk has a handle (Euler characteristic " + std::to_string(chi) + ", " +
              std::to_string(pt.boundary_loops.size()) + " boundary loops); use a smaller radius");
  validate_mesh(pm);
  patch.boundary_loop = pt.boundary_loops[0];
}

// 8. Where the center lies in the patch: at patch vertex pv ...
void center_at_vertex(Patch& patch, int pv) {
  const TriMesh& pm = patch.mesh;
  for (int t = 0; t < pm.num_triangles() && patch.center.triangle < 0; ++t)
    for (int k = 0; k < 3; ++k)
      if (pm.triangles[t][k] == pv) {
        patch.center.triangle = t;
        patch.center.barycentric = Vec3::Zero();
        patch.center.barycentric[k] = 1.0;
      }
}

// ... or in the piece of host triangle `host_t` that holds it best (largest smallest weight).
void center_in_triangle(Patch& patch, int host_t, const Vec3& center_point) {
  const auto [t, weights] = piece_holding(patch.mesh, patch.host_triangle, host_t, center_point);
  if (t < 0) return;
  patch.center.triangle = t;
  patch.center.barycentric = weights;
}

// 9. Normalize to geodesic radius 1 around the center, ...
void normalize_to_unit_radius(Patch& patch, const Vec3& center_point, double r) {
  patch.center_position = center_point;
  patch.radius = r;
  for (Vec3& p : patch.mesh.positions) p = (p - center_point) / r;
}

// ... parametrize, measure.
void parametrize_and_measure(Patch& patch) {
  const TriMesh& pm = patch.mesh;
  patch.uv = disk_parametrization(pm, patch.boundary_loop);
  patch.param_flipped_triangles = count_flipped_triangles(pm, patch.uv);
  {
    HeatGeodesics heat(pm);
    const Eigen::VectorXd pd = heat.from_point(patch.center.triangle, patch.center.barycentric);
    patch.max_geodesic_distance = pd.maxCoeff();
  }
}

}  // namespace

int Patch::filled_triangles() const {
  return static_cast<int>(std::count(host_triangle.begin(), host_triangle.end(), -1));
}

Patch extract_geodesic_disk(const TriMesh& host, const PatchOptions& options) {
  check_options(host, options);
  auto report = [&](double fraction) {
    if (options.progress && !options.progress(fraction))
      fail(MCON_ERROR_CANCELLED, "patch extraction cancelled by the progress callback");
  };
  report(0.0);
  const double r = options.radius;
  const PatchCenter& c = options.center;
  const Vec3 center_point = center_point_on_host(host, c);

  MeshRegion region = region_around_center(host, c, center_point, r);  // 1.
  PartDefects defects;
  RegionRepairs repairs;
  const bool repair = options.validate_region && options.repair_region;
  if (options.validate_region) defects = validate_region(host, region, repair);
  if (repair && !(defects.zero_area_triangles.empty() && defects.pinched_vertices.empty()))
    repairs = repair_region(region, c, defects);
  report(0.1);
  Eigen::VectorXd d = distance_from_center(region, c, center_point);
  report(0.4);
  const IsoRegion iso = cut_at_radius(region, std::move(d), c, r, options.snap_fraction);  // 2.
  const std::vector<char> kept = disk_triangles(iso, c);                                  // 3.
  const OutsideParts outside = outside_parts(iso, kept);                                  // 4.
  report(0.55);

  PatchDraft draft = assemble_patch(iso, kept, outside, options.fill_holes);  // 5.
  MeshTopology pt = split_pinch_points(draft);                                // 6.
  const std::vector<int> holes = holes_inside(pt, draft.is_cut_vertex, options.fill_holes);
  cap_holes(draft, pt, holes);  // 7.
  if (!holes.empty()) pt = build_topology(draft.patch.mesh);
  Patch& patch = draft.patch;
  require_one_disk(patch, pt);
  require_radius_within_reach(iso);
  report(0.7);

  if (c.vertex >= 0)  // 8.
    center_at_vertex(patch, draft.vertex_of_region[iso.center_vertex]);
  else
    center_in_triangle(patch, c.triangle, center_point);
  require(patch.center.triangle >= 0, MCON_ERROR_UNKNOWN, "the center was lost while cutting the patch");

  patch.repairs = {repairs.zero_area_triangles_removed, repairs.triangles_split, repairs.vertices_merged,
                   pinched_in_patch(patch, defects.pinched_vertices)};
  normalize_to_unit_radius(patch, center_point, r);  // 9.
  report(0.8);
  parametrize_and_measure(patch);
  report(1.0);
  return std::move(draft.patch);
}

}  // namespace mcon
