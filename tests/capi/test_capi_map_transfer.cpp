// Transfers through a map between two nose patches of the MakeHuman sample body: every field
// kind, labels, points, polylines (re-traced on the target), the guide-aligned cross field and
// its `.rosy` file.
#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "map_test_util.h"

using namespace map_test;

namespace {

struct MapSetup {
  ContextPtr ctx;
  MeshPtr mesh;
  PatchPtr source, target;
  MapPtr map, backward;
  PatchArrays s, t;
};

// One map per process (each test runs in its own process under ctest, so this is per test).
MapSetup& setup() {
  static MapSetup* st = [] {
    auto* x = new MapSetup;
    x->ctx = make_context();
    x->mesh = make_mesh(x->ctx.get(), body().arrays);
    x->source = extract(x->mesh.get(), 297, 0.45);
    x->target = extract(x->mesh.get(), 297, 0.55);
    x->map = compute(x->source.get(), x->target.get(), fast_options());
    x->backward = compute(x->target.get(), x->source.get(), fast_options());
    x->s = arrays_of_patch(x->source.get());
    x->t = arrays_of_patch(x->target.get());
    return x;
  }();
  return *st;
}

std::vector<uint8_t> mask_of(mcon_map map, size_t n) {
  std::vector<uint8_t> m(n);
  EXPECT_EQ(mcon_map_get_outside_mask(map, m.data(), n), MCON_OK);
  return m;
}

// Angle-weighted vertex normals in host units (the same as normalized: a similarity).
std::vector<std::array<double, 3>> normals_of(const PatchArrays& a) {
  std::vector<std::array<double, 3>> n(a.nv(), {0, 0, 0});
  for (size_t f = 0; f < a.nt(); ++f) {
    const double* p[3];
    for (int k = 0; k < 3; ++k) p[k] = &a.xyz[3 * a.tri[3 * f + k]];
    double e1[3], e2[3], c[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = p[1][k] - p[0][k];
      e2[k] = p[2][k] - p[0][k];
    }
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int corner = 0; corner < 3; ++corner) {
      const double* o = p[corner];
      const double* q1 = p[(corner + 1) % 3];
      const double* q2 = p[(corner + 2) % 3];
      double a1[3], a2[3];
      for (int k = 0; k < 3; ++k) {
        a1[k] = q1[k] - o[k];
        a2[k] = q2[k] - o[k];
      }
      const double dot = a1[0] * a2[0] + a1[1] * a2[1] + a1[2] * a2[2];
      const double cr[3] = {a1[1] * a2[2] - a1[2] * a2[1], a1[2] * a2[0] - a1[0] * a2[2], a1[0] * a2[1] - a1[1] * a2[0]};
      const double angle = std::atan2(std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), dot);
      for (int k = 0; k < 3; ++k) n[a.tri[3 * f + corner]][k] += angle * c[k] / len;
    }
  }
  for (auto& x : n) {
    const double len = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (double& c : x) c /= len;
  }
  return n;
}

// Barycentric weights of host point x in the plane of patch triangle f, and its distance from it.
std::array<double, 3> bary_in(const PatchArrays& a, uint32_t f, const double* x, double& off) {
  double p[3][3];
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) p[c][k] = a.info.center[k] + a.info.radius * a.xyz[3 * a.tri[3 * f + c] + k];
  double e1[3], e2[3], d[3];
  for (int k = 0; k < 3; ++k) {
    e1[k] = p[1][k] - p[0][k];
    e2[k] = p[2][k] - p[0][k];
    d[k] = x[k] - p[0][k];
  }
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), p1 = dot(d, e1), p2 = dot(d, e2);
  const double det = d11 * d22 - d12 * d12;
  const double u = (d22 * p1 - d12 * p2) / det, v = (d11 * p2 - d12 * p1) / det;
  double r[3];
  for (int k = 0; k < 3; ++k) r[k] = d[k] - u * e1[k] - v * e2[k];
  off = std::sqrt(dot(r, r));
  return {1 - u - v, u, v};
}

struct Traced {
  std::vector<uint32_t> sizes, input, tri;
  std::vector<uint8_t> closed;
  std::vector<double> bary, xyz;
};

Traced read_set(mcon_polyline_set set) {
  Traced r;
  size_t np = 0, n = 0;
  EXPECT_EQ(mcon_polyline_set_get_counts(set, &np, &n), MCON_OK);
  r.sizes.resize(np);
  r.input.resize(np);
  r.closed.resize(np);
  EXPECT_EQ(mcon_polyline_set_get_polylines(set, r.sizes.data(), r.closed.data(), r.input.data(), np), MCON_OK);
  r.tri.resize(n);
  r.bary.resize(3 * n);
  r.xyz.resize(3 * n);
  EXPECT_EQ(mcon_polyline_set_get_points(set, r.tri.data(), r.bary.data(), r.xyz.data(), n), MCON_OK);
  size_t sum = 0;
  for (uint32_t s : r.sizes) sum += s;
  EXPECT_EQ(sum, n);
  return r;
}

// Every segment inside the triangle of its first point; every point on the target surface.
void expect_on_target(const Traced& r, const PatchArrays& t) {
  size_t first = 0;
  for (size_t p = 0; p < r.sizes.size(); ++p) {
    const size_t n = r.sizes[p];
    ASSERT_GE(n, 2u);
    for (size_t i = 0; i < n; ++i) {
      const size_t a = first + i;
      ASSERT_LT(r.tri[a], t.nt());
      double x[3], off = 0;
      point_xyz(t, r.tri[a], &r.bary[3 * a], x);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], r.xyz[3 * a + k], 1e-9);
      const auto b = bary_in(t, r.tri[a], &r.xyz[3 * a], off);
      EXPECT_LE(off, 1e-9);
      EXPECT_GE(std::min({b[0], b[1], b[2]}), -1e-7);
      if (i + 1 == n && !r.closed[p]) continue;
      const size_t next = first + (i + 1) % n;
      const auto bn = bary_in(t, r.tri[a], &r.xyz[3 * next], off);
      EXPECT_LE(off, 1e-8) << "polyline " << p << " segment " << i;
      EXPECT_GE(std::min({bn[0], bn[1], bn[2]}), -1e-6) << "polyline " << p << " segment " << i;
    }
    first += n;
  }
}

// Points of a circle of radius r in a patch's uv disk (as surface points).
void circle_points(const PatchArrays& a, double r, int n, std::vector<uint32_t>& tri, std::vector<double>& bary) {
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * 3.141592653589793 * i / n;
    uint32_t t = 0;
    double b[3];
    ASSERT_TRUE(locate_uv(a, r * std::cos(angle), r * std::sin(angle), t, b));
    tri.push_back(t);
    bary.insert(bary.end(), b, b + 3);
  }
}

}  // namespace

TEST(CapiMapTransfer, InterpolatedKindsScalarVectorUv) {
  MapSetup& x = setup();
  const std::vector<uint8_t> mask = mask_of(x.map.get(), x.t.nv());
  // scalar, 2 channels: constants are reproduced exactly.
  std::vector<double> scalar(2 * x.s.nv());
  for (size_t v = 0; v < x.s.nv(); ++v) {
    scalar[2 * v] = 3.5;
    scalar[2 * v + 1] = -1.25;
  }
  std::vector<double> out(2 * x.t.nv(), 9);
  ASSERT_EQ(mcon_map_transfer_field(x.map.get(), MCON_FIELD_SCALAR, 2, scalar.data(), scalar.size(), out.data(),
                                    out.size()),
            MCON_OK)
      << last_message();
  for (size_t w = 0; w < x.t.nv(); ++w) {
    EXPECT_NEAR(out[2 * w], mask[w] ? 0.0 : 3.5, 1e-12);
    EXPECT_NEAR(out[2 * w + 1], mask[w] ? 0.0 : -1.25, 1e-12);
  }
  // uv: the source's own disk parametrization lands inside the unit disk.
  std::vector<double> uv(2 * x.t.nv());
  ASSERT_EQ(mcon_map_transfer_field(x.map.get(), MCON_FIELD_UV, 2, x.s.uv.data(), x.s.uv.size(), uv.data(), uv.size()),
            MCON_OK);
  for (size_t w = 0; w < x.t.nv(); ++w) EXPECT_LE(std::hypot(uv[2 * w], uv[2 * w + 1]), 1.0 + 1e-9);
  // vector3: the source's host positions. Both patches are cut around the same body vertex, so a
  // good map sends each target vertex near its own position on the body.
  std::vector<double> host(3 * x.s.nv());
  for (size_t v = 0; v < x.s.nv(); ++v)
    for (int k = 0; k < 3; ++k) host[3 * v + k] = x.s.info.center[k] + x.s.info.radius * x.s.xyz[3 * v + k];
  std::vector<double> mapped(3 * x.t.nv());
  ASSERT_EQ(mcon_map_transfer_field(x.map.get(), MCON_FIELD_VECTOR3, 3, host.data(), host.size(), mapped.data(),
                                    mapped.size()),
            MCON_OK);
  double sum = 0;
  size_t inside = 0;
  for (size_t w = 0; w < x.t.nv(); ++w) {
    if (mask[w]) continue;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double truth = x.t.info.center[k] + x.t.info.radius * x.t.xyz[3 * w + k];
      d2 += (mapped[3 * w + k] - truth) * (mapped[3 * w + k] - truth);
    }
    sum += std::sqrt(d2);
    ++inside;
  }
  ASSERT_GT(inside, 0u);
  const double mean = sum / static_cast<double>(inside);
  std::printf("mean distance of mapped body positions: %.4f (target radius %.2f)\n", mean, x.t.info.radius);
  EXPECT_LT(mean, 0.15 * x.t.info.radius);
}

TEST(CapiMapTransfer, TangentVectorsArePushedIntoTheTargetsTangentPlanes) {
  MapSetup& x = setup();
  const auto ns = normals_of(x.s), nt = normals_of(x.t);
  std::vector<double> tangent(3 * x.s.nv());
  double max_len = 0;
  for (size_t v = 0; v < x.s.nv(); ++v) {
    const double a[3] = {1, 0.2, 0};
    const double d = a[0] * ns[v][0] + a[1] * ns[v][1] + a[2] * ns[v][2];
    double len = 0;
    for (int k = 0; k < 3; ++k) {
      tangent[3 * v + k] = a[k] - d * ns[v][k];
      len += tangent[3 * v + k] * tangent[3 * v + k];
    }
    max_len = std::max(max_len, std::sqrt(len));
  }
  std::vector<double> out(3 * x.t.nv());
  ASSERT_EQ(mcon_map_transfer_field(x.map.get(), MCON_FIELD_TANGENT_VECTOR, 3, tangent.data(), tangent.size(),
                                    out.data(), out.size()),
            MCON_OK)
      << last_message();
  const std::vector<uint8_t> mask = mask_of(x.map.get(), x.t.nv());
  size_t nonzero = 0;
  for (size_t w = 0; w < x.t.nv(); ++w) {
    const double* u = &out[3 * w];
    const double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (mask[w]) {
      EXPECT_EQ(len, 0.0);
      continue;
    }
    EXPECT_LE(len, max_len + 1e-9);  // the source's length, not the map's stretch
    if (len > 0) {
      ++nonzero;
      EXPECT_LE(std::abs(u[0] * nt[w][0] + u[1] * nt[w][1] + u[2] * nt[w][2]) / len, 1e-9) << w;
    }
  }
  EXPECT_GT(nonzero, x.t.nv() / 3);
}

TEST(CapiMapTransfer, LabelsComeFromTheDominantCornerOnly) {
  MapSetup& x = setup();
  std::vector<int32_t> labels(2 * x.s.nv());
  for (size_t v = 0; v < x.s.nv(); ++v) {
    labels[2 * v] = static_cast<int32_t>(v);
    labels[2 * v + 1] = -static_cast<int32_t>(v) - 1;
  }
  std::vector<int32_t> out(2 * x.t.nv());
  ASSERT_EQ(mcon_map_transfer_labels(x.map.get(), 2, labels.data(), labels.size(), -777, out.data(), out.size()),
            MCON_OK)
      << last_message();
  std::vector<int32_t> tri(x.t.nv());
  std::vector<double> bary(3 * x.t.nv());
  ASSERT_EQ(mcon_map_get_correspondences(x.map.get(), MCON_MAP_TARGET_TO_SOURCE, tri.data(), bary.data(), tri.size()),
            MCON_OK);
  for (size_t w = 0; w < x.t.nv(); ++w) {
    if (tri[w] < 0) {
      EXPECT_EQ(out[2 * w], -777);
      EXPECT_EQ(out[2 * w + 1], -777);
      continue;
    }
    int best = 0;
    for (int k = 1; k < 3; ++k)
      if (bary[3 * w + k] > bary[3 * w + best]) best = k;
    EXPECT_EQ(out[2 * w], static_cast<int32_t>(x.s.tri[3 * tri[w] + best]));
    EXPECT_EQ(out[2 * w + 1], -out[2 * w] - 1);  // both channels from the same corner
  }
  // Asking for labels through transfer_field is refused.
  std::vector<double> d(x.s.nv()), o(x.t.nv());
  EXPECT_EQ(mcon_map_transfer_field(x.map.get(), MCON_FIELD_INTEGER_LABEL, 1, d.data(), d.size(), o.data(), o.size()),
            MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CapiMapTransfer, PointsKeepTheirIndexAndTheCenterLandsNearTheCenter) {
  MapSetup& x = setup();
  std::vector<uint32_t> tri = {x.s.info.center_patch_triangle, 0, 5};
  std::vector<double> bary = {x.s.info.center_barycentric[0], x.s.info.center_barycentric[1],
                              x.s.info.center_barycentric[2], 0.2, 0.3, 0.5, 1, 0, 0};
  std::vector<uint32_t> out_tri(3);
  std::vector<double> out_bary(9), out_xyz(9);
  ASSERT_EQ(mcon_map_transfer_points(x.map.get(), tri.data(), bary.data(), 3, out_tri.data(), out_bary.data(),
                                     out_xyz.data(), 3),
            MCON_OK)
      << last_message();
  for (size_t i = 0; i < 3; ++i) {
    if (out_tri[i] == MCON_INVALID_INDEX) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(out_xyz[3 * i + k], 0.0);
      continue;
    }
    ASSERT_LT(out_tri[i], x.t.nt());
    double p[3];
    point_xyz(x.t, out_tri[i], &out_bary[3 * i], p);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], out_xyz[3 * i + k], 1e-9);
  }
  ASSERT_NE(out_tri[0], MCON_INVALID_INDEX);
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += std::pow(out_xyz[k] - x.t.info.center[k], 2);
  std::printf("center -> %.4f from the target's center\n", std::sqrt(d2));
  EXPECT_LT(std::sqrt(d2), 0.2 * x.t.info.radius);
  // Only some outputs asked for.
  std::vector<uint32_t> only(3);
  ASSERT_EQ(mcon_map_transfer_points(x.map.get(), tri.data(), bary.data(), 3, only.data(), nullptr, nullptr, 3), MCON_OK);
  EXPECT_EQ(only, out_tri);
}

TEST(CapiMapTransfer, PolylinesAreRetracedOnTheTarget) {
  MapSetup& x = setup();
  std::vector<uint32_t> tri;
  std::vector<double> bary;
  circle_points(x.s, 0.35, 24, tri, bary);
  circle_points(x.s, 0.7, 40, tri, bary);
  {
    uint32_t t = 0;
    double b[3];
    for (double u : {-0.5, 0.0, 0.5}) {
      ASSERT_TRUE(locate_uv(x.s, u, 0.1, t, b));
      tri.push_back(t);
      bary.insert(bary.end(), b, b + 3);
    }
  }
  const std::vector<uint32_t> sizes = {24, 40, 3};
  const std::vector<uint8_t> closed = {1, 1, 0};
  mcon_polyline_set set = nullptr;
  ASSERT_EQ(mcon_map_transfer_polylines(x.map.get(), tri.data(), bary.data(), tri.size(), sizes.data(), closed.data(),
                                        sizes.size(), &set),
            MCON_OK)
      << last_message();
  const PolylineSetPtr guard(set);
  const Traced r = read_set(set);
  ASSERT_GE(r.sizes.size(), 3u);
  std::set<uint32_t> inputs(r.input.begin(), r.input.end());
  EXPECT_EQ(inputs, (std::set<uint32_t>{0, 1, 2}));
  size_t total = 0;
  for (uint32_t s : r.sizes) total += s;
  EXPECT_GT(total, tri.size());  // split at target edges
  for (size_t p = 0; p < r.sizes.size(); ++p)
    if (r.input[p] == 2) {
      EXPECT_EQ(r.closed[p], 0);
    }
  // The small inner loop stays whole (the source is the smaller cut of the same nose).
  EXPECT_EQ(std::count(r.input.begin(), r.input.end(), 0u), 1);
  for (size_t p = 0; p < r.sizes.size(); ++p)
    if (r.input[p] == 0) {
      EXPECT_EQ(r.closed[p], 1);
    }
  expect_on_target(r, x.t);

  // NULL closed flags = all open.
  mcon_polyline_set open = nullptr;
  ASSERT_EQ(mcon_map_transfer_polylines(x.map.get(), tri.data(), bary.data(), tri.size(), sizes.data(), nullptr,
                                        sizes.size(), &open),
            MCON_OK);
  const PolylineSetPtr guard2(open);
  const Traced ro = read_set(open);
  for (uint8_t c : ro.closed) EXPECT_EQ(c, 0);
  expect_on_target(ro, x.t);
}

TEST(CapiMapTransfer, PartsOutsideTheOverlapAreDropped) {
  // Backward: the larger cut onto the smaller one. A diameter of the larger patch leaves the
  // smaller one at both ends: what remains ends on the smaller patch's boundary.
  MapSetup& x = setup();
  std::vector<uint32_t> tri;
  std::vector<double> bary;
  for (double u = -0.98; u <= 0.981; u += 0.14) {
    uint32_t t = 0;
    double b[3];
    ASSERT_TRUE(locate_uv(x.t, u, 0.02, t, b));
    tri.push_back(t);
    bary.insert(bary.end(), b, b + 3);
  }
  const uint32_t size = static_cast<uint32_t>(tri.size());
  mcon_polyline_set set = nullptr;
  ASSERT_EQ(mcon_map_transfer_polylines(x.backward.get(), tri.data(), bary.data(), tri.size(), &size, nullptr, 1, &set),
            MCON_OK)
      << last_message();
  const PolylineSetPtr guard(set);
  const Traced r = read_set(set);
  expect_on_target(r, x.s);
  // Boundary edges of the smaller patch.
  std::map<std::pair<uint32_t, uint32_t>, int> edge_count;
  for (size_t f = 0; f < x.s.nt(); ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = x.s.tri[3 * f + k], b = x.s.tri[3 * f + (k + 1) % 3];
      edge_count[{std::min(a, b), std::max(a, b)}]++;
    }
  auto on_boundary = [&](size_t i) {
    const uint32_t f = r.tri[i];
    for (int k = 0; k < 3; ++k)
      if (r.bary[3 * i + k] <= 1e-9) {
        const uint32_t a = x.s.tri[3 * f + (k + 1) % 3], b = x.s.tri[3 * f + (k + 2) % 3];
        if (edge_count[{std::min(a, b), std::max(a, b)}] == 1) return true;
      }
    return false;
  };
  uint32_t mapped_outside[2];
  ASSERT_EQ(mcon_map_transfer_points(x.backward.get(), &tri.front(), &bary[0], 1, &mapped_outside[0], nullptr, nullptr, 1),
            MCON_OK);
  ASSERT_EQ(mcon_map_transfer_points(x.backward.get(), &tri.back(), &bary[bary.size() - 3], 1, &mapped_outside[1], nullptr,
                                     nullptr, 1),
            MCON_OK);
  ASSERT_GE(r.sizes.size(), 1u);
  size_t first = 0;
  for (size_t p = 0; p < r.sizes.size(); ++p) {
    EXPECT_EQ(r.input[p], 0u);
    EXPECT_EQ(r.closed[p], 0);
    // A piece starts on the boundary unless it starts at the input's first point (inside).
    if (p > 0 || mapped_outside[0] == MCON_INVALID_INDEX) {
      EXPECT_TRUE(on_boundary(first)) << p;
    }
    if (p + 1 < r.sizes.size() || mapped_outside[1] == MCON_INVALID_INDEX) {
      EXPECT_TRUE(on_boundary(first + r.sizes[p] - 1)) << p;
    }
    first += r.sizes[p];
  }
  EXPECT_TRUE(mapped_outside[0] == MCON_INVALID_INDEX || mapped_outside[1] == MCON_INVALID_INDEX)
      << "the diameter's ends should leave the smaller patch";
}

TEST(CapiMapTransfer, CrossFieldFollowsTheGuidesAndTheRosyFileReadsBack) {
  MapSetup& x = setup();
  std::vector<uint32_t> tri;
  std::vector<double> bary;
  circle_points(x.s, 0.4, 30, tri, bary);
  const uint32_t size = 30;
  const uint8_t closed = 1;
  mcon_polyline_set set = nullptr;
  ASSERT_EQ(mcon_map_transfer_polylines(x.map.get(), tri.data(), bary.data(), tri.size(), &size, &closed, 1, &set),
            MCON_OK);
  const PolylineSetPtr guard(set);
  const Traced r = read_set(set);

  mcon_cross_field_options o;
  ASSERT_EQ(mcon_cross_field_options_init(&o), MCON_OK);
  EXPECT_EQ(o.alignment_weight, 10.0);
  std::vector<double> dir(3 * x.t.nt()), conf(x.t.nt());
  ASSERT_EQ(mcon_patch_compute_cross_field(x.target.get(), set, &o, dir.data(), conf.data(), x.t.nt()), MCON_OK)
      << last_message();
  // Unit, in the face plane, confidence in [0, 1].
  for (size_t f = 0; f < x.t.nt(); ++f) {
    const double* d = &dir[3 * f];
    EXPECT_NEAR(std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), 1.0, 1e-9);
    EXPECT_GE(conf[f], 0.0);
    EXPECT_LE(conf[f], 1.0 + 1e-12);
  }
  // Aligned with the guide (modulo 90 degrees) in the faces the guide crosses.
  double agreement = 0;
  int segments = 0;
  for (size_t i = 0; i + 1 < r.tri.size(); ++i) {
    double seg[3], len = 0;
    for (int k = 0; k < 3; ++k) {
      seg[k] = r.xyz[3 * (i + 1) + k] - r.xyz[3 * i + k];
      len += seg[k] * seg[k];
    }
    len = std::sqrt(len);
    if (len < 1e-9) continue;
    const double* d = &dir[3 * r.tri[i]];
    const double c = (seg[0] * d[0] + seg[1] * d[1] + seg[2] * d[2]) / len;
    const double angle = std::acos(std::min(1.0, std::abs(c)));
    agreement += std::cos(4 * angle);
    ++segments;
  }
  ASSERT_GT(segments, 10);
  EXPECT_GT(agreement / segments, 0.9);

  // No guides: the smoothest field; confidence may be NULL.
  std::vector<double> smooth(3 * x.t.nt());
  EXPECT_EQ(mcon_patch_compute_cross_field(x.target.get(), nullptr, nullptr, smooth.data(), nullptr, x.t.nt()), MCON_OK);

  // QuadWild reads a compressed .rosy as zeros: refused.
  const std::string gz = std::string(MACROCON_BINARY_DIR) + "/capi_map_transfer.rosy.gz";
  std::remove(gz.c_str());
  EXPECT_EQ(mcon_patch_write_rosy(x.target.get(), dir.data(), x.t.nt(), gz.c_str()), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("without .gz"), std::string::npos) << last_message();
  EXPECT_FALSE(std::ifstream(gz).good());
  for (const std::string name : {"capi_map_transfer.rosy"}) {
    const std::string path = std::string(MACROCON_BINARY_DIR) + "/" + name;
    std::remove(path.c_str());
    ASSERT_EQ(mcon_patch_write_rosy(x.target.get(), dir.data(), x.t.nt(), path.c_str()), MCON_OK) << last_message();
    const std::vector<mcon::Vec3> back = mcon::io::read_rosy(path);
    ASSERT_EQ(back.size(), x.t.nt());
    for (size_t f = 0; f < x.t.nt(); ++f)
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[f][k], dir[3 * f + k], 1e-6);
    std::remove(path.c_str());
  }
}

// mcon_map_transfer_field_f32: float in, float out; computed in double and rounded once, so it is
// the double transfer of the widened values cast to float (bit for bit), and within float
// precision of the double transfer of the unrounded values. Every interpolated kind.
TEST(CapiMapTransfer, Float32FieldsEqualTheRoundedDoubleTransfer) {
  MapSetup& x = setup();
  const auto ns = normals_of(x.s);
  struct Case {
    mcon_field_kind kind;
    uint32_t dim;
    std::vector<double> values;
  };
  std::vector<Case> cases;
  Case scalar{MCON_FIELD_SCALAR, 2, {}}, vec{MCON_FIELD_VECTOR3, 3, {}}, tangent{MCON_FIELD_TANGENT_VECTOR, 3, {}};
  for (size_t v = 0; v < x.s.nv(); ++v) {
    scalar.values.insert(scalar.values.end(), {x.s.xyz[3 * v] * 7.25 + 0.1, std::sin(3 * x.s.xyz[3 * v + 1])});
    for (int k = 0; k < 3; ++k) vec.values.push_back(x.s.info.center[k] + x.s.info.radius * x.s.xyz[3 * v + k]);
    const double a[3] = {1, 0.2, 0};
    const double d = a[0] * ns[v][0] + a[1] * ns[v][1] + a[2] * ns[v][2];
    for (int k = 0; k < 3; ++k) tangent.values.push_back(a[k] - d * ns[v][k]);
  }
  cases = {scalar, vec, tangent, Case{MCON_FIELD_UV, 2, x.s.uv}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.kind);
    std::vector<float> f32(c.values.begin(), c.values.end());
    const std::vector<double> widened(f32.begin(), f32.end());
    const size_t n = c.dim * x.t.nv();
    std::vector<float> out32(n, 9.0f);
    std::vector<double> ref(n), full(n);
    ASSERT_EQ(mcon_map_transfer_field_f32(x.map.get(), c.kind, c.dim, f32.data(), f32.size(), out32.data(), n),
              MCON_OK)
        << last_message();
    ASSERT_EQ(mcon_map_transfer_field(x.map.get(), c.kind, c.dim, widened.data(), widened.size(), ref.data(), n),
              MCON_OK);
    ASSERT_EQ(mcon_map_transfer_field(x.map.get(), c.kind, c.dim, c.values.data(), c.values.size(), full.data(), n),
              MCON_OK);
    double scale = 0;
    for (double v : full) scale = std::max(scale, std::abs(v));
    for (size_t i = 0; i < n; ++i) {
      ASSERT_EQ(out32[i], static_cast<float>(ref[i])) << i;
      // float inputs (relative error 2^-24 each) and one rounding of the result.
      ASSERT_NEAR(out32[i], full[i], 4e-7 * std::max(1.0, scale)) << i;
    }
  }
  // Errors as in the double function, in float units.
  std::vector<float> f(3 * x.s.nv(), 0.5f), out(3 * x.t.nv());
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_VECTOR3, 3, f.data(), f.size(), out.data(), out.size() - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_NE(last_message().find("capacity in floats"), std::string::npos) << last_message();
  EXPECT_NE(last_message().find("mcon_map_transfer_field_f32"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_VECTOR3, 3, f.data(), f.size() - 3, out.data(), out.size()),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_INTEGER_LABEL, 1, f.data(), x.s.nv(), out.data(),
                                        out.size()),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_UV, 3, f.data(), f.size(), out.data(), out.size()),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_VECTOR3, 3, nullptr, f.size(), out.data(), out.size()),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_field_f32(nullptr, MCON_FIELD_VECTOR3, 3, f.data(), f.size(), out.data(), out.size()),
            MCON_ERROR_NULL_POINTER);
  f[7] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_VECTOR3, 3, f.data(), f.size(), out.data(), out.size()),
            MCON_ERROR_NON_FINITE);
  EXPECT_NE(last_message().find("source_values[7]"), std::string::npos) << last_message();
  f[7] = std::numeric_limits<float>::infinity();
  EXPECT_EQ(mcon_map_transfer_field_f32(x.map.get(), MCON_FIELD_VECTOR3, 3, f.data(), f.size(), out.data(), out.size()),
            MCON_ERROR_NON_FINITE);
}
