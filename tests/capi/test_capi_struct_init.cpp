// Every mcon_*_init_sized writes exactly the caller's struct_size bytes: a struct from an older
// header (its first published size) is filled without a byte past its end, one from a newer header
// gets zeros beyond what this library knows, and sizes outside [first size, 4096] are refused.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "capi/capi_test_util.h"

using namespace capi_test;

namespace {

constexpr unsigned char kCanary = 0xA5;
constexpr std::size_t kSlack = 64;  // canary bytes after the caller's struct

struct InitCase {
  const char* name;
  std::size_t first_size;    // the struct's size before its first appended field
  std::size_t current_size;  // sizeof in this header
  std::function<mcon_status(void*, std::size_t)> init_sized;
  std::function<mcon_status(void*)> init;  // the header's inline *_init
};

template <typename T>
InitCase make_case(const char* name, std::size_t first_size, mcon_status (*sized)(T*, std::size_t),
                   mcon_status (*inline_init)(T*)) {
  return {name, first_size, sizeof(T), [sized](void* p, std::size_t n) { return sized(static_cast<T*>(p), n); },
          [inline_init](void* p) { return inline_init(static_cast<T*>(p)); }};
}

#define MCON_INIT_CASE(T, first) make_case<T>(#T, first, &T##_init_sized, &T##_init)

std::vector<InitCase> all_cases() {
  return {
      MCON_INIT_CASE(mcon_context_options, sizeof(mcon_context_options)),
      MCON_INIT_CASE(mcon_mesh_desc, offsetof(mcon_mesh_desc, index_format)),
      MCON_INIT_CASE(mcon_mesh_orientation_info, sizeof(mcon_mesh_orientation_info)),
      MCON_INIT_CASE(mcon_patch_options, sizeof(mcon_patch_options)),
      MCON_INIT_CASE(mcon_patch_info, offsetof(mcon_patch_info, host_reoriented_triangles)),
      MCON_INIT_CASE(mcon_patch_repair_info, sizeof(mcon_patch_repair_info)),
      MCON_INIT_CASE(mcon_library_entry_desc, offsetof(mcon_library_entry_desc, has_up)),
      MCON_INIT_CASE(mcon_library_info, sizeof(mcon_library_info)),
      MCON_INIT_CASE(mcon_retrieval_options, sizeof(mcon_retrieval_options)),
      MCON_INIT_CASE(mcon_library_entry_info, offsetof(mcon_library_entry_info, has_up)),
      MCON_INIT_CASE(mcon_patch_frame, sizeof(mcon_patch_frame)),
      MCON_INIT_CASE(mcon_map_options, offsetof(mcon_map_options, orientation)),
      MCON_INIT_CASE(mcon_map_info, offsetof(mcon_map_info, alignment_score_unreflected)),
      MCON_INIT_CASE(mcon_cross_field_options, sizeof(mcon_cross_field_options)),
      MCON_INIT_CASE(mcon_guide_cut_options, offsetof(mcon_guide_cut_options, fair_passes)),
      MCON_INIT_CASE(mcon_cut_mesh_info, offsetof(mcon_cut_mesh_info, faired_vertices)),
  };
}

std::uint32_t struct_size_of(const std::vector<unsigned char>& bytes) {
  std::uint32_t size;
  std::memcpy(&size, bytes.data(), sizeof size);
  return size;
}

// The current struct as the inline *_init fills it, for comparing prefixes.
std::vector<unsigned char> current_defaults(const InitCase& c) {
  std::vector<unsigned char> full(c.current_size, 0);
  EXPECT_EQ(c.init(full.data()), MCON_OK) << c.name;
  return full;
}

}  // namespace

TEST(CapiStructInit, TheInlineInitPassesTheHeadersSize) {
  for (const InitCase& c : all_cases()) {
    std::vector<unsigned char> bytes(c.current_size + kSlack, kCanary);
    ASSERT_EQ(c.init(bytes.data()), MCON_OK) << c.name;
    EXPECT_EQ(struct_size_of(bytes), c.current_size) << c.name;
    for (std::size_t i = c.current_size; i < bytes.size(); ++i) ASSERT_EQ(bytes[i], kCanary) << c.name << " byte " << i;
  }
}

TEST(CapiStructInit, AnOlderHeadersStructGetsItsFieldsAndNotOneByteMore) {
  for (const InitCase& c : all_cases()) {
    const std::vector<unsigned char> full = current_defaults(c);
    std::vector<unsigned char> bytes(c.first_size + kSlack, kCanary);
    ASSERT_EQ(c.init_sized(bytes.data(), c.first_size), MCON_OK) << c.name << ": " << last_message();
    EXPECT_EQ(struct_size_of(bytes), c.first_size) << c.name;
    EXPECT_EQ(std::memcmp(bytes.data() + 4, full.data() + 4, c.first_size - 4), 0) << c.name << ": other defaults";
    for (std::size_t i = c.first_size; i < bytes.size(); ++i)
      ASSERT_EQ(bytes[i], kCanary) << c.name << " wrote byte " << i << " past a " << c.first_size << "-byte struct";
  }
}

TEST(CapiStructInit, ANewerHeadersStructGetsZerosBeyondWhatThisLibraryKnows) {
  for (const InitCase& c : all_cases()) {
    const std::vector<unsigned char> full = current_defaults(c);
    const std::size_t newer = c.current_size + 24;
    std::vector<unsigned char> bytes(newer + kSlack, kCanary);
    ASSERT_EQ(c.init_sized(bytes.data(), newer), MCON_OK) << c.name << ": " << last_message();
    EXPECT_EQ(struct_size_of(bytes), newer) << c.name;
    EXPECT_EQ(std::memcmp(bytes.data() + 4, full.data() + 4, c.current_size - 4), 0) << c.name;
    for (std::size_t i = c.current_size; i < newer; ++i) ASSERT_EQ(bytes[i], 0) << c.name << " byte " << i;
    for (std::size_t i = newer; i < bytes.size(); ++i) ASSERT_EQ(bytes[i], kCanary) << c.name << " byte " << i;
  }
}

TEST(CapiStructInit, SizesOutsideTheKnownRangeAndNullAreRefusedWithoutWriting) {
  for (const InitCase& c : all_cases()) {
    for (std::size_t size : {std::size_t{0}, std::size_t{4}, c.first_size - 1, std::size_t{4097}, std::size_t{1} << 40}) {
      std::vector<unsigned char> bytes(c.current_size + kSlack, kCanary);
      EXPECT_EQ(c.init_sized(bytes.data(), size), MCON_ERROR_STRUCT_SIZE) << c.name << " size " << size;
      EXPECT_NE(last_message().find("struct_size " + std::to_string(size)), std::string::npos) << last_message();
      EXPECT_NE(last_message().find("pass sizeof"), std::string::npos) << last_message();
      for (unsigned char b : bytes) ASSERT_EQ(b, kCanary) << c.name << " size " << size;
    }
    EXPECT_EQ(c.init_sized(nullptr, c.current_size), MCON_ERROR_NULL_POINTER) << c.name;
    EXPECT_EQ(c.init(nullptr), MCON_ERROR_NULL_POINTER) << c.name;
  }
}
