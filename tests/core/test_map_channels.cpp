#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "map/map_channels.h"
#include "map/patch_map.h"
#include "patch/geodesic_disk_patch.h"
#include "test_meshes.h"

using namespace mcon;

namespace {

// A bumpy, asymmetric surface patch and its mirror image (x -> -x, triangles reversed so the
// normals stay outward): a reflection of the same geometry.
Patch bumpy_patch(bool mirrored) {
  TriMesh m = test_meshes::make_bumpy_grid(24);
  for (Vec3& p : m.positions) p.z() += 0.15 * p.x() * p.y() + 0.1 * p.x();
  if (mirrored) {
    for (Vec3& p : m.positions) p.x() = -p.x();
    for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  }
  PatchOptions o;
  o.center.vertex = 12 * 25 + 12;
  o.radius = 0.7;
  return extract_geodesic_disk(m, o);
}

std::vector<double> sorted(const Eigen::VectorXd& v) {
  std::vector<double> out(v.data(), v.data() + v.size());
  std::sort(out.begin(), out.end());
  return out;
}

const MapChannel& channel(const std::string& name) {
  for (const MapChannel& c : map_channels())
    if (name == c.name) return c;
  throw std::runtime_error("no channel " + name);
}

}  // namespace

TEST(MapChannels, NamesAreUniqueAndOnlyChiralityIsChiral) {
  std::set<std::string> names;
  for (const MapChannel& c : map_channels()) {
    EXPECT_TRUE(names.insert(c.name).second) << c.name;
    EXPECT_EQ(c.chiral, std::string(c.name) == "chirality") << c.name;
  }
  EXPECT_EQ(std::string(map_channels().front().name), "mean_curvature");
  EXPECT_FALSE(map_channels().front().center_based);  // the thesis' channel works without a center
  PatchMapOptions o;
  o.chord_weight = 0.25;
  EXPECT_EQ(channel("arc_minus_chord").weight(o), 0.25);
  EXPECT_EQ(channel("mean_curvature").weight(o), 1.0);
}

// A mirror image keeps every channel but the chiral one, which changes sign: the property the
// map's reflection handling (SurfaceMapOptions::chiral_columns) relies on.
TEST(MapChannels, ChiralityChangesSignUnderReflectionAndTheOthersDoNot) {
  const Patch a = bumpy_patch(false), b = bumpy_patch(true);
  ASSERT_EQ(a.mesh.num_vertices(), b.mesh.num_vertices());
  const PatchCenterFrame fa = patch_center_frame(a), fb = patch_center_frame(b);
  for (const MapChannel& c : map_channels()) {
    const Eigen::VectorXd va = c.compute(fa), vb = c.compute(fb);
    ASSERT_EQ(va.size(), a.mesh.num_vertices()) << c.name;
    const double scale = va.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 1e-6) << c.name << " is constant on an asymmetric patch";
    // The cut may number the patch vertices differently: compare the sorted values.
    const std::vector<double> sa = sorted(va), same = sorted(vb), flipped = sorted(-vb);
    const std::vector<double>& expected = c.chiral ? flipped : same;
    double err = 0, chiral_gap = 0;
    for (std::size_t i = 0; i < sa.size(); ++i) {
      err = std::max(err, std::abs(sa[i] - expected[i]));
      chiral_gap = std::max(chiral_gap, std::abs(sa[i] - same[i]));
    }
    EXPECT_LT(err, 1e-6 * scale) << c.name;
    if (c.chiral) {
      EXPECT_GT(chiral_gap, 0.05 * scale);  // and it is not mirror-symmetric to begin with
    }
  }
}
