// The benchmark's patch classes (shared/bench/*-landmarks.json) and their vertex lists on the base
// mesh (*-patches.json): a class is a geodesic disk, center vertex + radius, on a model whose
// random instances share the base connectivity (format: shared/bench/README.md).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mcon::tools {

enum class BenchSide { None, Left, Right };

const char* bench_side_name(BenchSide side);  // "none", "left", "right"

struct BenchClass {
  std::string name;         // e.g. "eye_l"
  std::string part;         // the body part without the side suffix, e.g. "eye"
  BenchSide side = BenchSide::None;
  int center_vertex = -1;   // 0-based vertex of the model's surface
  double radius = 0.0;      // geodesic radius on the base mesh, model units
  bool fill_holes = false;  // the patch rule's pocket-filling step is needed
  int approx_vertices = 0;  // vertex count of the patch on the base mesh
  bool alternative = false; // listed under `alternatives` (not recommended)
};

struct BenchSpec {
  std::string mesh;          // path relative to the shared folder
  std::string patches_file;  // path relative to the shared folder
  int surface_vertices = 0;  // the surface = the first surface_faces faces of the OBJ ...
  int surface_faces = 0;     // ... and its vertices 0 .. surface_vertices - 1
  std::vector<BenchClass> classes;       // file order
  std::vector<BenchClass> alternatives;  // file order

  // Looks in classes, then alternatives; throws mcon::Error(MCON_ERROR_NOT_FOUND).
  const BenchClass& find(std::string_view name) const;
};

// Throws mcon::Error (MCON_ERROR_IO for unreadable files, MCON_ERROR_INVALID_ARGUMENT for bad
// content, naming the file and the class).
BenchSpec read_bench_spec(const std::string& landmarks_path);

struct BenchPatch {
  std::string name;
  std::vector<int> vertices;  // sorted, unique
  bool alternative = false;
};

struct BenchPatches {
  std::string mesh;
  std::vector<BenchPatch> patches;  // classes then alternatives, file order

  const BenchPatch& find(std::string_view name) const;  // mcon::Error(MCON_ERROR_NOT_FOUND)
};

BenchPatches read_bench_patches(const std::string& patches_path);

// Both files of one model, cross-checked: same mesh, one patch per class, indices inside the
// surface and the center inside its patch.
struct BenchModelData {
  BenchSpec spec;
  BenchPatches patches;
};

// model = "makehuman" or "ict"; reads <shared_dir>/bench/<model>-landmarks.json and the patches file
// it names.
BenchModelData read_bench_model(const std::string& shared_dir, const std::string& model);

}  // namespace mcon::tools
