// Read times of the shared meshes through mcon::io::read_mesh (gunzip + parse + triangulate +
// compact + validate), with the gunzip, parse and validate_mesh shares measured separately.
// Prints one JSON object.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/file_suffix.h"
#include "io/mesh_io.h"
#include "io/polygon_soup.h"

namespace {

template <typename F>
double median_ms(int runs, F&& f) {
  std::vector<double> times;
  for (int r = 0; r < runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

struct Case {
  const char* file;
  long face_end;
  const char* group;
};

}  // namespace

int main() {
  const std::string shared = MACROCON_SHARED_DIR;
  const Case cases[] = {{"makehuman/base.obj.gz", -1, ""},
                        {"makehuman/base.obj.gz", 13378, ""},
                        {"makehuman/base.obj.gz", -1, "body"},
                        {"ict-facekit/generic_neutral_mesh.obj.gz", 14034, ""},
                        {"cgal/cgal-hand.off.gz", -1, ""},
                        {"cgal/cgal-head.off.gz", -1, ""},
                        {"cgal/cgal-man.off.gz", -1, ""},
                        {"cgal/cgal-mannequin-devil.off.gz", -1, ""}};
  const int runs = 7;
  std::printf("{\n  \"benchmark\": \"mesh_io\",\n  \"runs\": %d,\n  \"reads\": [\n", runs);
  bool first = true;
  for (const Case& c : cases) {
    const std::string path = shared + "/meshes/" + c.file;
    mcon::io::MeshFileOptions options;
    options.face_end = c.face_end;
    options.obj_group = c.group;
    mcon::io::LoadedMesh loaded;
    const double read_ms = median_ms(runs, [&] { loaded = mcon::io::read_mesh(path, options); });
    std::string text;
    const double gunzip_ms = median_ms(runs, [&] { text = mcon::io::read_file_maybe_gz(path); });
    const bool obj = mcon::io::ends_with_ignoring_case(path, ".obj.gz");
    const double parse_ms = median_ms(runs, [&] {
      const mcon::io::PolygonSoup soup = obj ? mcon::io::parse_obj(text, path) : mcon::io::parse_off(text, path);
      if (soup.num_faces() == 0) std::abort();
    });
    const double validate_ms = median_ms(runs, [&] { mcon::validate_mesh(loaded.mesh); });
    std::printf("%s    {\"file\": \"%s\", \"face_end\": %ld, \"group\": \"%s\", \"bytes\": %zu, \"vertices\": %d, "
                "\"triangles\": %d, \"read_ms\": %.2f, \"gunzip_ms\": %.2f, \"parse_ms\": %.2f, "
                "\"validate_ms\": %.2f}",
                first ? "" : ",\n", c.file, c.face_end, c.group, text.size(), loaded.mesh.num_vertices(),
                loaded.mesh.num_triangles(), read_ms, gunzip_ms, parse_ms, validate_ms);
    first = false;
  }
  std::printf("\n  ]\n}\n");
  return 0;
}
