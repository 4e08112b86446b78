#include <gtest/gtest.h>

#include <set>
#include <string>

#include "base/error.h"
#include "retrieval/retrieval_config.h"
#include "retrieval/retrieval_descriptors.h"
#include "test_meshes.h"

using namespace mcon;

// The registry is the one place a built-in descriptor is declared: names and C API codes are
// unique, the default is in it, and every row computes the number of values it declares.
TEST(RetrievalDescriptors, RegistryRowsAreUniqueAndComputeTheirDimension) {
  const TriMesh disk = test_meshes::make_disk(6);
  std::set<std::string> names;
  std::set<std::uint32_t> codes;
  for (const BuiltinDescriptor& d : builtin_descriptors()) {
    EXPECT_TRUE(names.insert(d.name).second) << d.name;
    EXPECT_TRUE(codes.insert(d.code).second) << d.code;
    EXPECT_NE(d.code, static_cast<std::uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CUSTOM));
    EXPECT_FALSE(is_custom_descriptor(d.name));
    EXPECT_EQ(find_builtin_descriptor(d.name), &d);
    EXPECT_EQ(find_builtin_descriptor_code(d.code), &d);
    EXPECT_EQ(builtin_descriptor_values(d.name), d.values);
    const Eigen::MatrixXd values = compute_retrieval_descriptor(disk, d.name);
    EXPECT_EQ(values.rows(), disk.num_vertices()) << d.name;
    EXPECT_EQ(values.cols(), static_cast<Eigen::Index>(d.values)) << d.name;
  }
  EXPECT_TRUE(names.count(kDescriptorCurv9));
  EXPECT_EQ(names.size(), 3u);  // curv9, hks, wks: a new row must also get its enum value and docs
}

TEST(RetrievalDescriptors, UnknownNamesAreRejectedWithTheKnownOnes) {
  EXPECT_EQ(find_builtin_descriptor("bogus"), nullptr);
  EXPECT_EQ(find_builtin_descriptor_code(2), nullptr);
  EXPECT_EQ(builtin_descriptor_values("custom:mine"), 0u);
  EXPECT_EQ(builtin_descriptor_names(), "curv9, hks or wks");
  try {
    compute_retrieval_descriptor(test_meshes::make_disk(3), "bogus");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), MCON_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(e.what()).find("curv9, hks or wks"), std::string::npos) << e.what();
  }
}
