// Constraint library container: bit-exact round trips, hostile files (truncated, corrupted,
// forged), atomic saves that never damage the previous file, and add/remove/merge semantics.
#include <gtest/gtest.h>

#include <dirent.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <set>
#include <thread>

#include "base/atomic_file.h"
#include "base/error.h"
#include "library/library_file.h"
#include "library_samples.h"
#include "macrocon_library_generated.h"

using namespace mcon;
using test_samples::sample_config;
using test_samples::sample_entry;
using test_samples::sample_library;
using test_samples::tiny_library;

namespace {

using Bytes = std::vector<std::uint8_t>;

struct Outcome {
  mcon_status status = MCON_OK;
  std::string message;
};

Outcome try_load(const Bytes& bytes) {
  try {
    load_library_from_buffer(bytes.data(), bytes.size());
  } catch (const Error& e) {
    return {e.status(), e.what()};
  }
  return {};
}

template <typename F>
Outcome outcome_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return {e.status(), e.what()};
  }
  return {};
}

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
template <typename T, std::size_t N>
bool same_bits(const std::array<T, N>& a, const std::array<T, N>& b) {
  return std::memcmp(a.data(), b.data(), N * sizeof(T)) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

bool same_point(const SurfacePoint& a, const SurfacePoint& b) {
  return a.triangle == b.triangle && same_bits(a.barycentric, b.barycentric);
}

bool same_polylines(const std::vector<ConstraintPolyline>& a, const std::vector<ConstraintPolyline>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].closed != b[i].closed || a[i].points.size() != b[i].points.size()) return false;
    for (std::size_t k = 0; k < a[i].points.size(); ++k)
      if (!same_point(a[i].points[k], b[i].points[k])) return false;
  }
  return true;
}

// Every field, floating-point values compared bit for bit (so -0.0 != 0.0).
void expect_identical(const ConstraintLibrary& a, const ConstraintLibrary& b) {
  EXPECT_EQ(a.name(), b.name());
  EXPECT_EQ(a.description(), b.description());
  const RetrievalConfig &ca = a.retrieval(), &cb = b.retrieval();
  EXPECT_EQ(ca.descriptor, cb.descriptor);
  EXPECT_EQ(ca.dimension, cb.dimension);
  EXPECT_TRUE(same_bits(ca.normalization_mean, cb.normalization_mean));
  EXPECT_TRUE(same_bits(ca.normalization_scale, cb.normalization_scale));
  EXPECT_EQ(ca.vocabulary_size, cb.vocabulary_size);
  EXPECT_TRUE(same_bits(ca.vocabulary, cb.vocabulary));
  EXPECT_TRUE(same_bits(ca.sigma_bof, cb.sigma_bof));
  EXPECT_EQ(ca.rings, cb.rings);
  EXPECT_EQ(ca.seed, cb.seed);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("entry " + std::to_string(i));
    const MacroConstraint &x = a.entries()[i], &y = b.entries()[i];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.class_label, y.class_label);
    EXPECT_EQ(x.tags, y.tags);
    EXPECT_EQ(x.author, y.author);
    EXPECT_EQ(x.licence, y.licence);
    EXPECT_TRUE(same_bits(x.positions, y.positions));
    EXPECT_EQ(x.triangles, y.triangles);
    EXPECT_TRUE(same_point(x.center, y.center));
    EXPECT_TRUE(same_bits(x.source_scale, y.source_scale));
    EXPECT_TRUE(same_bits(x.source_origin, y.source_origin));
    EXPECT_TRUE(same_polylines(x.guides, y.guides));
    EXPECT_TRUE(same_polylines(x.features, y.features));
    ASSERT_EQ(x.singularities.size(), y.singularities.size());
    for (std::size_t k = 0; k < x.singularities.size(); ++k) {
      EXPECT_TRUE(same_point(x.singularities[k].location, y.singularities[k].location));
      EXPECT_EQ(x.singularities[k].index_quarters, y.singularities[k].index_quarters);
    }
    ASSERT_EQ(x.fields.size(), y.fields.size());
    for (std::size_t k = 0; k < x.fields.size(); ++k) {
      EXPECT_EQ(x.fields[k].name, y.fields[k].name);
      EXPECT_EQ(x.fields[k].kind, y.fields[k].kind);
      EXPECT_EQ(x.fields[k].dimension, y.fields[k].dimension);
      EXPECT_TRUE(same_bits(x.fields[k].values, y.fields[k].values));
      EXPECT_EQ(x.fields[k].labels, y.fields[k].labels);
    }
    EXPECT_TRUE(same_bits(x.descriptors, y.descriptors));
    EXPECT_TRUE(same_bits(x.histogram, y.histogram));
  }
}

// A scratch directory removed (recursively, one level) at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = ::testing::TempDir() + "mcon_library_XXXXXX";
    path_ = ::mkdtemp(tmpl.data()) ? tmpl : "";
    EXPECT_FALSE(path_.empty());
  }
  ~TempDir() {
    ::chmod(path_.c_str(), 0700);
    for (const std::string& name : list()) {
      const std::string p = path_ + "/" + name;
      if (::rmdir(p.c_str()) != 0) ::unlink(p.c_str());
    }
    ::rmdir(path_.c_str());
  }
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::set<std::string> list() const {
    std::set<std::string> names;
    if (DIR* d = ::opendir(path_.c_str())) {
      while (dirent* e = ::readdir(d))
        if (std::strcmp(e->d_name, ".") != 0 && std::strcmp(e->d_name, "..") != 0) names.insert(e->d_name);
      ::closedir(d);
    }
    return names;
  }

 private:
  std::string path_;
};

Bytes read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// Runs `body` in a child process and returns its exit code (for process-wide changes such as
// resource limits or dropping root, which must not leak into the rest of the test run).
int run_in_child(const std::function<int()>& body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(body());
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// --- Forging files with the generated object API -------------------------------------------

Bytes pack(const fb::LibraryT& lib, const char* identifier = kLibraryFileIdentifier) {
  flatbuffers::FlatBufferBuilder b;
  b.Finish(fb::Library::Pack(b, &lib), identifier);
  Bytes bytes(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize());
  // A forged file carries a matching checksum, so that it reaches the check under test.
  if (lib.content_checksum != 0 && std::string(identifier) == kLibraryFileIdentifier) seal_library_buffer(bytes);
  return bytes;
}

// The sample library as mutable object-API tables, changed by `edit`, packed again.
Bytes forge(const std::function<void(fb::LibraryT&)>& edit, const char* identifier = kLibraryFileIdentifier) {
  const Bytes good = serialize_library(sample_library());
  std::unique_ptr<fb::LibraryT> lib(fb::GetLibrary(good.data())->UnPack());
  edit(*lib);
  return pack(*lib, identifier);
}

Outcome load_forged(const std::function<void(fb::LibraryT&)>& edit) { return try_load(forge(edit)); }

void expect_rejected(const Outcome& o, mcon_status status, const std::string& message_part) {
  EXPECT_EQ(o.status, status) << o.message;
  EXPECT_NE(o.message.find(message_part), std::string::npos) << "message: " << o.message;
}

}  // namespace

// --- Round trips -------------------------------------------------------------------------------

TEST(ConstraintLibrary, RoundTripIsBitExactAndDeterministic) {
  const ConstraintLibrary lib = sample_library();
  const Bytes bytes = serialize_library(lib);
  ASSERT_GT(bytes.size(), kLibraryMinBytes);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()) + 4, 4), "MCLB");
  EXPECT_TRUE(fb::LibraryBufferHasIdentifier(bytes.data()));

  const ConstraintLibrary back = load_library_from_buffer(bytes.data(), bytes.size());
  expect_identical(lib, back);
  EXPECT_EQ(serialize_library(back), bytes);  // same library, same bytes
  // The sample really contains the values that catch lossy round trips.
  EXPECT_TRUE(std::signbit(back.entries()[0].descriptors[0]));
  EXPECT_TRUE(std::signbit(back.entries()[0].source_origin[1]));
  EXPECT_EQ(back.entries()[0].descriptors[7], std::numeric_limits<float>::denorm_min());
  EXPECT_EQ(back.entries()[0].fields.size(), 5u);
  EXPECT_EQ(back.entries()[0].tags.size(), 3u);
}

TEST(ConstraintLibrary, EmptyAndVocabularyLessLibrariesRoundTrip) {
  ConstraintLibrary empty;  // default config: no vocabulary yet, no descriptors
  const Bytes bytes = serialize_library(empty);
  const ConstraintLibrary back = load_library_from_buffer(bytes.data(), bytes.size());
  expect_identical(empty, back);

  ConstraintLibrary unconfigured;
  RetrievalConfig none;
  unconfigured.add_entry(sample_entry(none, 0, 1, true));
  const Bytes b2 = serialize_library(unconfigured);
  expect_identical(unconfigured, load_library_from_buffer(b2.data(), b2.size()));
}

TEST(ConstraintLibrary, LoadsFromAnUnalignedBuffer) {
  const Bytes bytes = serialize_library(sample_library());
  Bytes shifted(bytes.size() + 1);
  std::memcpy(shifted.data() + 1, bytes.data(), bytes.size());
  expect_identical(sample_library(), load_library_from_buffer(shifted.data() + 1, bytes.size()));
}

TEST(ConstraintLibrary, SaveAndLoadFileRoundTrip) {
  TempDir dir;
  const std::string path = dir.file("faces.mcl");
  const ConstraintLibrary lib = sample_library();
  save_library_atomic(lib, path);
  expect_identical(lib, load_library_from_file(path));
  EXPECT_EQ(read_bytes(path), serialize_library(lib));
  EXPECT_EQ(dir.list(), std::set<std::string>{"faces.mcl"});  // no temporary file left
}

// --- Hostile buffers -------------------------------------------------------------------------

TEST(ConstraintLibraryHostile, EveryTruncationIsRejectedOrLoadsTheSameLibrary) {
  const ConstraintLibrary lib = sample_library();
  const Bytes bytes = serialize_library(lib);
  for (std::size_t len = 0; len < bytes.size(); ++len) {
    const Bytes cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(len));
    try {
      const ConstraintLibrary back = load_library_from_buffer(cut.data(), cut.size());
      // Only trailing alignment padding may be cut without loss.
      ASSERT_GT(len + 8, bytes.size()) << "a truncation to " << len << " bytes loaded";
      expect_identical(lib, back);
    } catch (const Error& e) {
      ASSERT_EQ(e.status(), MCON_ERROR_INVALID_LIBRARY) << "length " << len << ": " << e.what();
    }
  }
}

TEST(ConstraintLibraryHostile, EverySingleByteCorruptionIsRejectedOrConsistent) {
  const Bytes good = serialize_library(tiny_library());
  std::size_t rejected = 0, loaded = 0;
  for (std::size_t pos = 0; pos < good.size(); ++pos) {
    for (std::uint8_t flip : {std::uint8_t{0x01}, std::uint8_t{0xff}}) {  // low bit; every bit
      Bytes bad = good;
      bad[pos] ^= flip;
      try {
        const ConstraintLibrary lib = load_library_from_buffer(bad.data(), bad.size());
        // Accepted corruptions (a float payload, padding) must still give a valid, stable library.
        const Bytes again = serialize_library(lib);
        ASSERT_EQ(serialize_library(load_library_from_buffer(again.data(), again.size())), again);
        ++loaded;
      } catch (const Error& e) {
        ASSERT_TRUE(e.status() == MCON_ERROR_INVALID_LIBRARY || e.status() == MCON_ERROR_UNSUPPORTED)
            << "byte " << pos << " ^ " << int(flip) << ": " << status_name(e.status()) << " " << e.what();
        ASSERT_FALSE(std::string(e.what()).empty());
        ++rejected;
      }
      ASSERT_TRUE(pos >= 8 || loaded == 0) << "a corrupt root offset or file identifier loaded (byte " << pos << ")";
    }
  }
  // Offsets, lengths, indices, kinds and barycentrics are checked; float payloads and string bytes
  // may change without making the library invalid (about half of this file).
  EXPECT_GT(3 * rejected, 2 * good.size()) << rejected << " rejected, " << loaded << " loaded of " << 2 * good.size();
}

TEST(ConstraintLibraryHostile, TooSmallTooLargeNullOrForeignBuffers) {
  expect_rejected(try_load(Bytes{}), MCON_ERROR_INVALID_LIBRARY, "0 bytes");
  expect_rejected(try_load(Bytes(15, 0)), MCON_ERROR_INVALID_LIBRARY, "15 bytes");
  expect_rejected(try_load(Bytes(64, 0)), MCON_ERROR_INVALID_LIBRARY, "not a Macrocon constraint library");
  const Outcome null = outcome_of([] { load_library_from_buffer(nullptr, 100); });
  EXPECT_EQ(null.status, MCON_ERROR_NULL_POINTER);
  const Outcome huge = outcome_of([] { load_library_from_buffer("", kLibraryMaxBytes + 1); });
  expect_rejected(huge, MCON_ERROR_INVALID_LIBRARY, "2147483647");
}

TEST(ConstraintLibraryHostile, WrongIdentifierAndFormatVersions) {
  expect_rejected(try_load(forge([](fb::LibraryT&) {}, "PNG!")), MCON_ERROR_INVALID_LIBRARY, "'PNG!'");
  EXPECT_EQ(try_load(forge([](fb::LibraryT&) {})).status, MCON_OK);  // the forging itself is sound
  const std::uint32_t next = kLibraryFormatVersion + 1;
  const std::string newer = "format version " + std::to_string(next) + " is newer";
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.format_version = next; }), MCON_ERROR_UNSUPPORTED, newer);
  // A newer format is UNSUPPORTED even when the rest of its layout does not verify here.
  Bytes future = forge([&](fb::LibraryT& l) { l.format_version = next; });
  future.resize(future.size() - 64);
  expect_rejected(try_load(future), MCON_ERROR_UNSUPPORTED, newer);
  expect_rejected(load_forged([](fb::LibraryT& l) { l.format_version = 0; }), MCON_ERROR_INVALID_LIBRARY,
                  "no format version");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval.reset(); }), MCON_ERROR_INVALID_LIBRARY,
                  "no retrieval config");
}

// Format 2: a content checksum over the whole buffer. Before it, 1,560 of 2,000 random one-bit
// flips of the starter library loaded with changed values; now every flip is rejected, and those
// that every other check would accept name the checksum.
TEST(ConstraintLibraryHostile, EveryBitFlipIsRejected) {
  const Bytes good = serialize_library(sample_library());
  const ConstraintLibrary loaded = load_library_from_buffer(good.data(), good.size());
  EXPECT_EQ(loaded.origin().format_version, kLibraryFormatVersion);
  EXPECT_TRUE(loaded.origin().checksum_verified);
  std::uint64_t state = 12345;
  int by_checksum = 0;
  const int flips = 2000;
  for (int k = 0; k < flips; ++k) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const std::size_t bit = static_cast<std::size_t>((state >> 17) % (8 * good.size()));
    Bytes bad = good;
    bad[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
    const Outcome o = try_load(bad);
    ASSERT_TRUE(o.status == MCON_ERROR_INVALID_LIBRARY || o.status == MCON_ERROR_UNSUPPORTED)
        << "bit " << bit << " flipped: status " << o.status << " " << o.message;
    if (o.message.find("content checksum mismatch") != std::string::npos) ++by_checksum;
  }
  EXPECT_GT(by_checksum, flips / 2);  // most flips change values no other check can tell apart
}

TEST(ConstraintLibraryHostile, FormatOneLoadsWithoutChecksumFormatTwoNeedsOne) {
  const Bytes old = forge([](fb::LibraryT& l) {
    l.format_version = 1;
    l.content_checksum = 0;  // not written: format 1 has no such field
  });
  const ConstraintLibrary lib = load_library_from_buffer(old.data(), old.size());
  EXPECT_EQ(lib.origin().format_version, 1u);
  EXPECT_FALSE(lib.origin().checksum_verified);
  EXPECT_EQ(lib.size(), sample_library().size());
  expect_rejected(load_forged([](fb::LibraryT& l) { l.content_checksum = 0; }), MCON_ERROR_INVALID_LIBRARY,
                  "has no content checksum");
  // A format-2 file whose content changed after it was sealed.
  Bytes changed = serialize_library(sample_library());
  std::unique_ptr<fb::LibraryT> edit(fb::GetLibrary(changed.data())->UnPack());
  edit->name = "renamed";
  flatbuffers::FlatBufferBuilder b;
  b.Finish(fb::Library::Pack(b, edit.get()), kLibraryFileIdentifier);
  expect_rejected(try_load(Bytes(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize())),
                  MCON_ERROR_INVALID_LIBRARY, "content checksum mismatch");
}

TEST(ConstraintLibrary, AnUpDirectionIsStoredOnlyWhenGiven) {
  // The sample's entries have none: their tables carry no up field at all (the bytes of files
  // written before entries could store one).
  const Bytes plain = serialize_library(sample_library());
  for (const auto* e : *fb::GetLibrary(plain.data())->entries()) EXPECT_EQ(e->up(), nullptr);
  const Outcome none = try_load(plain);
  ASSERT_EQ(none.status, MCON_OK) << none.message;
  // One entry with an up: it loads back exactly, the others still have none.
  const Outcome with = load_forged([](fb::LibraryT& l) { l.entries[1]->up = {0.0, -2.0, 1e-3}; });
  ASSERT_EQ(with.status, MCON_OK) << with.message;
  const Bytes forged = forge([](fb::LibraryT& l) { l.entries[1]->up = {0.0, -2.0, 1e-3}; });
  const ConstraintLibrary back = load_library_from_buffer(forged.data(), forged.size());
  ASSERT_TRUE(back.entries()[1].up.has_value());
  EXPECT_EQ(*back.entries()[1].up, (std::array<double, 3>{{0.0, -2.0, 1e-3}}));
  EXPECT_FALSE(back.entries()[0].up.has_value());
  const Bytes again = serialize_library(back);
  EXPECT_EQ(serialize_library(load_library_from_buffer(again.data(), again.size())), again);  // same library, same bytes
}

TEST(ConstraintLibraryHostile, AnUpDirectionMustBeThreeFiniteNumbersNotAllZero) {
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->up = {0.0, 1.0}; }), MCON_ERROR_INVALID_LIBRARY,
                  "entry 0 'nose_07': up");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->up = {0.0, 0.0, 0.0}; }),
                  MCON_ERROR_INVALID_LIBRARY, "up is the zero vector");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->up = {0.0, std::nan(""), 1.0}; }),
                  MCON_ERROR_INVALID_LIBRARY, "up is not finite");
}

TEST(ConstraintLibraryHostile, OutOfRangeIndices) {
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->triangles[37] = 900; }),
                  MCON_ERROR_INVALID_LIBRARY, "entry 0 'nose_07': triangle 12 uses vertex 900 of 19");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->center_face = 24; }), MCON_ERROR_INVALID_LIBRARY,
                  "center lies on triangle 24 of 24");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->guides[0]->faces[1] = 1000000; }),
                  MCON_ERROR_INVALID_LIBRARY, "guide 0 point 1 lies on triangle 1000000 of 24");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->features[0]->faces[2] = 99; }),
                  MCON_ERROR_INVALID_LIBRARY, "feature 0 point 2 lies on triangle 99");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[1]->id = 7; }), MCON_ERROR_INVALID_LIBRARY,
                  "entry 1 'eye_corner_01': id 7 is already used by entry 0");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[1]->id = 0; }), MCON_ERROR_INVALID_LIBRARY,
                  "id 0 is reserved");
  auto sing_face = [](fb::LibraryT& l) -> std::uint32_t& { return l.entries[0]->singularities[1]->face; };
  expect_rejected(load_forged([&](fb::LibraryT& l) { sing_face(l) = 24; }), MCON_ERROR_INVALID_LIBRARY,
                  "singularity 1 lies on triangle 24 of 24");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->singularities[0]->index_quarters = 0; }),
                  MCON_ERROR_INVALID_LIBRARY, "index_quarters 0");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->singularities[0]->index_quarters = 4; }),
                  MCON_ERROR_INVALID_LIBRARY, "index_quarters 4");
}

TEST(ConstraintLibraryHostile, NonFiniteValues) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[0]->positions[5] = nan; }),
                  MCON_ERROR_INVALID_LIBRARY, "vertex 1 has a non-finite coordinate");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[1]->descriptors[3] = nan; }),
                  MCON_ERROR_INVALID_LIBRARY, "entry 1 'eye_corner_01': descriptors value 3 is not finite");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[0]->histogram[2] = nan; }),
                  MCON_ERROR_INVALID_LIBRARY, "histogram value 2");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[0]->histogram[2] = -1.0f; }),
                  MCON_ERROR_INVALID_LIBRARY, "histogram value 2");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[0]->fields[1]->values[4] = nan; }),
                  MCON_ERROR_INVALID_LIBRARY, "field 1 'direction' value 4 is not finite");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.retrieval->vocabulary[1] = inf; }),
                  MCON_ERROR_INVALID_LIBRARY, "retrieval config: vocabulary value 1 is not finite");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.retrieval->normalization_scale[0] = 0.0; }),
                  MCON_ERROR_INVALID_LIBRARY, "normalization_scale value 0 is not positive");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.retrieval->sigma_bof = -inf; }), MCON_ERROR_INVALID_LIBRARY,
                  "sigma_bof");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[0]->source_scale = 0; }), MCON_ERROR_INVALID_LIBRARY,
                  "source_scale");
  expect_rejected(load_forged([&](fb::LibraryT& l) { l.entries[0]->source_origin[2] = inf; }),
                  MCON_ERROR_INVALID_LIBRARY, "source_origin");
}

TEST(ConstraintLibraryHostile, InconsistentLengths) {
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->positions.pop_back(); }),
                  MCON_ERROR_INVALID_LIBRARY, "positions has 56 values, not a multiple of 3");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->triangles.pop_back(); }),
                  MCON_ERROR_INVALID_LIBRARY, "not a multiple of 3");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->descriptors.push_back(0); }),
                  MCON_ERROR_INVALID_LIBRARY, "descriptors has 39 values, expected 19 vertices * dimension 2 = 38");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[1]->histogram.clear(); }), MCON_ERROR_INVALID_LIBRARY,
                  "histogram has 0 values, expected vocabulary_size 3 * rings 2 = 6");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->vocabulary.pop_back(); }),
                  MCON_ERROR_INVALID_LIBRARY, "vocabulary has 5 values, expected vocabulary_size 3 * dimension 2 = 6");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->normalization_mean.push_back(1); }),
                  MCON_ERROR_INVALID_LIBRARY, "normalization_mean has 3 values");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->rings = 0; }), MCON_ERROR_INVALID_LIBRARY,
                  "rings is 0");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->rings = 100000; }), MCON_ERROR_INVALID_LIBRARY,
                  "rings is 100000");
  // A huge k * d must not overflow into a match.
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->vocabulary_size = 0x80000003u; }),
                  MCON_ERROR_INVALID_LIBRARY, "vocabulary has 6 values");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[0]->values.pop_back(); }),
                  MCON_ERROR_INVALID_LIBRARY, "field 0 'sizing' values has 18 values, expected 19 vertices * 1 = 19");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[3]->dimension = 3; }),
                  MCON_ERROR_INVALID_LIBRARY, "field 3 'uv' has dimension 3, its kind needs 2");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[4]->values = {1.0f}; }),
                  MCON_ERROR_INVALID_LIBRARY, "integer label field but has float values");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[2]->name = "sizing"; }),
                  MCON_ERROR_INVALID_LIBRARY, "repeats a field name");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[0]->kind = fb::FieldKind::Unset; }),
                  MCON_ERROR_INVALID_LIBRARY, "unknown kind 0");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[0]->kind = static_cast<fb::FieldKind>(77); }),
                  MCON_ERROR_INVALID_LIBRARY, "unknown kind 77");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->guides[0]->barycentrics.pop_back(); }),
                  MCON_ERROR_INVALID_LIBRARY, "guide 0 has 3 faces but 8 barycentric weights");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->guides[0]->faces.resize(1); l.entries[0]->guides[0]->barycentrics.resize(3); }),
                  MCON_ERROR_INVALID_LIBRARY, "guide 0 has 1 points, needs at least 2");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->center_barycentric.pop_back(); }),
                  MCON_ERROR_INVALID_LIBRARY, "center barycentric has 2 values, expected 3");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->source_origin.clear(); }),
                  MCON_ERROR_INVALID_LIBRARY, "source_origin has 0 values, expected 3");
}

namespace {

// The library's descriptor dimension changed to `d` everywhere it shows (normalization,
// vocabulary, every entry's descriptors), so only the descriptor's own dimension can disagree.
void set_dimension(fb::LibraryT& l, std::uint32_t d) {
  fb::RetrievalConfigT& c = *l.retrieval;
  c.dimension = d;
  c.normalization_mean.assign(d, 0.5);
  c.normalization_scale.assign(d, 2.0);
  c.vocabulary.assign(static_cast<std::size_t>(c.vocabulary_size) * d, 0.25);
  for (auto& e : l.entries) e->descriptors.assign(e->positions.size() / 3 * d, 0.125f);
}

}  // namespace

TEST(ConstraintLibraryHostile, UnknownDescriptorNamesAndWrongDimensions) {
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->descriptor = "bogus"; }), MCON_ERROR_INVALID_LIBRARY,
                  "retrieval config: unknown descriptor 'bogus' (this build knows curv9, hks or wks, and custom:<name>)");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->descriptor = "custom:"; }),
                  MCON_ERROR_INVALID_LIBRARY, "unknown descriptor 'custom:'");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->descriptor = "CURV9"; }), MCON_ERROR_INVALID_LIBRARY,
                  "unknown descriptor 'CURV9'");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.retrieval->descriptor = std::string("curv9\0x", 7); }),
                  MCON_ERROR_INVALID_LIBRARY, "descriptor 'curv9\\x00x' contains a NUL byte at offset 5");
  // A built-in descriptor fixes the dimension: curv9 is 9 values per vertex, hks and wks 100.
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    l.retrieval->descriptor = "curv9";
                    set_dimension(l, 5);
                  }),
                  MCON_ERROR_INVALID_LIBRARY,
                  "retrieval config: descriptor 'curv9' has 9 values per vertex, the library declares dimension 5");
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    l.retrieval->descriptor = "hks";
                    set_dimension(l, 9);
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "descriptor 'hks' has 100 values per vertex, the library declares dimension 9");
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    l.retrieval->descriptor = "wks";
                    set_dimension(l, 9);
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "descriptor 'wks' has 100 values per vertex");
  // The same forgeries with the right dimension load; custom descriptors have any dimension.
  EXPECT_EQ(load_forged([](fb::LibraryT& l) {
              l.retrieval->descriptor = "curv9";
              set_dimension(l, 9);
            }).status,
            MCON_OK);
  EXPECT_EQ(load_forged([](fb::LibraryT& l) {
              l.retrieval->descriptor = "custom:my descriptor";
              set_dimension(l, 5);
            }).status,
            MCON_OK);
  // Callers building a library in memory get the same checks.
  RetrievalConfig c = sample_config();
  c.descriptor = "hks";
  expect_rejected(outcome_of([&] { ConstraintLibrary lib(c); }), MCON_ERROR_INVALID_ARGUMENT,
                  "descriptor 'hks' has 100 values per vertex, the library declares dimension 2");
  c.descriptor = "bogus";
  expect_rejected(outcome_of([&] { ConstraintLibrary lib(c); }), MCON_ERROR_INVALID_ARGUMENT,
                  "unknown descriptor 'bogus'");
}

TEST(ConstraintLibraryHostile, EveryStringIsUtf8WithoutNul) {
  const std::string bad_utf8 = "ab\xc3(";  // a lead byte without its continuation
  const std::string nul("ab\0cd", 5);
  using Edit = std::function<void(fb::LibraryT&, const std::string&)>;
  const std::vector<std::pair<Edit, std::string>> places = {
      {[](fb::LibraryT& l, const std::string& s) { l.name = s; }, "library name"},
      {[](fb::LibraryT& l, const std::string& s) { l.description = s; }, "library description"},
      {[](fb::LibraryT& l, const std::string& s) { l.retrieval->descriptor = "custom:" + s; }, "retrieval config: descriptor"},
      {[](fb::LibraryT& l, const std::string& s) { l.entries[1]->name = s; }, "entry 1 'ab"},
      {[](fb::LibraryT& l, const std::string& s) { l.entries[0]->class_label = s; }, "entry 0 'nose_07': class_label"},
      {[](fb::LibraryT& l, const std::string& s) { l.entries[0]->tags[1]->text = s; }, "entry 0 'nose_07': tag 1"},
      {[](fb::LibraryT& l, const std::string& s) { l.entries[0]->author = s; }, "entry 0 'nose_07': author"},
      {[](fb::LibraryT& l, const std::string& s) { l.entries[0]->licence = s; }, "entry 0 'nose_07': licence"},
      {[](fb::LibraryT& l, const std::string& s) { l.entries[0]->fields[2]->name = s; }, "entry 0 'nose_07': field 2 'ab"},
  };
  for (const auto& [edit, where] : places) {
    SCOPED_TRACE(where);
    expect_rejected(load_forged([&](fb::LibraryT& l) { edit(l, bad_utf8); }), MCON_ERROR_INVALID_LIBRARY, where);
    expect_rejected(load_forged([&](fb::LibraryT& l) { edit(l, bad_utf8); }), MCON_ERROR_INVALID_LIBRARY,
                    "is not valid UTF-8 (byte 0xc3 at offset");
    expect_rejected(load_forged([&](fb::LibraryT& l) { edit(l, nul); }), MCON_ERROR_INVALID_LIBRARY,
                    "contains a NUL byte at offset");
    EXPECT_EQ(load_forged([&](fb::LibraryT& l) { edit(l, "Gr\xc3\xb6\xc3\x9f" "e \xe2\x82\xac"); }).status, MCON_OK);
  }
  // Field names that differ only after a NUL would be the same name to every C caller.
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->fields[1]->name = std::string("sizing\0x", 8); }),
                  MCON_ERROR_INVALID_LIBRARY, "field 1 'sizing\\x00x' name contains a NUL byte at offset 6");
  // Messages show such names escaped, never raw.
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[1]->name = "eye\x1b[2J\xff"; }),
                  MCON_ERROR_INVALID_LIBRARY, "entry 1 'eye\\x1b[2J\\xff': name is not valid UTF-8");
  // add_entry runs the same checks for callers.
  ConstraintLibrary lib(sample_config());
  MacroConstraint e = sample_entry(lib.retrieval(), 0, 1, true);
  e.author = "\xff";
  expect_rejected(outcome_of([&] { lib.add_entry(e); }), MCON_ERROR_INVALID_ARGUMENT,
                  "author is not valid UTF-8 (byte 0xff at offset 0)");
  EXPECT_EQ(lib.size(), 0u);
}

TEST(ConstraintLibraryHostile, BadBarycentrics) {
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->center_barycentric = {0.5, 0.5, 0.5}; }),
                  MCON_ERROR_INVALID_LIBRARY, "center has barycentric weights summing to 1.5");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->center_barycentric = {1.5, -0.5, 0.0}; }),
                  MCON_ERROR_INVALID_LIBRARY, "center has barycentric weight 0 = 1.5");
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    l.entries[0]->guides[0]->barycentrics[4] = std::numeric_limits<double>::quiet_NaN();
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "guide 0 point 1 has barycentric weight 1");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[0]->singularities[0]->barycentric = {-0.1, 0.6, 0.5}; }),
                  MCON_ERROR_INVALID_LIBRARY, "singularity 0 has barycentric weight 0");
  // Round-off within the tolerance is accepted.
  EXPECT_EQ(load_forged([](fb::LibraryT& l) { l.entries[0]->center_barycentric = {1 + 1e-9, -1e-9, 0}; }).status,
            MCON_OK);
}

TEST(ConstraintLibraryHostile, InvalidPatchMeshes) {
  // Two vertices of triangle 0 made equal: the mesh validator's error, reported as INVALID_LIBRARY.
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    auto& t = l.entries[1]->triangles;
                    t[1] = t[0];
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "MCON_ERROR_REPEATED_INDEX");
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    auto& p = l.entries[1]->positions;  // vertex 1 onto vertex 0: zero-area triangles
                    p[3] = p[0], p[4] = p[1], p[5] = p[2];
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "MCON_ERROR_DEGENERATE_TRIANGLE");
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    auto& p = l.entries[1]->positions;  // an isolated extra vertex
                    p.insert(p.end(), {5, 5, 5});
                    auto& d = l.entries[1]->descriptors;
                    d.insert(d.end(), {0, 0});
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "MCON_ERROR_ISOLATED_VERTEX");
  expect_rejected(load_forged([](fb::LibraryT& l) { l.entries[1]->triangles.clear(); }), MCON_ERROR_INVALID_LIBRARY,
                  "patch mesh is empty");
  // A closed octahedron is a valid mesh but not a disk.
  expect_rejected(load_forged([](fb::LibraryT& l) {
                    auto& e = *l.entries[1];
                    const TriMesh sphere = test_meshes::make_icosphere(0);
                    MacroConstraint tmp;
                    set_entry_mesh(tmp, sphere);
                    e.positions = tmp.positions;
                    e.triangles = tmp.triangles;
                    e.descriptors.assign(2 * sphere.positions.size(), 0.5f);
                  }),
                  MCON_ERROR_INVALID_LIBRARY, "not a topological disk");
}

namespace {

// A library whose entries vector holds `copies` offsets to one packed entry.
Bytes entry_bomb(const fb::EntryT& entry, const fb::RetrievalConfigT& config, std::size_t copies) {
  flatbuffers::FlatBufferBuilder b;
  const auto one = fb::Entry::Pack(b, &entry);
  const auto entries = b.CreateVector(std::vector<flatbuffers::Offset<fb::Entry>>(copies, one));
  const auto packed_config = fb::RetrievalConfig::Pack(b, &config);
  fb::LibraryBuilder lb(b);
  lb.add_format_version(1);
  lb.add_retrieval(packed_config);
  lb.add_entries(entries);
  fb::FinishLibraryBuffer(b, lb.Finish());
  return Bytes(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize());
}

}  // namespace

TEST(ConstraintLibraryHostile, AliasedEntriesAreRejectedWithoutBlowingUp) {
  // 200,000 offsets at one entry: under 1 MB of file that, read naively, is 200,000 entries to
  // verify, copy and validate.
  const Bytes good = serialize_library(sample_library());
  std::unique_ptr<fb::LibraryT> lib(fb::GetLibrary(good.data())->UnPack());
  const auto start = std::chrono::steady_clock::now();
  // The full entry has 12 sub-tables: the Verifier's table limit (size / 4) stops it.
  expect_rejected(try_load(entry_bomb(*lib->entries[0], *lib->retrieval, 200000)), MCON_ERROR_INVALID_LIBRARY,
                  "table count exceeds the limits");
  // The minimal entry is a single table: it passes the Verifier, and the read budget stops the
  // loader at the second copy (the offsets alone use up nearly all of the file's bytes).
  expect_rejected(try_load(entry_bomb(*lib->entries[1], *lib->retrieval, 200000)), MCON_ERROR_INVALID_LIBRARY,
                  "same data more than once");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
}

TEST(ConstraintLibraryHostile, AliasedVectorsExceedTheReadBudget) {
  // 30,000 singularity offsets pointing at one singularity table: valid values, but the loader would
  // copy 32 bytes for every 4 in the file. Only the read budget notices.
  const Bytes good = serialize_library(tiny_library());
  std::unique_ptr<fb::LibraryT> lib(fb::GetLibrary(good.data())->UnPack());
  const fb::EntryT& e = *lib->entries[0];
  flatbuffers::FlatBufferBuilder b;
  const double w[3] = {0.5, 0.25, 0.25};
  const auto one = fb::CreateSingularity(b, 0, b.CreateVector(w, 3), 1);
  const auto singularities = b.CreateVector(std::vector<flatbuffers::Offset<fb::Singularity>>(30000, one));
  const auto name = b.CreateString(e.name);
  const auto positions = b.CreateVector(e.positions);
  const auto triangles = b.CreateVector(e.triangles);
  const auto center = b.CreateVector(e.center_barycentric);
  const auto origin = b.CreateVector(e.source_origin);
  const auto descriptors = b.CreateVector(e.descriptors);
  const auto histogram = b.CreateVector(e.histogram);
  const auto entry = fb::CreateEntry(b, e.id, name, 0, 0, 0, 0, positions, triangles, e.center_face, center,
                                     e.source_scale, origin, 0, 0, singularities, 0, descriptors, histogram);
  const auto entries = b.CreateVector(&entry, 1);
  const auto config = fb::RetrievalConfig::Pack(b, lib->retrieval.get());
  fb::LibraryBuilder lb(b);
  lb.add_format_version(1);
  lb.add_retrieval(config);
  lb.add_entries(entries);
  fb::FinishLibraryBuffer(b, lb.Finish());
  const Bytes forged(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize());
  expect_rejected(try_load(forged), MCON_ERROR_INVALID_LIBRARY, "same data more than once");
}

// --- Files -------------------------------------------------------------------------------------

TEST(ConstraintLibraryFile, MissingDirectoryEmptyAndHugeFiles) {
  TempDir dir;
  EXPECT_EQ(outcome_of([&] { load_library_from_file(dir.file("missing.mcl")); }).status, MCON_ERROR_IO);
  EXPECT_EQ(outcome_of([&] { load_library_from_file(dir.path()); }).status, MCON_ERROR_IO);
  write_bytes(dir.file("empty.mcl"), {});
  expect_rejected(outcome_of([&] { load_library_from_file(dir.file("empty.mcl")); }), MCON_ERROR_INVALID_LIBRARY,
                  "has 0 bytes");
  // A sparse 2 GiB file: rejected by its size before anything is mapped or read.
  const std::string huge = dir.file("huge.mcl");
  const int fd = ::open(huge.c_str(), O_WRONLY | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, off_t{1} << 31), 0);
  ::close(fd);
  expect_rejected(outcome_of([&] { load_library_from_file(huge); }), MCON_ERROR_INVALID_LIBRARY, "2147483648 bytes");
  // A corrupt file names itself in the message.
  Bytes bad = serialize_library(sample_library());
  bad[bad.size() / 2] ^= 0xff;
  bad.resize(bad.size() - 100);
  write_bytes(dir.file("bad.mcl"), bad);
  expect_rejected(outcome_of([&] { load_library_from_file(dir.file("bad.mcl")); }), MCON_ERROR_INVALID_LIBRARY,
                  "bad.mcl");
}

TEST(ConstraintLibraryFile, RewritingTheFileWhileItLoadsNeverCrashes) {
  // A writer truncating, refilling and flipping bytes of the file in place while it is loaded
  // over and over: each load must succeed or fail with a status, never die of a signal (a
  // memory-mapped file that shrinks under its reader raises SIGBUS). In a child, so a crash is
  // one failed test rather than the end of the run.
  TempDir dir;
  const std::string path = dir.file("busy.mcl");
  ConstraintLibrary lib(sample_config());
  for (int i = 0; i < 24; ++i) lib.add_entry(sample_entry(lib.retrieval(), 0, 6, true, "e" + std::to_string(i)));
  const Bytes good = serialize_library(lib);
  ASSERT_GT(good.size(), 16u * 4096);  // many pages: truncations cut whole pages off
  write_bytes(path, good);
  const int code = run_in_child([&] {
    std::atomic<bool> stop{false};
    std::atomic<long> cycles{0};
    std::thread writer([&] {
      const int fd = ::open(path.c_str(), O_WRONLY);
      if (fd < 0) return;
      std::uint32_t x = 12345;
      while (!stop.load()) {
        x = x * 1664525u + 1013904223u;
        const std::size_t cut = x % good.size(), pos = (x >> 7) % good.size();
        const std::uint8_t flipped = static_cast<std::uint8_t>(good[pos] ^ 0xff);
        bool ok = ::ftruncate(fd, static_cast<off_t>(cut)) == 0;
        ok = ok && ::pwrite(fd, good.data() + cut, good.size() - cut, static_cast<off_t>(cut)) >= 0;
        ok = ok && ::pwrite(fd, &flipped, 1, static_cast<off_t>(pos)) == 1;
        ok = ok && ::pwrite(fd, &good[pos], 1, static_cast<off_t>(pos)) == 1;
        ok = ok && ::ftruncate(fd, 0) == 0 && ::pwrite(fd, good.data(), good.size(), 0) >= 0;
        if (!ok) break;
        ++cycles;
        std::this_thread::sleep_for(std::chrono::microseconds(200));  // intact for a while: some loads succeed
      }
      ::close(fd);
    });
    long loaded = 0, refused = 0, other = 0;
    const auto start = std::chrono::steady_clock::now();
    while (loaded + refused + other < 4000 && std::chrono::steady_clock::now() - start < std::chrono::seconds(3)) {
      try {
        load_library_from_file(path);
        ++loaded;
      } catch (const Error& e) {
        const mcon_status s = e.status();
        (s == MCON_ERROR_INVALID_LIBRARY || s == MCON_ERROR_IO || s == MCON_ERROR_UNSUPPORTED ? refused : other)++;
      }
    }
    stop.store(true);
    writer.join();
    std::fprintf(stderr, "%ld loads succeeded, %ld refused, %ld other errors; %ld writer cycles\n", loaded, refused,
                 other, cycles.load());
    if (other != 0) return 20;
    if (cycles.load() == 0) return 21;  // the writer never ran: nothing was tested
    return refused > 0 ? 0 : 22;        // no load saw a torn file: nothing was tested
  });
  EXPECT_EQ(code, 0) << "exit code 128 + N: a load died of signal N";
}

// --- Atomic save -------------------------------------------------------------------------------

TEST(ConstraintLibrarySave, OverwriteKeepsPermissionsAndLeavesNoTemporaryFile) {
  TempDir dir;
  const std::string path = dir.file("lib.mcl");
  save_library_atomic(tiny_library(), path);
  ASSERT_EQ(::chmod(path.c_str(), 0640), 0);
  save_library_atomic(sample_library(), path);
  expect_identical(sample_library(), load_library_from_file(path));
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
  EXPECT_EQ(dir.list(), std::set<std::string>{"lib.mcl"});
}

TEST(ConstraintLibrarySave, FollowsASymlinkAndKeepsIt) {
  TempDir dir;
  save_library_atomic(tiny_library(), dir.file("real.mcl"));
  ASSERT_EQ(::symlink("real.mcl", dir.file("link.mcl").c_str()), 0);
  save_library_atomic(sample_library(), dir.file("link.mcl"));
  struct stat st {};
  ASSERT_EQ(::lstat(dir.file("link.mcl").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  expect_identical(sample_library(), load_library_from_file(dir.file("real.mcl")));
}

TEST(ConstraintLibrarySave, ReadOnlyDirectoryFailsWithIoAndKeepsTheOldFile) {
  TempDir dir;
  const std::string path = dir.file("lib.mcl");
  save_library_atomic(tiny_library(), path);
  const Bytes before = read_bytes(path);
  ASSERT_EQ(::chmod(dir.path().c_str(), 0555), 0);
  // In a child: root ignores permission bits, so a root test run drops to 'nobody' first.
  const int code = run_in_child([&] {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) return 10;
    const Outcome o = outcome_of([&] { save_library_atomic(sample_library(), path); });
    if (o.status != MCON_ERROR_IO) return 11;
    return o.message.find("temporary file") != std::string::npos ? 0 : 12;
  });
  EXPECT_EQ(code, 0);
  ASSERT_EQ(::chmod(dir.path().c_str(), 0700), 0);
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_EQ(dir.list(), std::set<std::string>{"lib.mcl"});
}

TEST(ConstraintLibrarySave, UnreadableDirectoryFailsBeforeTheFileIsReplaced) {
  // A directory its writer may write but not read (0333): syncing the rename needs the directory
  // open for reading, and that must fail before the rename, so the old file stays.
  TempDir dir;
  const std::string path = dir.file("lib.mcl");
  save_library_atomic(tiny_library(), path);
  const Bytes before = read_bytes(path);
  ASSERT_EQ(::chmod(dir.path().c_str(), 0333), 0);
  // In a child: root ignores permission bits, so a root test run drops to 'nobody' first.
  const int code = run_in_child([&] {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) return 10;
    const Outcome o = outcome_of([&] { save_library_atomic(sample_library(), path); });
    std::fprintf(stderr, "%s\n", o.message.c_str());
    if (o.status != MCON_ERROR_IO) return 11;
    return o.message.find("nothing was replaced") != std::string::npos ? 0 : 12;
  });
  EXPECT_EQ(code, 0);
  ASSERT_EQ(::chmod(dir.path().c_str(), 0700), 0);
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_EQ(dir.list(), std::set<std::string>{"lib.mcl"});  // the temporary file was removed
}

TEST(ConstraintLibrarySave, RemovesTemporariesOfDeadWritersOnly) {
  TempDir dir;
  const std::string path = dir.file("lib.mcl");
  save_library_atomic(tiny_library(), path);
  // A writer that died during a save (its pid reaped) and one still running (a sleeping child).
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ASSERT_GT(dead, 0);
  ASSERT_EQ(::waitpid(dead, nullptr, 0), dead);
  const pid_t alive = ::fork();
  if (alive == 0) {
    ::pause();
    ::_exit(0);
  }
  ASSERT_GT(alive, 0);
  const std::string stale = temporary_file_stem(path, dead) + "0";
  const std::string live = temporary_file_stem(path, alive) + "3";
  // The same pid written on another host (a directory shared over NFS): not ours to judge.
  std::string foreign = temporary_file_stem(path, dead) + "1";
  const std::size_t tag = foreign.rfind(".tmp.") + 5;
  foreign[tag] = foreign[tag] == '0' ? '1' : '0';
  const std::string other_file = temporary_file_stem(dir.file("other.mcl"), dead) + "0";
  const std::string unrelated = dir.file(".lib.mcl.tmp.notes");
  for (const std::string& p : {stale, live, foreign, other_file, unrelated}) write_bytes(p, {1, 2, 3});
  save_library_atomic(sample_library(), path);
  ::kill(alive, SIGKILL);
  ::waitpid(alive, nullptr, 0);
  auto name = [](const std::string& p) { return p.substr(p.find_last_of('/') + 1); };
  EXPECT_EQ(dir.list(), (std::set<std::string>{"lib.mcl", name(live), name(foreign), name(other_file), name(unrelated)}));
  expect_identical(sample_library(), load_library_from_file(path));
}

TEST(ConstraintLibrarySave, FailedWriteMidwayKeepsTheOldFileAndRemovesTheTemporary) {
  TempDir dir;
  const std::string path = dir.file("lib.mcl");
  save_library_atomic(tiny_library(), path);
  const Bytes before = read_bytes(path);
  const std::size_t new_size = serialize_library(sample_library()).size();
  ASSERT_GT(new_size, before.size() + 1000);
  // A file size limit between the old and the new size: the write of the new library fails
  // part-way (EFBIG), as on a full disk.
  const int code = run_in_child([&] {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlim_t limit = before.size() + 512;
    const rlimit rl{limit, limit};
    if (::setrlimit(RLIMIT_FSIZE, &rl) != 0) return 10;
    const Outcome o = outcome_of([&] { save_library_atomic(sample_library(), path); });
    return o.status == MCON_ERROR_IO ? 0 : 11;
  });
  EXPECT_EQ(code, 0);
  EXPECT_EQ(read_bytes(path), before);
  EXPECT_EQ(dir.list(), std::set<std::string>{"lib.mcl"});
}

TEST(ConstraintLibrarySave, UnwritableTargetsFailWithIo) {
  TempDir dir;
  ASSERT_EQ(::mkdir(dir.file("sub").c_str(), 0755), 0);
  const Outcome is_dir = outcome_of([&] { save_library_atomic(tiny_library(), dir.file("sub")); });
  expect_rejected(is_dir, MCON_ERROR_IO, "not a regular file");
  const Outcome no_dir = outcome_of([&] { save_library_atomic(tiny_library(), dir.file("missing/lib.mcl")); });
  expect_rejected(no_dir, MCON_ERROR_IO, "temporary file");
  EXPECT_EQ(outcome_of([&] { save_library_atomic(tiny_library(), ""); }).status, MCON_ERROR_IO);
  EXPECT_EQ(dir.list(), std::set<std::string>{"sub"});
}

// --- Operations ----------------------------------------------------------------------------------

TEST(ConstraintLibraryOps, AddAssignsIdsAndRejectsDuplicatesAndInvalidEntries) {
  ConstraintLibrary lib(sample_config());
  EXPECT_EQ(lib.add_entry(sample_entry(lib.retrieval(), 0, 1, false)), 1u);
  EXPECT_EQ(lib.add_entry(sample_entry(lib.retrieval(), 40, 1, false)), 40u);
  EXPECT_EQ(lib.add_entry(sample_entry(lib.retrieval(), 0, 1, false)), 41u);  // largest + 1
  expect_rejected(outcome_of([&] { lib.add_entry(sample_entry(lib.retrieval(), 40, 1, false)); }),
                  MCON_ERROR_INVALID_ARGUMENT, "id 40 is already used");

  MacroConstraint bad = sample_entry(lib.retrieval(), 0, 2, true);
  bad.triangles[5] = 1000;
  expect_rejected(outcome_of([&] { lib.add_entry(bad); }), MCON_ERROR_INVALID_ARGUMENT, "uses vertex 1000 of 19");
  MacroConstraint wrong_config = sample_entry(lib.retrieval(), 0, 1, false);
  wrong_config.histogram.pop_back();
  expect_rejected(outcome_of([&] { lib.add_entry(wrong_config); }), MCON_ERROR_INVALID_ARGUMENT, "histogram has 5");
  EXPECT_EQ(lib.size(), 3u);  // failures changed nothing
  ASSERT_NE(lib.find_entry(41), nullptr);
  EXPECT_EQ(lib.find_entry(41)->id, 41u);
  EXPECT_EQ(lib.find_entry(2), nullptr);
  EXPECT_EQ(lib.add_entry(sample_entry(lib.retrieval(), 0, 1, false)), 42u);
}

TEST(ConstraintLibraryOps, ConstructorValidatesConfigAndEntries) {
  RetrievalConfig c = sample_config();
  c.normalization_scale.pop_back();
  expect_rejected(outcome_of([&] { ConstraintLibrary lib(c); }), MCON_ERROR_INVALID_ARGUMENT, "normalization_scale");
  std::vector<MacroConstraint> twice{sample_entry(sample_config(), 5, 1, false),
                                     sample_entry(sample_config(), 5, 1, false, "other")};
  expect_rejected(outcome_of([&] { ConstraintLibrary lib(sample_config(), twice); }), MCON_ERROR_INVALID_ARGUMENT,
                  "entry 1 'other': id 5 is already used by entry 0");
}

TEST(ConstraintLibraryOps, RemoveKeepsOrderAndReportsMissingIds) {
  ConstraintLibrary lib(sample_config());
  for (int i = 0; i < 4; ++i) lib.add_entry(sample_entry(lib.retrieval(), 0, 1, false, "e" + std::to_string(i)));
  lib.remove_entry(2);
  ASSERT_EQ(lib.size(), 3u);
  EXPECT_EQ(lib.entries()[0].id, 1u);
  EXPECT_EQ(lib.entries()[1].id, 3u);
  EXPECT_EQ(lib.entries()[2].id, 4u);
  EXPECT_EQ(lib.find_entry(2), nullptr);
  EXPECT_EQ(lib.find_entry(4)->name, "e3");  // lookups follow the shifted positions
  expect_rejected(outcome_of([&] { lib.remove_entry(2); }), MCON_ERROR_NOT_FOUND, "no entry with id 2");
  const Bytes bytes = serialize_library(lib);
  expect_identical(lib, load_library_from_buffer(bytes.data(), bytes.size()));
}

TEST(ConstraintLibraryOps, MergeRenumbersCollidingIdsAndRequiresTheSameConfig) {
  ConstraintLibrary a(sample_config()), b(sample_config());
  a.add_entry(sample_entry(a.retrieval(), 1, 1, false, "a1"));
  a.add_entry(sample_entry(a.retrieval(), 5, 1, false, "a5"));
  b.add_entry(sample_entry(b.retrieval(), 5, 2, true, "b5"));
  b.add_entry(sample_entry(b.retrieval(), 2, 1, false, "b2"));
  b.add_entry(sample_entry(b.retrieval(), 1, 1, false, "b1"));
  const auto changes = a.merge(b);
  ASSERT_EQ(a.size(), 5u);
  ASSERT_EQ(changes.size(), 2u);
  EXPECT_EQ(changes[0].old_id, 5u);
  EXPECT_EQ(changes[0].new_id, 6u);
  EXPECT_EQ(changes[1].old_id, 1u);
  EXPECT_EQ(changes[1].new_id, 7u);
  EXPECT_EQ(a.find_entry(6)->name, "b5");
  EXPECT_EQ(a.find_entry(2)->name, "b2");
  EXPECT_EQ(a.find_entry(7)->name, "b1");
  EXPECT_EQ(a.find_entry(5)->name, "a5");
  EXPECT_EQ(b.size(), 3u);  // the source is unchanged

  // Merging a library into itself doubles it with fresh ids.
  ConstraintLibrary self = sample_library();
  const auto self_changes = self.merge(self);
  EXPECT_EQ(self.size(), 4u);
  EXPECT_EQ(self_changes.size(), 2u);
  const Bytes bytes = serialize_library(self);
  expect_identical(self, load_library_from_buffer(bytes.data(), bytes.size()));

  RetrievalConfig other_config = sample_config();
  other_config.vocabulary[0] += 1e-9;
  ConstraintLibrary c(other_config);
  c.add_entry(sample_entry(c.retrieval(), 0, 1, false));
  expect_rejected(outcome_of([&] { a.merge(c); }), MCON_ERROR_INVALID_ARGUMENT, "different retrieval configs");
  EXPECT_EQ(a.size(), 5u);
}
