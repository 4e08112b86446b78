// The same through the header-only C++ wrapper.
#include <cstdio>
#include <vector>

#include <macrocon/macrocon.hpp>

int main() {
  try {
    macrocon::Context ctx;
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<uint32_t> tris = {0, 1, 2, 0, 2, 3};
    macrocon::Mesh mesh = macrocon::Mesh::from_arrays(ctx, xyz, tris);
    std::printf("macrocon C++ wrapper: %zu vertices: ok\n", mesh.vertex_count());
  } catch (const macrocon::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  macrocon::shutdown();
  return 0;
}
