// libFuzzer target for the mesh readers (OBJ, OFF, PLY, plain and gzip) and the soup-to-mesh step
// of read_mesh (face selection, triangulation, compaction, orient_and_validate). The first input
// byte picks the format and whether the rest is stored as a `.gz` archive (the rest is then the
// hostile archive itself). Any input must either read or throw mcon::Error with a status the
// readers document (IO, UNSUPPORTED, the validation statuses of orient_and_validate, or
// INVALID_ARGUMENT for coordinates outside the supported range or a too small extent); a crash,
// a sanitizer report, another exception or status is a finding, and so is an accepted mesh that
// fails validate_mesh or whose vertex maps disagree with it.
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

#include "base/error.h"
#include "fuzz/fuzz_input_file.h"
#include "io/mesh_io.h"
#include "io/polygon_soup.h"

namespace {

// INVALID_ARGUMENT only for coordinates outside the supported range (mesh/mesh.h, kMaxCoordinate
// and kMinExtent; the message names "the supported range" or "the supported minimum"): with default
// options read_mesh has no other argument to reject.
bool documented(const mcon::Error& e) {
  switch (e.status()) {
    case MCON_ERROR_INVALID_ARGUMENT: return std::string_view(e.what()).find("supported ") != std::string_view::npos;
    case MCON_ERROR_IO:
    case MCON_ERROR_UNSUPPORTED:
    case MCON_ERROR_NON_FINITE:
    case MCON_ERROR_INDEX_OUT_OF_RANGE:
    case MCON_ERROR_REPEATED_INDEX:
    case MCON_ERROR_DEGENERATE_TRIANGLE:
    case MCON_ERROR_NON_MANIFOLD_EDGE:
    case MCON_ERROR_NON_MANIFOLD_VERTEX:
    case MCON_ERROR_ISOLATED_VERTEX:
    case MCON_ERROR_EMPTY_MESH:
    case MCON_ERROR_NON_ORIENTABLE: return true;
    default: return false;
  }
}

void check_loaded(const mcon::io::LoadedMesh& loaded) {
  try {
    mcon::validate_mesh(loaded.mesh);
  } catch (const mcon::Error& e) {
    mcon_fuzz::finding("an accepted mesh fails validate_mesh: ", e.what());
  }
  const int nv = loaded.mesh.num_vertices();
  if (static_cast<int>(loaded.mesh_to_file.size()) != nv) mcon_fuzz::finding("mesh_to_file has the wrong size");
  for (int v = 0; v < nv; ++v) {
    const int f = loaded.mesh_to_file[v];
    if (f < 0 || f >= static_cast<int>(loaded.file_to_mesh.size()) || loaded.file_to_mesh[f] != v)
      mcon_fuzz::finding("file_to_mesh and mesh_to_file disagree");
  }
  if (loaded.triangle_to_face.size() != loaded.mesh.triangles.size())
    mcon_fuzz::finding("triangle_to_face has the wrong size");
}

// The in-memory parsers on the same bytes: they must agree with the file path (plain files only).
void check_parser(int format, std::string_view text) {
  try {
    if (format == 0) mcon::io::parse_obj(text, "fuzz.obj");
    if (format == 1) mcon::io::parse_off(text, "fuzz.off");
    if (format == 2) mcon::io::parse_ply(text, "fuzz.ply");
  } catch (const mcon::Error& e) {
    if (e.status() != MCON_ERROR_IO && e.status() != MCON_ERROR_UNSUPPORTED)
      mcon_fuzz::finding("a parser threw an undocumented status: ", e.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kSuffixes[] = {".obj", ".off", ".ply"};
  const int format = data[0] % 3;
  const bool gz = (data[0] / 3) % 2 == 1;
  const std::string path = mcon_fuzz::write_input_file(data + 1, size - 1, std::string(kSuffixes[format]) + (gz ? ".gz" : ""));
  if (!gz) check_parser(format, std::string_view(reinterpret_cast<const char*>(data + 1), size - 1));
  mcon::io::MeshFileOptions options;
  options.max_bytes = 1u << 24;  // a hostile archive may inflate; 16 MB is plenty for fuzz inputs
  try {
    check_loaded(mcon::io::read_mesh(path, options));
  } catch (const mcon::Error& e) {
    if (!documented(e)) {
      std::fprintf(stderr, "unexpected status %d: %s\n", static_cast<int>(e.status()), e.what());
      std::abort();
    }
  }
  return 0;
}
