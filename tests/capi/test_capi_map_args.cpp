// Negative tests for every function of the map section of macrocon.h: NULL and wrong-type
// handles, NULL outputs, struct_size, capacities, bad triangles and barycentric weights, wrong
// dimensions for a kind, non-disk arrays, NaN. The patches are small synthetic bumpy disks made
// with mcon_patch_create_from_arrays, so the map is quick.
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

#include "map_test_util.h"

using namespace map_test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

mcon::TriMesh bumpy_disk(int rings, double phase) {
  mcon::TriMesh m = mcon::test_meshes::make_disk(rings);
  for (auto& p : m.positions)
    p.z() = 0.25 * std::exp(-((p.x() - 0.2) * (p.x() - 0.2) + p.y() * p.y()) / 0.1) +
            0.1 * std::sin(3 * p.x() + phase) * std::cos(2 * p.y());
  return m;
}

mcon_patch_frame center_frame() {
  mcon_patch_frame f;
  EXPECT_EQ(mcon_patch_frame_init(&f), MCON_OK);
  f.center_triangle = 0;  // make_disk: triangle 0 touches the center vertex 0
  f.center_barycentric[0] = 1;
  f.center_barycentric[1] = f.center_barycentric[2] = 0;
  return f;
}

// The status of mcon_patch_create_from_arrays (out_patch must be NULL on failure).
mcon_status create_status(mcon_context ctx, const Arrays& a, const mcon_patch_frame& f) {
  const mcon_mesh_desc d = desc_of(a);
  mcon_patch p = reinterpret_cast<mcon_patch>(&p);
  const mcon_status s = mcon_patch_create_from_arrays(ctx, &d, &f, &p);
  if (s == MCON_OK) {
    mcon_patch_release(p);
  } else {
    EXPECT_EQ(p, nullptr);
  }
  return s;
}

class CapiMapArgs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ctx_ = make_context().release();
    const mcon_patch_frame f = center_frame();
    for (int i = 0; i < 2; ++i) {
      const Arrays a = arrays_of(bumpy_disk(i == 0 ? 7 : 9, 0.3 * i));
      const mcon_mesh_desc d = desc_of(a);
      ASSERT_EQ(mcon_patch_create_from_arrays(ctx_, &d, &f, i == 0 ? &source_ : &target_), MCON_OK) << last_message();
    }
    mcon_map_options o = fast_options();
    ASSERT_EQ(mcon_map_compute(source_, target_, &o, &map_), MCON_OK) << last_message();
    mcon_patch_info info;
    mcon_patch_info_init(&info);
    mcon_patch_get_info(source_, &info);
    ns_ = info.vertex_count;
    nts_ = info.triangle_count;
    mcon_patch_get_info(target_, &info);
    nt_ = info.vertex_count;
    ntt_ = info.triangle_count;
    // From the center to a point halfway out.
    const uint32_t tri[2] = {0, static_cast<uint32_t>(nts_ / 3)};
    const double bary[6] = {1, 0, 0, 1.0 / 3, 1.0 / 3, 1.0 / 3};
    const uint32_t size = 2;
    ASSERT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 2, &size, nullptr, 1, &set_), MCON_OK) << last_message();
  }
  static void TearDownTestSuite() {
    mcon_polyline_set_release(set_);
    mcon_map_release(map_);
    mcon_patch_release(source_);
    mcon_patch_release(target_);
    mcon_context_release(ctx_);
  }
  static mcon_context ctx_;
  static mcon_patch source_, target_;
  static mcon_map map_;
  static mcon_polyline_set set_;
  static size_t ns_, nt_, nts_, ntt_;
};
mcon_context CapiMapArgs::ctx_ = nullptr;
mcon_patch CapiMapArgs::source_ = nullptr;
mcon_patch CapiMapArgs::target_ = nullptr;
mcon_map CapiMapArgs::map_ = nullptr;
mcon_polyline_set CapiMapArgs::set_ = nullptr;
size_t CapiMapArgs::ns_ = 0, CapiMapArgs::nt_ = 0, CapiMapArgs::nts_ = 0, CapiMapArgs::ntt_ = 0;

bool mentions(const std::string& text) { return last_message().find(text) != std::string::npos; }

}  // namespace

TEST_F(CapiMapArgs, InitFunctions) {
  EXPECT_EQ(mcon_patch_frame_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_options_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_info_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cross_field_options_init(nullptr), MCON_ERROR_NULL_POINTER);
  mcon_map_options o;
  std::memset(&o, 0x55, sizeof o);
  ASSERT_EQ(mcon_map_options_init(&o), MCON_OK);
  EXPECT_EQ(o.struct_size, sizeof o);
  EXPECT_EQ(o.seed, 0u);
  EXPECT_EQ(o.alignment_samples, 10000u);
  EXPECT_EQ(o.allow_reflection, 1u);
  EXPECT_EQ(o.max_iterations, 100u);
  EXPECT_EQ(o.progress, nullptr);
  EXPECT_EQ(o.orientation, static_cast<uint32_t>(MCON_MAP_ORIENTATION_AUTOMATIC));
  mcon_patch_frame f;
  std::memset(&f, 0x55, sizeof f);
  ASSERT_EQ(mcon_patch_frame_init(&f), MCON_OK);
  EXPECT_EQ(f.center_triangle, MCON_INVALID_INDEX);
  EXPECT_EQ(f.origin[0], 0.0);
  EXPECT_EQ(f.scale, 1.0);
  mcon_cross_field_options c;
  ASSERT_EQ(mcon_cross_field_options_init(&c), MCON_OK);
  EXPECT_EQ(c.align_to_boundary, 0u);
  EXPECT_EQ(c.boundary_weight, 1.0);
}

TEST_F(CapiMapArgs, CreateFromArraysRejectsBadArguments) {
  const Arrays a = arrays_of(bumpy_disk(4, 0));
  const mcon_mesh_desc d = desc_of(a);
  mcon_patch_frame f = center_frame();
  mcon_patch p = reinterpret_cast<mcon_patch>(&f);
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx_, &d, &f, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_create_from_arrays(nullptr, &d, &f, &p), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(p, nullptr);
  Garbage g;
  EXPECT_EQ(mcon_patch_create_from_arrays(reinterpret_cast<mcon_context>(&g), &d, &f, &p), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx_, nullptr, &f, &p), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx_, &d, nullptr, &p), MCON_ERROR_NULL_POINTER);
  mcon_patch_frame small = f;
  small.struct_size = sizeof(mcon_patch_frame) - 1;
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx_, &d, &small, &p), MCON_ERROR_STRUCT_SIZE);
  mcon_mesh_desc small_desc = d;
  small_desc.struct_size = 4;
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx_, &small_desc, &f, &p), MCON_ERROR_STRUCT_SIZE);
  EXPECT_EQ(p, nullptr);

  auto with = [&](auto change) {
    mcon_patch_frame x = center_frame();
    change(x);
    return create_status(ctx_, a, x);
  };
  EXPECT_EQ(with([](mcon_patch_frame&) {}), MCON_OK);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.center_triangle = MCON_INVALID_INDEX; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("center_triangle")) << last_message();
  EXPECT_EQ(with([&](mcon_patch_frame& x) { x.center_triangle = static_cast<uint32_t>(a.triangle_count()); }),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.center_barycentric[0] = -0.5; x.center_barycentric[1] = 1.5; }),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.center_barycentric[1] = 0.5; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.center_barycentric[2] = kNaN; }), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.scale = 0; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.scale = -2; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.scale = kNaN; }), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(with([](mcon_patch_frame& x) { x.origin[1] = kNaN; }), MCON_ERROR_NON_FINITE);

  // Mesh validation errors as mcon_mesh_create.
  Arrays nan = a;
  nan.positions[4] = kNaN;
  EXPECT_EQ(create_status(ctx_, nan, f), MCON_ERROR_NON_FINITE);
  Arrays bad_index = a;
  bad_index.indices[5] = 100000;
  EXPECT_EQ(create_status(ctx_, bad_index, f), MCON_ERROR_INDEX_OUT_OF_RANGE);
  mcon_mesh_desc no_type = d;
  no_type.position_type = 0;
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx_, &no_type, &f, &p), MCON_ERROR_INVALID_ARGUMENT);

  // Not disks.
  EXPECT_EQ(create_status(ctx_, arrays_of(mcon::test_meshes::make_icosphere(1)), f), MCON_ERROR_NOT_A_DISK);
  EXPECT_TRUE(mentions("closed")) << last_message();
  EXPECT_EQ(create_status(ctx_, arrays_of(mcon::test_meshes::make_cylinder(1, 2, 12, 3)), f), MCON_ERROR_NOT_A_DISK);
  EXPECT_TRUE(mentions("boundary loops")) << last_message();
  Arrays two = a;
  const Arrays b = arrays_of(bumpy_disk(3, 1));
  const uint32_t offset = static_cast<uint32_t>(two.vertex_count());
  for (size_t i = 0; i < b.positions.size(); ++i) two.positions.push_back(b.positions[i] + (i % 3 == 0 ? 5.0 : 0.0));
  for (uint32_t i : b.indices) two.indices.push_back(i + offset);
  EXPECT_EQ(create_status(ctx_, two, f), MCON_ERROR_NOT_A_DISK);
  EXPECT_TRUE(mentions("pieces")) << last_message();
}

TEST_F(CapiMapArgs, ComputeRejectsBadArguments) {
  mcon_map_options o = fast_options();
  mcon_map m = reinterpret_cast<mcon_map>(&o);
  EXPECT_EQ(mcon_map_compute(source_, target_, &o, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_compute(nullptr, target_, &o, &m), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(m, nullptr);
  EXPECT_EQ(mcon_map_compute(source_, nullptr, &o, &m), MCON_ERROR_NULL_POINTER);
  Garbage g;
  EXPECT_EQ(mcon_map_compute(reinterpret_cast<mcon_patch>(&g), target_, &o, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_compute(source_, reinterpret_cast<mcon_patch>(map_), &o, &m), MCON_ERROR_INVALID_ARGUMENT);
  // The first published size (ending before `orientation`) is the minimum.
  for (uint32_t size : {0u, static_cast<uint32_t>(offsetof(mcon_map_options, orientation) - 1)}) {
    mcon_map_options x = o;
    x.struct_size = size;
    EXPECT_EQ(mcon_map_compute(source_, target_, &x, &m), MCON_ERROR_STRUCT_SIZE);
  }
  mcon_map_options x = o;
  x.alignment_samples = 0;
  EXPECT_EQ(mcon_map_compute(source_, target_, &x, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("alignment_samples")) << last_message();
  x = o;
  x.max_iterations = 0;
  EXPECT_EQ(mcon_map_compute(source_, target_, &x, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("max_iterations")) << last_message();
  EXPECT_EQ(m, nullptr);
}

TEST_F(CapiMapArgs, ComputeRejectsAnOrientationOutsideTheEnum) {
  const mcon_map_options o = fast_options();
  for (uint32_t bad : {3u, 7u, 0x80000000u, 0xFFFFFFFFu}) {
    mcon_map_options x = o;
    x.orientation = bad;
    mcon_map m = reinterpret_cast<mcon_map>(&x);
    EXPECT_EQ(mcon_map_compute(source_, target_, &x, &m), MCON_ERROR_INVALID_ARGUMENT) << bad;
    EXPECT_TRUE(mentions("orientation " + std::to_string(bad))) << last_message();
    EXPECT_TRUE(mentions("mcon_map_orientation")) << last_message();
    EXPECT_EQ(m, nullptr);
  }
}

TEST_F(CapiMapArgs, OptionsOfTheFirstPublishedSizeGetTheAutomaticOrientation) {
  // A caller compiled before `orientation` existed passes the old struct_size; whatever lies
  // beyond it in memory (here a REVERSE that would flip the map, or an invalid value) is not read.
  mcon_map_info reference;
  ASSERT_EQ(mcon_map_info_init(&reference), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(map_, &reference), MCON_OK);  // map_: fast_options, full size
  std::vector<double> phi_reference(2 * ns_);
  ASSERT_EQ(mcon_map_get_phi(map_, phi_reference.data(), phi_reference.size()), MCON_OK);
  for (uint32_t beyond : {static_cast<uint32_t>(MCON_MAP_ORIENTATION_REVERSE), 99u}) {
    mcon_map_options old = fast_options();
    old.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, orientation));
    old.orientation = beyond;
    mcon_map m = nullptr;
    ASSERT_EQ(mcon_map_compute(source_, target_, &old, &m), MCON_OK) << last_message();
    const MapPtr map(m);
    EXPECT_EQ(old.struct_size, offsetof(mcon_map_options, orientation));  // the caller's struct is untouched
    mcon_map_info info;
    ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
    ASSERT_EQ(mcon_map_get_info(m, &info), MCON_OK);
    EXPECT_EQ(info.reflected, reference.reflected);
    EXPECT_EQ(info.orientation_compared, reference.orientation_compared);
    std::vector<double> phi(2 * ns_);
    ASSERT_EQ(mcon_map_get_phi(m, phi.data(), phi.size()), MCON_OK);
    EXPECT_EQ(phi, phi_reference);  // bit-identical to the automatic default
  }
}

TEST_F(CapiMapArgs, InfoOfTheFirstPublishedSizeIsFilledUpToItsEnd) {
  // An old caller's info struct ends at optimization_seconds: those bytes are written, nothing after.
  const size_t old_size = offsetof(mcon_map_info, alignment_score_unreflected);
  std::vector<unsigned char> buffer(sizeof(mcon_map_info) + 16, 0xA5);
  mcon_map_info* info = reinterpret_cast<mcon_map_info*>(buffer.data());
  const uint32_t size = static_cast<uint32_t>(old_size);
  std::memcpy(buffer.data(), &size, sizeof size);
  ASSERT_EQ(mcon_map_get_info(map_, info), MCON_OK) << last_message();
  EXPECT_EQ(info->struct_size, size);
  EXPECT_EQ(info->source_vertex_count, ns_);
  EXPECT_GT(info->optimization_seconds, 0.0);
  for (size_t b = old_size; b < buffer.size(); ++b) ASSERT_EQ(buffer[b], 0xA5) << "byte " << b << " was written";
  mcon_map_info small;
  ASSERT_EQ(mcon_map_info_init(&small), MCON_OK);
  small.struct_size = static_cast<uint32_t>(old_size - 1);
  EXPECT_EQ(mcon_map_get_info(map_, &small), MCON_ERROR_STRUCT_SIZE);
}

TEST_F(CapiMapArgs, RetainReleaseAndInfo) {
  EXPECT_EQ(mcon_map_retain(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_release(nullptr), MCON_OK);
  EXPECT_EQ(mcon_polyline_set_retain(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_polyline_set_release(nullptr), MCON_OK);
  EXPECT_EQ(mcon_map_retain(reinterpret_cast<mcon_map>(set_)), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_polyline_set_release(reinterpret_cast<mcon_polyline_set>(map_)), MCON_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(mcon_map_retain(map_), MCON_OK);
  ASSERT_EQ(mcon_map_release(map_), MCON_OK);
  ASSERT_EQ(mcon_polyline_set_retain(set_), MCON_OK);
  ASSERT_EQ(mcon_polyline_set_release(set_), MCON_OK);

  mcon_map_info info;
  ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
  EXPECT_EQ(mcon_map_get_info(nullptr, &info), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_info(map_, nullptr), MCON_ERROR_NULL_POINTER);
  Garbage g;
  EXPECT_EQ(mcon_map_get_info(reinterpret_cast<mcon_map>(&g), &info), MCON_ERROR_INVALID_ARGUMENT);
  info.struct_size = 8;
  EXPECT_EQ(mcon_map_get_info(map_, &info), MCON_ERROR_STRUCT_SIZE);
  ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(map_, &info), MCON_OK);
  EXPECT_EQ(info.source_vertex_count, ns_);
  EXPECT_EQ(info.target_vertex_count, nt_);
  EXPECT_EQ(info.flipped_triangles, 0u);
}

TEST_F(CapiMapArgs, EnergyTermsByIndexMatchTheInfoFields) {
  uint32_t count = 0;
  ASSERT_EQ(mcon_map_get_energy_term_count(map_, &count), MCON_OK) << last_message();
  ASSERT_GE(count, 4u);
  mcon_map_info info;
  ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(map_, &info), MCON_OK);
  const std::vector<std::pair<std::string, double>> expected = {{"descriptor", info.energy_descriptor},
                                                                {"distortion", info.energy_distortion},
                                                                {"area", info.energy_area},
                                                                {"injectivity", info.energy_injectivity}};
  for (uint32_t i = 0; i < count; ++i) {
    const char* name = nullptr;
    double value = -1;
    ASSERT_EQ(mcon_map_get_energy_term(map_, i, &name, &value), MCON_OK) << last_message();
    ASSERT_NE(name, nullptr);
    if (i < expected.size()) {
      EXPECT_EQ(name, expected[i].first);
      EXPECT_EQ(value, expected[i].second) << name;
    }
    EXPECT_TRUE(std::isfinite(value)) << name;
  }
  // Either output alone is enough.
  const char* name = nullptr;
  EXPECT_EQ(mcon_map_get_energy_term(map_, 1, &name, nullptr), MCON_OK);
  EXPECT_STREQ(name, "distortion");
  double value = 0;
  EXPECT_EQ(mcon_map_get_energy_term(map_, 0, nullptr, &value), MCON_OK);
  EXPECT_EQ(value, info.energy_descriptor);
}

TEST_F(CapiMapArgs, EnergyTermGettersRejectBadArguments) {
  uint32_t count = 0;
  EXPECT_EQ(mcon_map_get_energy_term_count(nullptr, &count), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_energy_term_count(map_, nullptr), MCON_ERROR_NULL_POINTER);
  Garbage g;
  EXPECT_EQ(mcon_map_get_energy_term_count(reinterpret_cast<mcon_map>(&g), &count), MCON_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(mcon_map_get_energy_term_count(map_, &count), MCON_OK);
  const char* name = nullptr;
  double value = 0;
  EXPECT_EQ(mcon_map_get_energy_term(nullptr, 0, &name, &value), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_energy_term(map_, 0, nullptr, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_energy_term(reinterpret_cast<mcon_map>(&g), 0, &name, &value), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_get_energy_term(map_, count, &name, &value), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("mcon_map_get_energy_term_count")) << last_message();
  EXPECT_EQ(mcon_map_get_energy_term(map_, UINT32_MAX, &name, &value), MCON_ERROR_INVALID_ARGUMENT);
}

TEST_F(CapiMapArgs, QueriesRejectBadArguments) {
  std::vector<int32_t> tri(nt_ + ns_);
  std::vector<double> bary(3 * (nt_ + ns_)), phi(2 * ns_);
  std::vector<uint8_t> mask(nt_);
  EXPECT_EQ(mcon_map_get_correspondences(nullptr, MCON_MAP_SOURCE_TO_TARGET, tri.data(), bary.data(), ns_),
            MCON_ERROR_NULL_POINTER);
  for (int bad : {0, 3, -1}) {
    mcon_map_direction d;
    std::memcpy(&d, &bad, sizeof d);
    EXPECT_EQ(mcon_map_get_correspondences(map_, d, tri.data(), bary.data(), ns_), MCON_ERROR_INVALID_ARGUMENT) << bad;
  }
  EXPECT_EQ(mcon_map_get_correspondences(map_, MCON_MAP_SOURCE_TO_TARGET, tri.data(), bary.data(), ns_ - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_map_get_correspondences(map_, MCON_MAP_TARGET_TO_SOURCE, tri.data(), nullptr, nt_ - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_map_get_correspondences(map_, MCON_MAP_TARGET_TO_SOURCE, nullptr, nullptr, 0), MCON_OK);
  EXPECT_EQ(mcon_map_get_phi(nullptr, phi.data(), phi.size()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_phi(map_, nullptr, phi.size()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_phi(map_, phi.data(), phi.size() - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_map_get_outside_mask(nullptr, mask.data(), nt_), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_outside_mask(map_, nullptr, nt_), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_get_outside_mask(map_, mask.data(), nt_ - 1), MCON_ERROR_BUFFER_TOO_SMALL);
}

TEST_F(CapiMapArgs, TransferPointsRejectsBadPoints) {
  uint32_t tri[2] = {0, 1};
  double bary[6] = {1, 0, 0, 0.2, 0.3, 0.5};
  uint32_t ot[2];
  double ob[6], ox[6];
  EXPECT_EQ(mcon_map_transfer_points(nullptr, tri, bary, 2, ot, ob, ox, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_points(map_, nullptr, bary, 2, ot, ob, ox, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_points(map_, tri, nullptr, 2, ot, ob, ox, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_points(map_, tri, bary, 2, ot, ob, ox, 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_map_transfer_points(map_, nullptr, nullptr, 0, ot, ob, ox, 0), MCON_OK);
  tri[1] = static_cast<uint32_t>(nts_);
  EXPECT_EQ(mcon_map_transfer_points(map_, tri, bary, 2, ot, ob, ox, 2), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("out of range")) << last_message();
  tri[1] = 1;
  bary[3] = -0.2;
  bary[5] = 0.9;
  EXPECT_EQ(mcon_map_transfer_points(map_, tri, bary, 2, ot, ob, ox, 2), MCON_ERROR_INVALID_ARGUMENT);
  bary[3] = 0.5;  // sums to 1.7
  EXPECT_EQ(mcon_map_transfer_points(map_, tri, bary, 2, ot, ob, ox, 2), MCON_ERROR_INVALID_ARGUMENT);
  bary[3] = kNaN;
  EXPECT_EQ(mcon_map_transfer_points(map_, tri, bary, 2, ot, ob, ox, 2), MCON_ERROR_NON_FINITE);
}

TEST_F(CapiMapArgs, TransferPolylinesRejectsBadPolylines) {
  const uint32_t tri[4] = {0, 1, 2, 3};
  double bary[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
  mcon_polyline_set s = reinterpret_cast<mcon_polyline_set>(&s);
  uint32_t sizes[2] = {2, 2};
  uint8_t closed[2] = {0, 0};
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, sizes, closed, 2, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_polylines(nullptr, tri, bary, 4, sizes, closed, 2, &s), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, nullptr, closed, 2, &s), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(s, nullptr);
  EXPECT_EQ(mcon_map_transfer_polylines(map_, nullptr, bary, 4, sizes, closed, 2, &s), MCON_ERROR_NULL_POINTER);
  uint32_t one[2] = {1, 3};
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, one, closed, 2, &s), MCON_ERROR_INVALID_ARGUMENT);
  closed[0] = 1;
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, sizes, closed, 2, &s), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("closed")) << last_message();
  closed[0] = 0;
  uint32_t too_many[2] = {2, 3};
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, too_many, closed, 2, &s), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, sizes, closed, 1, &s), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("point_count")) << last_message();
  bary[4] = 0.5;
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, sizes, closed, 2, &s), MCON_ERROR_INVALID_ARGUMENT);
  bary[4] = kNaN;
  EXPECT_EQ(mcon_map_transfer_polylines(map_, tri, bary, 4, sizes, closed, 2, &s), MCON_ERROR_NON_FINITE);
  bary[4] = 0;
  const uint32_t bad_tri[4] = {0, 1, static_cast<uint32_t>(nts_) + 7, 3};
  EXPECT_EQ(mcon_map_transfer_polylines(map_, bad_tri, bary, 4, sizes, closed, 2, &s), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(s, nullptr);
  // Zero polylines is a valid, empty set.
  ASSERT_EQ(mcon_map_transfer_polylines(map_, nullptr, nullptr, 0, nullptr, nullptr, 0, &s), MCON_OK);
  size_t np = 9, n = 9;
  EXPECT_EQ(mcon_polyline_set_get_counts(s, &np, &n), MCON_OK);
  EXPECT_EQ(np, 0u);
  EXPECT_EQ(n, 0u);
  mcon_polyline_set_release(s);
}

TEST_F(CapiMapArgs, PolylineSetGettersRejectBadArguments) {
  size_t np = 0, n = 0;
  EXPECT_EQ(mcon_polyline_set_get_counts(nullptr, &np, &n), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_polyline_set_get_counts(set_, nullptr, &n), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_polyline_set_get_counts(set_, &np, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_polyline_set_get_counts(reinterpret_cast<mcon_polyline_set>(map_), &np, &n), MCON_ERROR_INVALID_ARGUMENT);
  ASSERT_EQ(mcon_polyline_set_get_counts(set_, &np, &n), MCON_OK);
  ASSERT_GE(np, 1u);
  std::vector<uint32_t> sizes(np), input(np), tri(n);
  std::vector<uint8_t> closed(np);
  std::vector<double> bary(3 * n), xyz(3 * n);
  EXPECT_EQ(mcon_polyline_set_get_polylines(nullptr, sizes.data(), closed.data(), input.data(), np),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_polyline_set_get_polylines(set_, sizes.data(), closed.data(), input.data(), np - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_polyline_set_get_polylines(set_, nullptr, nullptr, input.data(), np), MCON_OK);
  EXPECT_EQ(input[0], 0u);
  EXPECT_EQ(mcon_polyline_set_get_points(nullptr, tri.data(), bary.data(), xyz.data(), n), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_polyline_set_get_points(set_, tri.data(), bary.data(), xyz.data(), n - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_polyline_set_get_points(set_, nullptr, nullptr, xyz.data(), n), MCON_OK);
}

TEST_F(CapiMapArgs, TransferFieldRejectsBadKindsDimensionsAndValues) {
  std::vector<double> in(3 * ns_, 0.5), out(3 * nt_);
  auto call = [&](int kind, uint32_t dim, size_t count, size_t cap) {
    mcon_field_kind k;
    std::memcpy(&k, &kind, sizeof k);
    return mcon_map_transfer_field(map_, k, dim, in.data(), count, out.data(), cap);
  };
  EXPECT_EQ(call(MCON_FIELD_SCALAR, 3, 3 * ns_, 3 * nt_), MCON_OK);
  EXPECT_EQ(mcon_map_transfer_field(nullptr, MCON_FIELD_SCALAR, 1, in.data(), ns_, out.data(), nt_),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_field(map_, MCON_FIELD_SCALAR, 1, nullptr, ns_, out.data(), nt_), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_field(map_, MCON_FIELD_SCALAR, 1, in.data(), ns_, nullptr, nt_), MCON_ERROR_NULL_POINTER);
  for (int bad : {0, 6, 99, -3}) EXPECT_EQ(call(bad, 1, ns_, nt_), MCON_ERROR_INVALID_ARGUMENT) << bad;
  EXPECT_EQ(call(MCON_FIELD_INTEGER_LABEL, 1, ns_, nt_), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("mcon_map_transfer_labels")) << last_message();
  EXPECT_EQ(call(MCON_FIELD_SCALAR, 0, 0, nt_), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(MCON_FIELD_VECTOR3, 2, 2 * ns_, 3 * nt_), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(MCON_FIELD_TANGENT_VECTOR, 2, 2 * ns_, 3 * nt_), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(MCON_FIELD_UV, 3, 3 * ns_, 3 * nt_), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(call(MCON_FIELD_UV, 2, 2 * ns_ - 1, 3 * nt_), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("value_count")) << last_message();
  EXPECT_EQ(call(MCON_FIELD_VECTOR3, 3, 3 * ns_, 3 * nt_ - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  in[7] = kNaN;
  EXPECT_EQ(call(MCON_FIELD_TANGENT_VECTOR, 3, 3 * ns_, 3 * nt_), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(call(MCON_FIELD_SCALAR, 1, ns_, nt_), MCON_ERROR_NON_FINITE);
}

TEST_F(CapiMapArgs, TransferLabelsRejectsBadArguments) {
  std::vector<int32_t> in(2 * ns_, 4), out(2 * nt_);
  EXPECT_EQ(mcon_map_transfer_labels(map_, 2, in.data(), in.size(), -1, out.data(), out.size()), MCON_OK);
  EXPECT_EQ(mcon_map_transfer_labels(nullptr, 2, in.data(), in.size(), -1, out.data(), out.size()),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_labels(map_, 0, in.data(), 0, -1, out.data(), out.size()), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_transfer_labels(map_, 2, nullptr, in.size(), -1, out.data(), out.size()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_labels(map_, 2, in.data(), in.size(), -1, nullptr, out.size()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_map_transfer_labels(map_, 2, in.data(), in.size() - 1, -1, out.data(), out.size()),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_map_transfer_labels(map_, 2, in.data(), in.size(), -1, out.data(), out.size() - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
}

TEST_F(CapiMapArgs, CrossFieldAndRosyRejectBadArguments) {
  std::vector<double> dir(3 * ntt_), conf(ntt_);
  mcon_cross_field_options o;
  ASSERT_EQ(mcon_cross_field_options_init(&o), MCON_OK);
  EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &o, dir.data(), conf.data(), ntt_), MCON_OK) << last_message();
  EXPECT_EQ(mcon_patch_compute_cross_field(nullptr, set_, &o, dir.data(), conf.data(), ntt_), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &o, nullptr, conf.data(), ntt_), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &o, dir.data(), conf.data(), ntt_ - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  // The guides lie on the target, not on the source.
  EXPECT_EQ(mcon_patch_compute_cross_field(source_, set_, &o, dir.data(), conf.data(), ntt_ + nts_),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("another patch")) << last_message();
  Garbage g;
  EXPECT_EQ(mcon_patch_compute_cross_field(target_, reinterpret_cast<mcon_polyline_set>(&g), &o, dir.data(),
                                           conf.data(), ntt_),
            MCON_ERROR_INVALID_ARGUMENT);
  mcon_cross_field_options x = o;
  x.struct_size = 3;
  EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &x, dir.data(), conf.data(), ntt_), MCON_ERROR_STRUCT_SIZE);
  for (double w : {0.0, -1.0}) {
    x = o;
    x.alignment_weight = w;
    EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &x, dir.data(), conf.data(), ntt_),
              MCON_ERROR_INVALID_ARGUMENT);
    x = o;
    x.boundary_weight = w;
    EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &x, dir.data(), conf.data(), ntt_),
              MCON_ERROR_INVALID_ARGUMENT);
  }
  x = o;
  x.alignment_weight = kNaN;
  EXPECT_EQ(mcon_patch_compute_cross_field(target_, set_, &x, dir.data(), conf.data(), ntt_), MCON_ERROR_NON_FINITE);

  const std::string path = std::string(MACROCON_BINARY_DIR) + "/capi_map_args.rosy";
  EXPECT_EQ(mcon_patch_write_rosy(nullptr, dir.data(), ntt_, path.c_str()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_write_rosy(target_, nullptr, ntt_, path.c_str()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_write_rosy(target_, dir.data(), ntt_, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_write_rosy(target_, dir.data(), ntt_, ""), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_patch_write_rosy(target_, dir.data(), ntt_ - 1, path.c_str()), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_patch_write_rosy(target_, dir.data(), ntt_, "/nonexistent-dir/x/field.rosy"), MCON_ERROR_IO);
  dir[4] = kNaN;
  EXPECT_EQ(mcon_patch_write_rosy(target_, dir.data(), ntt_, path.c_str()), MCON_ERROR_NON_FINITE);
}

TEST_F(CapiMapArgs, ComputeRejectsBadGuidance) {
  std::vector<double> gs(2 * ns_, 0.5), gt(2 * nt_, 0.5);
  for (size_t v = 0; v < ns_; ++v) gs[2 * v] = static_cast<double>(v);
  for (size_t w = 0; w < nt_; ++w) gt[2 * w] = static_cast<double>(w);
  auto status = [&](const mcon_map_options& x) {
    mcon_map m = reinterpret_cast<mcon_map>(&m);
    const mcon_status s = mcon_map_compute(source_, target_, &x, &m);
    if (s == MCON_OK) {
      mcon_map_release(m);
    } else {
      EXPECT_EQ(m, nullptr);
    }
    return s;
  };
  mcon_map_options o = fast_options();
  EXPECT_EQ(o.guidance_dimension, 0u);
  EXPECT_EQ(o.guidance_weight, 1.0);
  o.source_guidance = gs.data();
  EXPECT_EQ(status(o), MCON_ERROR_INVALID_ARGUMENT) << "an array with guidance_dimension 0";
  EXPECT_TRUE(mentions("guidance_dimension 0")) << last_message();

  o.guidance_dimension = 2;
  EXPECT_EQ(status(o), MCON_ERROR_NULL_POINTER) << "no target array";
  EXPECT_TRUE(mentions("target_guidance")) << last_message();
  o.target_guidance = gt.data();
  EXPECT_EQ(status(o), MCON_OK) << last_message();

  mcon_map_options x = o;
  x.source_guidance_stride = sizeof(double);  // smaller than a row of 2
  EXPECT_EQ(status(x), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(mentions("source_guidance: stride")) << last_message();
  x = o;
  x.guidance_dimension = 5000;
  EXPECT_EQ(status(x), MCON_ERROR_INVALID_ARGUMENT);
  for (double w : {-1.0, kNaN, std::numeric_limits<double>::infinity()}) {
    x = o;
    x.guidance_weight = w;
    EXPECT_EQ(status(x), MCON_ERROR_INVALID_ARGUMENT) << w;
    EXPECT_TRUE(mentions("guidance_weight")) << last_message();
  }
  std::vector<double> bad = gt;
  bad[2 * (nt_ / 2) + 1] = kNaN;
  x = o;
  x.target_guidance = bad.data();
  EXPECT_EQ(status(x), MCON_ERROR_NON_FINITE);
  EXPECT_TRUE(mentions("target_guidance")) << last_message();

  // A strided source array (rows of 3 doubles, the guidance in the first 2) is the packed one.
  std::vector<double> wide(3 * ns_, -7.0);
  for (size_t v = 0; v < ns_; ++v) {
    wide[3 * v] = gs[2 * v];
    wide[3 * v + 1] = gs[2 * v + 1];
  }
  x = o;
  x.source_guidance = wide.data();
  x.source_guidance_stride = 3 * sizeof(double);
  mcon_map packed = nullptr, strided = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &o, &packed), MCON_OK) << last_message();
  ASSERT_EQ(mcon_map_compute(source_, target_, &x, &strided), MCON_OK) << last_message();
  const MapPtr p1(packed), p2(strided);
  std::vector<double> phi1(2 * ns_), phi2(2 * ns_);
  ASSERT_EQ(mcon_map_get_phi(packed, phi1.data(), phi1.size()), MCON_OK);
  ASSERT_EQ(mcon_map_get_phi(strided, phi2.data(), phi2.size()), MCON_OK);
  EXPECT_EQ(phi1, phi2);
}

TEST_F(CapiMapArgs, OptionsOfTheOrientationSizeIgnoreGuidanceBeyondIt) {
  // A caller compiled before the guidance fields passes struct_size up to `orientation`: garbage
  // beyond it (a dimension without arrays, which the full size rejects) is not read.
  mcon_map_options old = fast_options();
  old.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, source_guidance));
  old.guidance_dimension = 3;
  mcon_map m = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &old, &m), MCON_OK) << last_message();
  const MapPtr map(m);
  std::vector<double> phi(2 * ns_), reference(2 * ns_);
  ASSERT_EQ(mcon_map_get_phi(m, phi.data(), phi.size()), MCON_OK);
  ASSERT_EQ(mcon_map_get_phi(map_, reference.data(), reference.size()), MCON_OK);
  EXPECT_EQ(phi, reference);
  mcon_map_options full = fast_options();
  full.guidance_dimension = 3;
  mcon_map n = nullptr;
  EXPECT_EQ(mcon_map_compute(source_, target_, &full, &n), MCON_ERROR_NULL_POINTER);
}

TEST_F(CapiMapArgs, RefineSigmaFactorIsCheckedAndSwitchesThePass) {
  // Default 0.5: the refinement pass is a stage of its own (levels 4); 0 turns it off (levels 3,
  // a different map); outside [0, 1] or NaN is refused with the field's name.
  mcon_map_options o;
  ASSERT_EQ(mcon_map_options_init(&o), MCON_OK);
  EXPECT_EQ(o.refine_sigma_factor, 0.5);
  auto info_of = [](mcon_map m) {
    mcon_map_info info;
    mcon_map_info_init(&info);
    EXPECT_EQ(mcon_map_get_info(m, &info), MCON_OK);
    return info;
  };
  EXPECT_EQ(info_of(map_).levels, 4u);
  mcon_map_options off = fast_options();
  off.refine_sigma_factor = 0;
  mcon_map m = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &off, &m), MCON_OK) << last_message();
  const MapPtr unrefined(m);
  EXPECT_EQ(info_of(m).levels, 3u);
  EXPECT_LT(info_of(m).iterations, info_of(map_).iterations);
  std::vector<double> phi(2 * ns_), reference(2 * ns_);
  ASSERT_EQ(mcon_map_get_phi(m, phi.data(), phi.size()), MCON_OK);
  ASSERT_EQ(mcon_map_get_phi(map_, reference.data(), reference.size()), MCON_OK);
  EXPECT_NE(phi, reference);
  for (double bad : {-0.1, 1.5, kNaN, std::numeric_limits<double>::infinity()}) {
    mcon_map_options x = fast_options();
    x.refine_sigma_factor = bad;
    mcon_map n = reinterpret_cast<mcon_map>(&n);
    EXPECT_EQ(mcon_map_compute(source_, target_, &x, &n), MCON_ERROR_INVALID_ARGUMENT) << bad;
    EXPECT_EQ(n, nullptr);
    EXPECT_TRUE(mentions("refine_sigma_factor")) << last_message();
  }
  // A caller compiled before the field (struct_size up to guidance_weight's end) gets the default,
  // and garbage beyond its size is not read.
  mcon_map_options old = fast_options();
  old.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, refine_sigma_factor));
  old.refine_sigma_factor = -5;
  mcon_map k = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &old, &k), MCON_OK) << last_message();
  const MapPtr defaulted(k);
  ASSERT_EQ(mcon_map_get_phi(k, phi.data(), phi.size()), MCON_OK);
  EXPECT_EQ(phi, reference);
}

TEST_F(CapiMapArgs, WorldFrameStartIsOptInAndReported) {
  // Default off (frame_decided 0); on, the world-frame start decides (frame_decided 1); with a
  // forced orientation it is refused with the field's name; a caller compiled before the fields
  // (struct_size up to refine_sigma_factor's end) gets the frame-free default.
  mcon_map_options o;
  ASSERT_EQ(mcon_map_options_init(&o), MCON_OK);
  EXPECT_EQ(o.use_world_frame, 0u);
  EXPECT_EQ(o.world_frame_mirror, 0u);
  auto info_of = [](mcon_map m) {
    mcon_map_info info;
    mcon_map_info_init(&info);
    EXPECT_EQ(mcon_map_get_info(m, &info), MCON_OK);
    return info;
  };
  EXPECT_EQ(info_of(map_).frame_decided, 0u);
  mcon_map_options on = fast_options();
  on.use_world_frame = 1;
  mcon_map m = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &on, &m), MCON_OK) << last_message();
  const MapPtr framed(m);
  EXPECT_EQ(info_of(m).frame_decided, 1u);
  mcon_map_options forced = on;
  forced.orientation = MCON_MAP_ORIENTATION_PRESERVE;
  mcon_map n = reinterpret_cast<mcon_map>(&n);
  EXPECT_EQ(mcon_map_compute(source_, target_, &forced, &n), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(n, nullptr);
  EXPECT_TRUE(mentions("use_world_frame")) << last_message();
  mcon_map_options old = on;
  old.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, use_world_frame));
  mcon_map k = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &old, &k), MCON_OK) << last_message();
  const MapPtr unframed(k);
  EXPECT_EQ(info_of(k).frame_decided, 0u);
  // An info struct from before the field: frame_decided is not written.
  mcon_map_info short_info;
  mcon_map_info_init(&short_info);
  short_info.struct_size = static_cast<uint32_t>(offsetof(mcon_map_info, frame_decided));
  short_info.frame_decided = 7;
  ASSERT_EQ(mcon_map_get_info(m, &short_info), MCON_OK);
  EXPECT_EQ(short_info.frame_decided, 7u);
}

TEST_F(CapiMapArgs, WorldFrameAnchorIsCheckedAndDefaulted) {
  // The default comes from mcon_map_options_init; 0 turns the anchor off (a different map here);
  // negative or non-finite is refused naming the field; a caller compiled before the field gets
  // the default.
  mcon_map_options o;
  ASSERT_EQ(mcon_map_options_init(&o), MCON_OK);
  EXPECT_GT(o.world_frame_anchor, 0.0);
  auto phi_of = [&](const mcon_map_options& opts) {
    mcon_map m = nullptr;
    EXPECT_EQ(mcon_map_compute(source_, target_, &opts, &m), MCON_OK) << last_message();
    const MapPtr owned(m);
    std::vector<double> phi(2 * ns_);
    EXPECT_EQ(mcon_map_get_phi(m, phi.data(), phi.size()), MCON_OK);
    return phi;
  };
  mcon_map_options on = fast_options();
  on.use_world_frame = 1;
  const std::vector<double> anchored = phi_of(on);
  mcon_map_options off = on;
  off.world_frame_anchor = 0;
  EXPECT_NE(phi_of(off), anchored);
  mcon_map_options old = on;
  old.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, world_frame_anchor));
  old.world_frame_anchor = -3;  // beyond the caller's struct: not read
  EXPECT_EQ(phi_of(old), anchored);
  for (const double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    mcon_map_options b = on;
    b.world_frame_anchor = bad;
    mcon_map m = reinterpret_cast<mcon_map>(&m);
    EXPECT_EQ(mcon_map_compute(source_, target_, &b, &m), MCON_ERROR_INVALID_ARGUMENT) << bad;
    EXPECT_EQ(m, nullptr);
    EXPECT_TRUE(mentions("world_frame_anchor")) << last_message();
  }
}

TEST_F(CapiMapArgs, UpHintsAreCheckedAndOptIn) {
  mcon_map_options o;
  ASSERT_EQ(mcon_map_options_init(&o), MCON_OK);
  EXPECT_EQ(o.use_up_hints, 0u);
  mcon_map_options up = fast_options();
  up.use_up_hints = 1;
  const double y[3] = {0, 1, 0};
  std::copy(y, y + 3, up.source_up);
  std::copy(y, y + 3, up.target_up);
  mcon_map m = nullptr;
  ASSERT_EQ(mcon_map_compute(source_, target_, &up, &m), MCON_OK) << last_message();
  mcon_map_release(m);
  // Zero and non-finite (the core test covers a vector normal to its patch).
  const double inf = std::numeric_limits<double>::infinity();
  const double bad[3][3] = {{0, 0, 0}, {0, kNaN, 0}, {inf, 0, 0}};
  for (const auto& b : bad) {
    mcon_map_options x = up;
    std::copy(b, b + 3, x.source_up);
    mcon_map n = reinterpret_cast<mcon_map>(&n);
    EXPECT_EQ(mcon_map_compute(source_, target_, &x, &n), MCON_ERROR_INVALID_ARGUMENT) << b[0] << " " << b[1] << " " << b[2];
    if (n != nullptr && n != reinterpret_cast<mcon_map>(&n)) mcon_map_release(n);
    EXPECT_TRUE(mentions("source_up")) << last_message();
  }
  // A caller compiled before the fields: the garbage beyond its struct_size is not read.
  mcon_map_options old = fast_options();
  old.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, use_up_hints));
  old.use_up_hints = 1;
  old.source_up[0] = old.source_up[1] = old.source_up[2] = 0;
  mcon_map k = nullptr;
  EXPECT_EQ(mcon_map_compute(source_, target_, &old, &k), MCON_OK) << last_message();
  mcon_map_release(k);
}

// A disk from arrays whose triangles disagree is repaired to the majority (a disk has no inside:
// an all-reversed disk stays as given), the center stays the caller's point, and the patch info
// reports the repair.
TEST(CapiPatchFromArrays, InconsistentTrianglesFollowTheMajority) {
  ContextPtr ctx = make_context();
  const Arrays a = arrays_of(bumpy_disk(7, 0.0));
  Arrays b = a, all = a;
  size_t reversed = 0;
  for (size_t t = 1; t < b.triangle_count(); t += 3, ++reversed) std::swap(b.indices[3 * t + 1], b.indices[3 * t + 2]);
  for (size_t t = 0; t < all.triangle_count(); ++t) std::swap(all.indices[3 * t + 1], all.indices[3 * t + 2]);
  mcon_patch_frame f = center_frame();
  f.center_triangle = 1;  // one of the reversed triangles of b
  f.center_barycentric[0] = 0.2;
  f.center_barycentric[1] = 0.7;
  f.center_barycentric[2] = 0.1;
  mcon_patch pa = nullptr, pb = nullptr, pall = nullptr;
  mcon_mesh_desc d = desc_of(a);
  ASSERT_EQ(mcon_patch_create_from_arrays(ctx.get(), &d, &f, &pa), MCON_OK) << last_message();
  std::swap(f.center_barycentric[1], f.center_barycentric[2]);  // the same point in b's corner order
  d = desc_of(b);
  ASSERT_EQ(mcon_patch_create_from_arrays(ctx.get(), &d, &f, &pb), MCON_OK) << last_message();
  d = desc_of(all);
  ASSERT_EQ(mcon_patch_create_from_arrays(ctx.get(), &d, &f, &pall), MCON_OK) << last_message();
  mcon_patch_info ia, ib, iall;
  for (mcon_patch_info* i : {&ia, &ib, &iall}) ASSERT_EQ(mcon_patch_info_init(i), MCON_OK);
  ASSERT_EQ(mcon_patch_get_info(pa, &ia), MCON_OK);
  ASSERT_EQ(mcon_patch_get_info(pb, &ib), MCON_OK);
  ASSERT_EQ(mcon_patch_get_info(pall, &iall), MCON_OK);
  EXPECT_EQ(ia.host_reoriented_triangles, 0u);
  EXPECT_EQ(ib.host_reoriented_triangles, reversed);
  EXPECT_EQ(ib.reoriented_triangles, reversed);
  EXPECT_EQ(ib.host_inconsistent_components, 1u);
  EXPECT_EQ(iall.host_reoriented_triangles, 0u);  // consistent, so never turned
  for (int k = 0; k < 3; ++k) EXPECT_EQ(ia.center_barycentric[k], ib.center_barycentric[k]) << k;
  std::vector<uint32_t> ta(3 * ia.triangle_count), tb(3 * ib.triangle_count);
  ASSERT_EQ(mcon_patch_get_triangles(pa, ta.data(), ta.size()), MCON_OK);
  ASSERT_EQ(mcon_patch_get_triangles(pb, tb.data(), tb.size()), MCON_OK);
  EXPECT_EQ(ta, tb);
  for (mcon_patch p : {pa, pb, pall}) mcon_patch_release(p);
}
