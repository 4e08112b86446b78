// Argument checks of the patch and descriptor functions that need no extracted patch: NULL and
// wrong-type handles, NULL outputs, struct_size, every option out of its range, bad enums.
// (Capacity checks need a real patch: test_capi_patch.cpp.)
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "capi/capi_test_util.h"

using namespace capi_test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class CapiPatchArgs : public ::testing::Test {
 protected:
  void SetUp() override {
    ctx_ = make_context();
    mesh_ = make_mesh(ctx_.get(), arrays_of(mcon::test_meshes::make_grid(5)));  // 25 vertices, 32 triangles
    ASSERT_NE(mesh_, nullptr);
    ASSERT_EQ(mcon_patch_options_init(&options_), MCON_OK);
    options_.center_vertex = 12;
    options_.radius = 0.3;
  }

  // Extraction with `o` must fail before any work with `expected`, a message containing `text`,
  // and *out_patch set to NULL.
  void expect_rejected(const mcon_patch_options& o, mcon_status expected, const std::string& text) {
    mcon_patch p = reinterpret_cast<mcon_patch>(&options_);
    EXPECT_EQ(mcon_patch_extract(mesh_.get(), &o, &p), expected) << last_message();
    EXPECT_EQ(p, nullptr);
    EXPECT_NE(last_message().find(text), std::string::npos) << "\"" << last_message() << "\" lacks \"" << text << "\"";
  }

  ContextPtr ctx_;
  MeshPtr mesh_;
  mcon_patch_options options_{};
};

}  // namespace

TEST_F(CapiPatchArgs, OptionsInitDefaults) {
  mcon_patch_options o;
  std::memset(&o, 0x77, sizeof(o));
  ASSERT_EQ(mcon_patch_options_init(&o), MCON_OK);
  EXPECT_EQ(o.struct_size, sizeof(mcon_patch_options));
  EXPECT_EQ(o.center_vertex, MCON_INVALID_INDEX);
  EXPECT_EQ(o.center_triangle, MCON_INVALID_INDEX);
  for (double b : o.center_barycentric) EXPECT_DOUBLE_EQ(b, 1.0 / 3.0);
  EXPECT_EQ(o.radius, 0.0);
  EXPECT_EQ(o.flags, static_cast<uint32_t>(MCON_PATCH_FILL_HOLES));
  EXPECT_DOUBLE_EQ(o.snap_fraction, 0.2);
  EXPECT_EQ(o.progress, nullptr);
  EXPECT_EQ(o.progress_user_data, nullptr);
  EXPECT_EQ(mcon_patch_options_init(nullptr), MCON_ERROR_NULL_POINTER);
}

TEST_F(CapiPatchArgs, ExtractRejectsNullAndWrongHandles) {
  mcon_patch p = nullptr;
  EXPECT_EQ(mcon_patch_extract(nullptr, &options_, &p), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("mesh handle is NULL"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_extract(mesh_.get(), nullptr, &p), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("options"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_extract(mesh_.get(), &options_, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("out_patch"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_extract(reinterpret_cast<mcon_mesh>(ctx_.get()), &options_, &p), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("not a valid mesh"), std::string::npos) << last_message();
  Garbage g;
  EXPECT_EQ(mcon_patch_extract(reinterpret_cast<mcon_mesh>(&g), &options_, &p), MCON_ERROR_INVALID_ARGUMENT);
}

TEST_F(CapiPatchArgs, ExtractRejectsStructSizeSmallerThanFirstVersion) {
  for (uint32_t size : {0u, 4u, static_cast<uint32_t>(sizeof(mcon_patch_options) - 1)}) {
    mcon_patch_options o = options_;
    o.struct_size = size;
    expect_rejected(o, MCON_ERROR_STRUCT_SIZE, "mcon_patch_options.struct_size is " + std::to_string(size));
  }
}

TEST_F(CapiPatchArgs, ExtractRejectsBadCenter) {
  mcon_patch_options o = options_;
  o.center_vertex = 25;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "center_vertex 25 is out of range (the host mesh has 25 vertices)");
  o.center_vertex = MCON_INVALID_INDEX;
  o.center_triangle = MCON_INVALID_INDEX;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "no center");
  o.center_triangle = 32;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "center_triangle 32 is out of range (the host mesh has 32 triangles)");
  o.center_triangle = 5;
  o.center_barycentric[1] = kNaN;
  expect_rejected(o, MCON_ERROR_NON_FINITE, "center_barycentric[1] is not finite");
  o.center_barycentric[1] = kInf;
  expect_rejected(o, MCON_ERROR_NON_FINITE, "center_barycentric[1] is not finite");
  o.center_barycentric[0] = 1.2;
  o.center_barycentric[1] = -0.2;
  o.center_barycentric[2] = 0;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "is not a point of the triangle");
  o.center_barycentric[0] = 0.5;
  o.center_barycentric[1] = 0.6;
  o.center_barycentric[2] = 0;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "is not a point of the triangle");
}

TEST_F(CapiPatchArgs, ExtractRejectsBadRadiusFlagsAndSnap) {
  mcon_patch_options o = options_;
  o.radius = kNaN;
  expect_rejected(o, MCON_ERROR_NON_FINITE, "radius is not finite");
  o.radius = kInf;
  expect_rejected(o, MCON_ERROR_NON_FINITE, "radius is not finite");
  o.radius = 0;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "radius must be > 0");
  o.radius = -0.5;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "radius must be > 0 (got -0.5)");
  o = options_;
  o.flags = MCON_PATCH_FILL_HOLES | 4u;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "flags 5");
  o = options_;
  o.snap_fraction = 0.46;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "snap_fraction 0.46");
  o.snap_fraction = -0.01;
  expect_rejected(o, MCON_ERROR_INVALID_ARGUMENT, "snap_fraction -0.01");
  o.snap_fraction = kNaN;
  expect_rejected(o, MCON_ERROR_NON_FINITE, "snap_fraction is not finite");
}

TEST_F(CapiPatchArgs, RejectedExtractionIsLoggedToTheMeshContext) {
  int calls = 0;
  mcon_context_options co;
  ASSERT_EQ(mcon_context_options_init(&co), MCON_OK);
  co.log_user_data = &calls;
  co.log_callback = [](void* user, mcon_status status, const char*) {
    if (status == MCON_ERROR_INVALID_ARGUMENT) ++*static_cast<int*>(user);
  };
  mcon_context raw = nullptr;
  ASSERT_EQ(mcon_context_create(&co, &raw), MCON_OK);
  ContextPtr logged(raw);
  MeshPtr mesh = make_mesh(logged.get(), arrays_of(mcon::test_meshes::make_grid(4)));
  mcon_patch_options o = options_;
  o.radius = -1;
  mcon_patch p = nullptr;
  EXPECT_EQ(mcon_patch_extract(mesh.get(), &o, &p), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(calls, 1);
}

TEST_F(CapiPatchArgs, GettersRejectNullAndWrongHandles) {
  // A mesh handle cast as a patch handle is caught by the magic tag, as is a zeroed block.
  Garbage g;
  const mcon_patch wrong[] = {reinterpret_cast<mcon_patch>(mesh_.get()), reinterpret_cast<mcon_patch>(ctx_.get()),
                              reinterpret_cast<mcon_patch>(&g)};
  double d[64];
  uint32_t u[64] = {};
  mcon_patch_info info;
  ASSERT_EQ(mcon_patch_info_init(&info), MCON_OK);
  for (mcon_patch p : {static_cast<mcon_patch>(nullptr), wrong[0], wrong[1], wrong[2]}) {
    const mcon_status expected = p == nullptr ? MCON_ERROR_NULL_POINTER : MCON_ERROR_INVALID_ARGUMENT;
    EXPECT_EQ(mcon_patch_get_info(p, &info), expected);
    EXPECT_NE(last_message().find("patch handle"), std::string::npos) << last_message();
    EXPECT_EQ(mcon_patch_get_positions(p, d, 64), expected);
    EXPECT_EQ(mcon_patch_get_triangles(p, u, 64), expected);
    EXPECT_EQ(mcon_patch_get_uv(p, d, 64), expected);
    EXPECT_EQ(mcon_patch_get_host_vertices(p, u, u, d, 64), expected);
    EXPECT_EQ(mcon_patch_get_host_triangles(p, u, 64), expected);
    EXPECT_EQ(mcon_patch_compute_descriptors(p, MCON_DESCRIPTOR_MEAN_CURVATURE, d, 64), expected);
    EXPECT_NE(last_message().find("mcon_patch_compute_descriptors"), std::string::npos) << last_message();
    const mcon_surface_point corner{0, {1, 0, 0}};
    EXPECT_EQ(mcon_patch_compute_distance_from_point(p, &corner, d, 64), expected);
    EXPECT_EQ(mcon_patch_compute_distance_from_vertices(p, u, 1, d, 64), expected);
    EXPECT_EQ(mcon_patch_retain(p), expected);
  }
  EXPECT_EQ(mcon_patch_release(nullptr), MCON_OK);
  for (mcon_patch p : wrong) EXPECT_EQ(mcon_patch_release(p), MCON_ERROR_INVALID_ARGUMENT);
  // The objects behind the wrong handles are untouched.
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(mesh_.get(), &nv, &nt), MCON_OK);
  EXPECT_EQ(nv, 25u);
}

TEST_F(CapiPatchArgs, InfoInitAndDescriptorDimension) {
  mcon_patch_info info;
  std::memset(&info, 0x33, sizeof(info));
  ASSERT_EQ(mcon_patch_info_init(&info), MCON_OK);
  EXPECT_EQ(info.struct_size, sizeof(mcon_patch_info));
  EXPECT_EQ(info.vertex_count, 0u);
  EXPECT_EQ(mcon_patch_info_init(nullptr), MCON_ERROR_NULL_POINTER);

  uint32_t dim = 0;
  ASSERT_EQ(mcon_descriptor_get_dimension(MCON_DESCRIPTOR_CURV9, &dim), MCON_OK);
  EXPECT_EQ(dim, 9u);
  ASSERT_EQ(mcon_descriptor_get_dimension(MCON_DESCRIPTOR_MEAN_CURVATURE, &dim), MCON_OK);
  EXPECT_EQ(dim, 1u);
  EXPECT_EQ(mcon_descriptor_get_dimension(MCON_DESCRIPTOR_CURV9, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("out_dimension"), std::string::npos) << last_message();
  for (int bad : {0, 3}) {  // in range of the C++ enum; the C check passes wilder values
    dim = 77;
    EXPECT_EQ(mcon_descriptor_get_dimension(static_cast<mcon_descriptor>(bad), &dim), MCON_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_message().find("descriptor " + std::to_string(bad) + " is not an mcon_descriptor"),
              std::string::npos)
        << last_message();
    EXPECT_EQ(dim, 77u);
  }
}
