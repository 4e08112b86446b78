#include <gtest/gtest.h>

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include "base/error.h"
#include "io/mesh_io.h"
#include "mesh/mesh.h"
#include "mesh/mesh_topology.h"
#include "test_meshes.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;
using namespace mcon::io;
namespace fs = std::filesystem;

namespace {

class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("macrocon_mesh_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write_text(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    // A fresh file, not a truncated one: ext4 flushes truncate-and-rewrite on close, which made
    // the many-files tests take seconds.
    fs::remove(p);
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }
  // Independent of the library's writer: plain zlib.
  std::string write_gz(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    gzFile f = gzopen(p.c_str(), "wb");
    EXPECT_NE(f, nullptr);
    EXPECT_EQ(gzwrite(f, content.data(), static_cast<unsigned>(content.size())), static_cast<int>(content.size()));
    EXPECT_EQ(gzclose(f), Z_OK);
    return p;
  }

  fs::path dir_;
};

std::string read_bytes(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

mcon_status read_status(const std::string& p, const MeshFileOptions& options = {}, std::string* message = nullptr) {
  return status_of([&] { read_mesh(p, options); }, message);
}

std::vector<int> iota_vector(int n) {
  std::vector<int> v(n);
  std::iota(v.begin(), v.end(), 0);
  return v;
}

// Unit cube, 8 vertices (index = x + 2y + 4z), six outward quads.
const int kCubeQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
Vec3 cube_vertex(int v) { return Vec3(v & 1, (v >> 1) & 1, (v >> 2) & 1); }

// Triangles expected from fan-splitting the cube quads as (a,b,c), (a,c,d).
std::vector<Tri> cube_triangles() {
  std::vector<Tri> tris;
  for (const auto& q : kCubeQuads) {
    tris.push_back({q[0], q[1], q[2]});
    tris.push_back({q[0], q[2], q[3]});
  }
  return tris;
}

std::string cube_obj() {
  std::string s;
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    s += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  for (const auto& q : kCubeQuads)
    s += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " + std::to_string(q[2] + 1) + " " +
         std::to_string(q[3] + 1) + "\n";
  return s;
}

std::string cube_off() {
  std::string s = "OFF\n8 6 12\n";
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    s += std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  for (const auto& q : kCubeQuads)
    s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
         std::to_string(q[3]) + "\n";
  return s;
}

// PLY values in either byte order.
struct PlyBytes {
  bool big_endian;
  std::string bytes;
  template <typename T>
  void put(T value) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    const std::uint16_t probe = 1;
    const bool host_little = *reinterpret_cast<const unsigned char*>(&probe) == 1;
    if (host_little == big_endian) std::reverse(b, b + sizeof(T));
    bytes.append(reinterpret_cast<const char*>(b), sizeof(T));
  }
};

// The cube with mixed scalar types, an unknown element between vertices and faces, and extra
// properties (scalars and lists) before and after the index list.
const char* kCubePlyHeaderBody =
    "comment mixed types and unknown data\n"
    "element vertex 8\n"
    "property uchar red\n"
    "property double x\n"
    "property list uchar float texcoord\n"
    "property float y\n"
    "property short z\n"
    "element edge 2\n"
    "property int vertex1\n"
    "property list int uint extra\n"
    "element face 6\n"
    "property uchar flags\n"
    "property list ushort uint vertex_index\n"
    "property double quality\n"
    "end_header\n";

std::string cube_ply_binary(bool big_endian) {
  PlyBytes out{big_endian, {}};
  out.bytes = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" +
              kCubePlyHeaderBody;
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    out.put<std::uint8_t>(200);
    out.put<double>(p.x());
    out.put<std::uint8_t>(2);
    out.put<float>(0.25f);
    out.put<float>(0.75f);
    out.put<float>(static_cast<float>(p.y()));
    out.put<std::int16_t>(static_cast<std::int16_t>(p.z()));
  }
  for (int e = 0; e < 2; ++e) {
    out.put<std::int32_t>(e);
    out.put<std::int32_t>(1);
    out.put<std::uint32_t>(77);
  }
  for (const auto& q : kCubeQuads) {
    out.put<std::uint8_t>(1);
    out.put<std::uint16_t>(4);
    for (int k = 0; k < 4; ++k) out.put<std::uint32_t>(static_cast<std::uint32_t>(q[k]));
    out.put<double>(0.5);
  }
  return out.bytes;
}

std::string cube_ply_ascii() {
  std::string s = std::string("ply\nformat ascii 1.0\n") + kCubePlyHeaderBody;
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    s += "200 " + std::to_string(p.x()) + " 2 0.25 0.75 " + std::to_string(p.y()) + " " +
         std::to_string(static_cast<int>(p.z())) + "\n";
  }
  s += "0 1 77\n1 1 77\n";
  for (const auto& q : kCubeQuads)
    s += "1 4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
         std::to_string(q[3]) + " 0.5\n";
  return s;
}

void expect_cube(const LoadedMesh& m) {
  ASSERT_EQ(m.mesh.num_vertices(), 8);
  for (int v = 0; v < 8; ++v) EXPECT_EQ(m.mesh.positions[v], cube_vertex(v)) << v;
  EXPECT_EQ(m.mesh.triangles, cube_triangles());
  EXPECT_EQ(m.file_to_mesh, iota_vector(8));
  EXPECT_EQ(m.mesh_to_file, iota_vector(8));
  EXPECT_EQ(m.triangle_to_face, (std::vector<int>{0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5}));
  const MeshTopology topology = build_topology(m.mesh);
  EXPECT_TRUE(topology.boundary_loops.empty());
  EXPECT_EQ(euler_characteristic(m.mesh, topology), 2);
}

TriMesh awkward_sphere() {
  TriMesh m = test_meshes::make_icosphere(2, 1.0 / 3.0);
  for (Vec3& p : m.positions) p += Vec3(1e-7, -12345.678901234567, 3.0e10 / 7.0);
  return m;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Round trips

TEST_F(MeshIo, ObjAndOffRoundTripsAreExact) {
  const TriMesh sphere = awkward_sphere();
  for (const std::string name : {"s.obj", "s.off", "s.obj.gz", "s.off.gz"}) {
    const std::string p = path(name);
    if (name.find(".obj") != std::string::npos) write_obj(p, sphere);
    else write_off(p, sphere);
    const LoadedMesh m = read_mesh(p);
    EXPECT_EQ(m.mesh.positions, sphere.positions) << name;  // bit-exact doubles
    EXPECT_EQ(m.mesh.triangles, sphere.triangles) << name;
    EXPECT_EQ(m.file_to_mesh, iota_vector(sphere.num_vertices())) << name;
    EXPECT_EQ(m.mesh_to_file, iota_vector(sphere.num_vertices())) << name;
    EXPECT_EQ(m.triangle_to_face, iota_vector(sphere.num_triangles())) << name;
  }
  // The .gz variants really are compressed.
  EXPECT_EQ(static_cast<unsigned char>(read_bytes(path("s.obj.gz"))[0]), 0x1f);
  EXPECT_EQ(read_bytes(path("s.off")).substr(0, 4), "OFF\n");
}

TEST_F(MeshIo, PlyRoundTripWithAttributesInHeaderAndBody) {
  const TriMesh grid = test_meshes::make_grid(5, 2.0, 0.3);
  const int nv = grid.num_vertices(), nt = grid.num_triangles();
  VertexAttribute distance{"geodesic distance", 1, {}};
  VertexAttribute uv{"uv", 2, {}};
  VertexAttribute normal{"normal", 3, {}};
  VertexAttribute clash{"x", 1, {}};  // must not collide with the position property x
  for (int v = 0; v < nv; ++v) {
    distance.values.push_back(0.5 * v);
    uv.values.insert(uv.values.end(), {grid.positions[v].x(), grid.positions[v].y()});
    normal.values.insert(normal.values.end(), {0.0, 0.0, 1.0});
    clash.values.push_back(-v);
  }
  FaceAttribute patch{"patch-id", {}};
  for (int t = 0; t < nt; ++t) patch.values.push_back(t % 3 - 1);

  const std::string p = path("grid.ply");
  write_ply(p, grid, {distance, uv, normal, clash}, {patch});
  const std::string bytes = read_bytes(p);
  const std::string expected_header =
      "ply\nformat binary_little_endian 1.0\ncomment written by macrocon\nelement vertex 25\n"
      "property float x\nproperty float y\nproperty float z\nproperty float geodesic_distance\n"
      "property float uv_x\nproperty float uv_y\nproperty float normal_x\nproperty float normal_y\n"
      "property float normal_z\nproperty float x_1\nelement face 32\nproperty list uchar int vertex_indices\n"
      "property int patch_id\nend_header\n";
  ASSERT_EQ(bytes.substr(0, expected_header.size()), expected_header);
  ASSERT_EQ(bytes.size(), expected_header.size() + 25u * 10 * 4 + 32u * (1 + 12 + 4));

  // Body spot checks: vertex 7's distance and x_1, triangle 5's attribute.
  auto bits_at = [&](std::size_t offset) {
    std::uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[offset + i])) << (8 * i);
    return bits;
  };
  auto float_at = [&](std::size_t offset) {
    const std::uint32_t bits = bits_at(offset);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  };
  const std::size_t v7 = expected_header.size() + 7 * 40;
  EXPECT_EQ(float_at(v7 + 12), 3.5f);
  EXPECT_EQ(float_at(v7 + 36), -7.0f);
  const std::size_t t5 = expected_header.size() + 25 * 40 + 5 * 17;
  EXPECT_EQ(bytes[t5], 3);
  EXPECT_EQ(static_cast<std::int32_t>(bits_at(t5 + 13)), patch.values[5]);

  // Reading skips the attributes and gives the float-rounded geometry.
  for (const std::string name : {"grid.ply", "grid.ply.gz"}) {
    if (name != "grid.ply") write_ply(path(name), grid, {distance, uv, normal, clash}, {patch});
    const LoadedMesh m = read_mesh(path(name));
    ASSERT_EQ(m.mesh.num_vertices(), nv);
    for (int v = 0; v < nv; ++v) EXPECT_EQ(m.mesh.positions[v], grid.positions[v].cast<float>().cast<double>());
    EXPECT_EQ(m.mesh.triangles, grid.triangles);
  }
}

TEST_F(MeshIo, WritersRejectBadInputAndUnwritablePaths) {
  const TriMesh grid = test_meshes::make_grid(3);
  EXPECT_EQ(status_of([&] { write_ply(path("a.ply"), grid, {{"d", 1, {1.0, 2.0}}}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { write_ply(path("a.ply"), grid, {{"d", 4, std::vector<double>(36)}}); }),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { write_ply(path("a.ply"), grid, {}, {{"f", {1}}}); }), MCON_ERROR_INVALID_ARGUMENT);
  TriMesh bad = grid;
  bad.triangles[0][1] = 9;
  EXPECT_EQ(status_of([&] { write_obj(path("a.obj"), bad); }), MCON_ERROR_INVALID_ARGUMENT);
  const std::string missing_dir = path("no/such/dir/");
  EXPECT_EQ(status_of([&] { write_obj(missing_dir + "a.obj", grid); }), MCON_ERROR_IO);
  EXPECT_EQ(status_of([&] { write_off(missing_dir + "a.off", grid); }), MCON_ERROR_IO);
  EXPECT_EQ(status_of([&] { write_ply(missing_dir + "a.ply", grid); }), MCON_ERROR_IO);
  EXPECT_EQ(status_of([&] { write_obj(missing_dir + "a.obj.gz", grid); }), MCON_ERROR_IO);
}

// ---------------------------------------------------------------------------------------------
// OBJ features

TEST_F(MeshIo, ObjPolygonsAreFanSplitABC_ACD) {
  const std::string p = write_text("poly.obj",
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 3 1 0\nv 2 2 0\n"
                                   "f 1 2 3 4\n"
                                   "f 2 5 6 7 3\n");
  const LoadedMesh m = read_mesh(p);
  EXPECT_EQ(m.mesh.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {1, 4, 5}, {1, 5, 6}, {1, 6, 2}}));
  EXPECT_EQ(m.triangle_to_face, (std::vector<int>{0, 0, 1, 1, 1}));
  expect_cube(read_mesh(write_text("cube.obj", cube_obj())));
}

TEST_F(MeshIo, ObjNegativeIndicesCountBackFromTheLastVertex) {
  std::string s;
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    s += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  for (const auto& q : kCubeQuads)
    s += "f " + std::to_string(q[0] - 8) + " " + std::to_string(q[1] - 8) + " " + std::to_string(q[2] - 8) + " " +
         std::to_string(q[3] - 8) + "\n";
  expect_cube(read_mesh(write_text("neg.obj", s)));
  // Relative to the vertices read so far, not to the whole file.
  const LoadedMesh m = read_mesh(write_text("rel.obj",
                                            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                            "v 1 1 0\nf 2 -1 3\n"));
  EXPECT_EQ(m.mesh.triangles, (std::vector<Tri>{{0, 1, 2}, {1, 3, 2}}));
}

TEST_F(MeshIo, ObjCornerFormsCommentsAndIgnoredStatements) {
  std::string s = "# header comment\r\nmtllib cube.mtl\r\no cube\r\n";
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    s += "v  " + std::to_string(p.x()) + "\t" + std::to_string(p.y()) + " " + std::to_string(p.z()) + " 1.0\r\n";
  }
  s += "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvn 0 0 1\r\nvp 0.5\r\nusemtl skin\r\ns 1\r\n\r\n   \r\n";
  const char* forms[6][4] = {{"%d", "%d", "%d", "%d"},           {"%d/1", "%d/2", "%d/3", "%d/1"},
                             {"%d//1", "%d//1", "%d//1", "%d//1"}, {"%d/1/1", "%d/2/1", "%d/3/1", "%d/1/1"},
                             {"%d/1/1", "%d//1", "%d/2", "%d"},      {"+%d/-1/-1", "%d/-2/-1", "%d", "%d"}};
  for (int f = 0; f < 6; ++f) {
    s += "f";
    for (int k = 0; k < 4; ++k) {
      char corner[32];
      std::snprintf(corner, sizeof(corner), forms[f][k], kCubeQuads[f][k] + 1);
      s += std::string(" ") + corner;
    }
    s += (f == 2 ? "  # a trailing comment\r\n" : "\r\n");
  }
  s += "l 1 2\r\n";  // polylines are not surface
  expect_cube(read_mesh(write_text("forms.obj", s)));
}

TEST_F(MeshIo, ObjGroupFilterKeepsOnlyThatGroup) {
  std::string s;
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    s += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  auto face = [](const int* q) {
    return "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " + std::to_string(q[2] + 1) + " " +
           std::to_string(q[3] + 1) + "\n";
  };
  s += face(kCubeQuads[0]);  // before any group
  s += "g bottom\n" + face(kCubeQuads[1]);
  s += "g side other\n" + face(kCubeQuads[2]) + face(kCubeQuads[3]);
  s += "o side\n" + face(kCubeQuads[4]);
  s += "g\n" + face(kCubeQuads[5]);
  const std::string p = write_text("groups.obj", s);

  MeshFileOptions options;
  options.obj_group = "side";
  const LoadedMesh side = read_mesh(p, options);
  EXPECT_EQ(side.triangle_to_face, (std::vector<int>{2, 2, 3, 3, 4, 4}));
  // Through mesh_to_file, every triangle is its file quad's (a,b,c) or (a,c,d).
  for (int t = 0; t < side.mesh.num_triangles(); ++t) {
    const int f = side.triangle_to_face[t];
    const int k = t % 2 == 0 ? 1 : 2;
    EXPECT_EQ(side.mesh_to_file[side.mesh.triangles[t][0]], kCubeQuads[f][0]);
    EXPECT_EQ(side.mesh_to_file[side.mesh.triangles[t][1]], kCubeQuads[f][k]);
    EXPECT_EQ(side.mesh_to_file[side.mesh.triangles[t][2]], kCubeQuads[f][k + 1]);
  }
  options.obj_group = "bottom";
  const LoadedMesh bottom = read_mesh(p, options);
  EXPECT_EQ(bottom.mesh.num_vertices(), 4);
  EXPECT_EQ(bottom.mesh_to_file, (std::vector<int>{4, 5, 6, 7}));
  EXPECT_EQ(bottom.file_to_mesh, (std::vector<int>{-1, -1, -1, -1, 0, 1, 2, 3}));
  options.obj_group = "default";  // a bare `g`
  EXPECT_EQ(read_mesh(p, options).triangle_to_face, (std::vector<int>{5, 5}));
  options.obj_group = "other";
  options.face_begin = 3;  // group and range combine
  EXPECT_EQ(read_mesh(p, options).triangle_to_face, (std::vector<int>{3, 3}));

  options = {};
  options.obj_group = "nonexistent";
  EXPECT_EQ(read_status(p, options), MCON_ERROR_NOT_FOUND);
  options.obj_group = "side";
  EXPECT_EQ(read_status(write_text("cube.off", cube_off()), options), MCON_ERROR_INVALID_ARGUMENT);
}

TEST_F(MeshIo, FaceRangeSelectsFileFacesAndCompacts) {
  // A strip of three quads: vertices 0..7 as two rows, plus an unused vertex 8.
  const std::string p = write_text("strip.off",
                                   "OFF\n9 3 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n0 1 0\n1 1 0\n2 1 0\n3 1 0\n9 9 9\n"
                                   "4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n");
  MeshFileOptions options;
  options.face_begin = 1;
  options.face_end = 2;
  const LoadedMesh m = read_mesh(p, options);
  EXPECT_EQ(m.mesh.num_vertices(), 4);
  EXPECT_EQ(m.file_to_mesh, (std::vector<int>{-1, 0, 1, -1, -1, 2, 3, -1, -1}));
  EXPECT_EQ(m.mesh_to_file, (std::vector<int>{1, 2, 5, 6}));
  EXPECT_EQ(m.triangle_to_face, (std::vector<int>{1, 1}));
  EXPECT_EQ(m.mesh.triangles, (std::vector<Tri>{{0, 1, 3}, {0, 3, 2}}));
  EXPECT_EQ(m.mesh.positions[3], Vec3(2, 1, 0));

  options.face_begin = 1;
  options.face_end = -1;  // to the end
  EXPECT_EQ(read_mesh(p, options).triangle_to_face, (std::vector<int>{1, 1, 2, 2}));
  // The whole file has an unreferenced vertex: it is dropped, not an error.
  EXPECT_EQ(read_mesh(p).mesh_to_file, iota_vector(8));

  for (auto [begin, end] : {std::pair<long, long>{0, 4}, {-1, 2}, {2, 1}}) {
    options.face_begin = begin;
    options.face_end = end;
    EXPECT_EQ(read_status(p, options), MCON_ERROR_INVALID_ARGUMENT) << begin << " " << end;
  }
  options.face_begin = 2;
  options.face_end = 2;
  EXPECT_EQ(read_status(p, options), MCON_ERROR_EMPTY_MESH);
}

// ---------------------------------------------------------------------------------------------
// OFF, PLY, gzip

TEST_F(MeshIo, OffVariantsAndComments) {
  expect_cube(read_mesh(write_text("cube.off", cube_off())));
  std::string coff = "# leading comment\n\nCOFF\n# counts next\n8 6 0\n";
  for (int v = 0; v < 8; ++v) {
    const Vec3 p = cube_vertex(v);
    coff += std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + " 255 0 0 255\n";
    if (v == 3) coff += "# a comment between vertices\n\n";
  }
  for (const auto& q : kCubeQuads)
    coff += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
            std::to_string(q[3]) + " 0.1 0.2 0.3\n";
  expect_cube(read_mesh(write_text("cube_c.off", coff)));
  std::string noff = cube_off();
  noff.replace(0, 3, "NOFF");
  expect_cube(read_mesh(write_text("cube_n.off", noff)));
  std::string one_line = cube_off();
  one_line.replace(0, 4, "OFF ");  // counts on the keyword's line
  expect_cube(read_mesh(write_text("cube_1.off", one_line)));
}

TEST_F(MeshIo, BinaryPlyBothByteOrdersAndAscii) {
  expect_cube(read_mesh(write_text("le.ply", cube_ply_binary(false))));
  expect_cube(read_mesh(write_text("be.ply", cube_ply_binary(true))));
  expect_cube(read_mesh(write_text("ascii.ply", cube_ply_ascii())));
  EXPECT_NE(cube_ply_binary(false), cube_ply_binary(true));
  // CRLF header lines.
  std::string crlf = cube_ply_binary(false);
  for (std::size_t at = 0; (at = crlf.find('\n', at)) != std::string::npos && at < crlf.find("end_header") + 12; at += 2)
    crlf.insert(at, "\r");
  expect_cube(read_mesh(write_text("crlf.ply", crlf)));
}

TEST_F(MeshIo, GzipAndCaseInsensitiveExtensions) {
  expect_cube(read_mesh(write_gz("cube.obj.gz", cube_obj())));
  expect_cube(read_mesh(write_gz("CUBE.OFF.GZ", cube_off())));
  expect_cube(read_mesh(write_gz("cube.Ply.Gz", cube_ply_binary(true))));
  expect_cube(read_mesh(write_text("CUBE.OBJ", cube_obj())));

  // A truncated archive is an error, not a shorter mesh.
  const std::string whole = read_bytes(write_gz("t.obj.gz", cube_obj() + std::string(4000, '#')));
  std::string message;
  EXPECT_EQ(read_status(write_text("cut.obj.gz", whole.substr(0, whole.size() / 2)), {}, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find("cut.obj.gz"), std::string::npos) << message;
  std::string corrupt = whole;
  corrupt[corrupt.size() - 6] ^= 0x5a;  // CRC mismatch
  EXPECT_EQ(read_status(write_text("crc.obj.gz", corrupt)), MCON_ERROR_IO);
}

TEST_F(MeshIo, DecompressionStopsAtTheSizeLimit) {
  // A gzip bomb: 64 MiB of '#' comment in about 64 KB, written with plain zlib in 1 MiB pieces.
  const std::string bomb = path("bomb.obj.gz");
  {
    gzFile f = gzopen(bomb.c_str(), "wb9");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(gzwrite(f, cube_obj().data(), static_cast<unsigned>(cube_obj().size())), static_cast<int>(cube_obj().size()));
    const std::string block(std::size_t{1} << 20, '#');
    for (int i = 0; i < 64; ++i) ASSERT_EQ(gzwrite(f, block.data(), static_cast<unsigned>(block.size())), int{1 << 20});
    ASSERT_EQ(gzclose(f), Z_OK);
  }
  ASSERT_LT(fs::file_size(bomb), std::uintmax_t{1} << 20);
  MeshFileOptions capped;
  capped.max_bytes = std::size_t{4} << 20;
  std::string message;
  EXPECT_EQ(read_status(bomb, capped, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find("'" + bomb + "' decompresses to more than 4194304 bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("MACROCON_MAX_INPUT_BYTES"), std::string::npos) << message;  // how to raise it
  // The same limit for plain files (checked from the size, before reading).
  const std::string big = write_text("big.obj", cube_obj() + std::string(std::size_t{5} << 20, '#'));
  EXPECT_EQ(read_status(big, capped, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find("'" + big + "' has more than 4194304 bytes"), std::string::npos) << message;
  // Under the default limit (1 GiB) the bomb is just a cube with a long comment.
  expect_cube(read_mesh(bomb));
  // The environment variable lowers or raises the default; a bad value is an error of its own.
  ASSERT_EQ(::setenv("MACROCON_MAX_INPUT_BYTES", "1000000", 1), 0);
  EXPECT_EQ(read_status(bomb, {}, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find("more than 1000000 bytes"), std::string::npos) << message;
  ASSERT_EQ(::setenv("MACROCON_MAX_INPUT_BYTES", "100MB", 1), 0);
  EXPECT_EQ(read_status(bomb, {}, &message), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(message.find("MACROCON_MAX_INPUT_BYTES is '100MB'"), std::string::npos) << message;
  ASSERT_EQ(::unsetenv("MACROCON_MAX_INPUT_BYTES"), 0);
  EXPECT_EQ(max_input_bytes(), kDefaultMaxInputBytes);
  EXPECT_EQ(max_input_bytes(12345), 12345u);
}

// ---------------------------------------------------------------------------------------------
// Bad input: a clear MCON_ERROR_IO naming the file (and line), never a crash.

TEST_F(MeshIo, MalformedFilesGiveIoErrors) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"obj", tri + "v 1 x 3\nf 1 2 3\n"},
      {"obj", tri + "v 1 2\nf 1 2 3\n"},
      {"obj", tri + "v 1 2 3abc\n"},
      {"obj", tri + "v 1e999999 0 0\n"},
      {"obj", tri + "f 1 2 4\n"},
      {"obj", tri + "f 0 1 2\n"},
      {"obj", tri + "f -4 1 2\n"},
      {"obj", tri + "f 1 2\n"},
      {"obj", tri + "f 1/2x 2 3\n"},
      {"obj", tri + "f 1/// 2 3\n"},
      {"obj", tri + "f 1 2 99999999999999999999\n"},
      {"obj", tri + "f 1 2 a\n"},
      {"off", ""},
      {"off", "PLY\n3 1 0\n"},
      {"off", "OFF\n3\n"},
      {"off", "OFF\n-3 1 0\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"},
      {"off", "OFF BINARY\n3 1 0\n"},
      {"off", "4OFF\n3 1 0\n"},
      {"ply", ""},
      {"ply", "plyx\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"},
      {"ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"},
      {"ply", "ply\nformat ascii 2.0\nend_header\n"},
      {"ply", "ply\nelement vertex 0\nend_header\n"},
      {"ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"},
      {"ply", "ply\nformat ascii 1.0\nend_header\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar float vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n"},
      {"ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1\n"},
      {"ply", "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n"},
      {"ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
              "property float z\nend_header\n\x01\x02\x03"},
      {"ply", "ply\nformat binary_little_endian 1.0\nelement edge 5\nproperty list uint int e\nend_header\n"
              "\xff\xff\xff\xff"},
      {"stl", "solid x\n"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string p = write_text("bad" + std::to_string(i) + "." + cases[i].first, cases[i].second);
    std::string message;
    EXPECT_EQ(read_status(p, {}, &message), MCON_ERROR_IO) << i << ": " << message;
    EXPECT_NE(message.find("bad" + std::to_string(i)), std::string::npos) << i << ": " << message;
  }
  EXPECT_EQ(read_status(path("missing.obj")), MCON_ERROR_IO);
  EXPECT_EQ(read_status(path("missing.obj.gz")), MCON_ERROR_IO);

  // Line numbers point at the bad line.
  std::string message;
  read_status(write_text("line.obj", "# c\n" + tri + "\nf 1 2 x\n"), {}, &message);
  EXPECT_NE(message.find("line.obj:6:"), std::string::npos) << message;
  read_status(write_text("line.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), {}, &message);
  EXPECT_NE(message.find("line.off:6:"), std::string::npos) << message;
  read_status(write_text("fwd.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\n"), {}, &message);
  EXPECT_NE(message.find("fwd.obj:2:"), std::string::npos) << message;
}

TEST_F(MeshIo, ValidationErrorsPropagateWithTheFileName) {
  std::string message;
  // Three triangles on one edge.
  EXPECT_EQ(
      read_status(write_text("fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n"),
                  {}, &message),
      MCON_ERROR_NON_MANIFOLD_EDGE);
  EXPECT_NE(message.find("fin.obj"), std::string::npos) << message;
  EXPECT_EQ(read_status(write_text("rep.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2 3\n")), MCON_ERROR_REPEATED_INDEX);
  EXPECT_EQ(read_status(write_text("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n")), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(read_status(write_text("empty.obj", "# nothing\n")), MCON_ERROR_EMPTY_MESH);
}

TEST_F(MeshIo, TruncatedBinaryPlyIsAnIoErrorAtEveryLength) {
  for (const bool big : {false, true}) {
    const std::string whole = cube_ply_binary(big);
    for (std::size_t n = 0; n < whole.size(); ++n) {
      const std::string p = write_text("cut.ply", whole.substr(0, n));
      std::string message;
      ASSERT_EQ(read_status(p, {}, &message), MCON_ERROR_IO) << n << ": " << message;
    }
  }
}

TEST_F(MeshIo, GarbageNeverCrashes) {
  // Deterministic mutations (byte overwrites, truncations) of valid files of every format: each
  // read must either succeed or throw mcon::Error — no other exception, no sanitizer report.
  const std::vector<std::pair<std::string, std::string>> seeds = {
      {"obj", cube_obj()}, {"off", cube_off()}, {"ply", cube_ply_binary(false)},
      {"ply", cube_ply_binary(true)}, {"ply", cube_ply_ascii()}};
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  auto next = [&state] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  const char alphabet[] = "0123456789-+./ \n#efvgxyzn\xff\x00\x80";
  int errors = 0, successes = 0;
  for (const auto& [ext, seed] : seeds) {
    for (int trial = 0; trial < 150; ++trial) {
      std::string s = seed;
      const int edits = 1 + static_cast<int>(next() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = next() % s.size();
        if (next() % 8 == 0) s.resize(at);
        else s[at] = (next() % 2) ? static_cast<char>(next() & 0xff) : alphabet[next() % (sizeof(alphabet) - 1)];
        if (s.empty()) break;
      }
      const std::string p = write_text("fuzz." + ext, s);
      try {
        read_mesh(p);
        ++successes;
      } catch (const Error&) {
        ++errors;
      }
    }
  }
  EXPECT_GT(errors, 0);
  EXPECT_EQ(errors + successes, 750);
}

// ---------------------------------------------------------------------------------------------
// Real data (/work/shared/meshes)

namespace {
const std::string kShared = MACROCON_SHARED_DIR;
}

TEST(MeshIoRealData, MakeHumanBodyIsClosed) {
  MeshFileOptions options;
  options.face_end = 13378;
  const LoadedMesh body = read_mesh(kShared + "/meshes/makehuman/base.obj.gz", options);
  EXPECT_EQ(body.mesh.num_vertices(), 13380);
  EXPECT_EQ(body.mesh.num_triangles(), 26756);
  EXPECT_EQ(body.mesh_to_file, iota_vector(13380));  // the body is vertices 0..13379
  const MeshTopology topology = build_topology(body.mesh);
  EXPECT_TRUE(topology.boundary_loops.empty());
  EXPECT_EQ(euler_characteristic(body.mesh, topology), 2);

  MeshFileOptions by_group;
  by_group.obj_group = "body";
  const LoadedMesh grouped = read_mesh(kShared + "/meshes/makehuman/base.obj.gz", by_group);
  EXPECT_EQ(grouped.mesh.positions, body.mesh.positions);
  EXPECT_EQ(grouped.mesh.triangles, body.mesh.triangles);
  EXPECT_EQ(grouped.triangle_to_face, body.triangle_to_face);
}

TEST(MeshIoRealData, IctFaceSurfaceHasOneBoundary) {
  MeshFileOptions options;
  options.face_end = 14034;  // faces 0..14033
  const LoadedMesh face = read_mesh(kShared + "/meshes/ict-facekit/generic_neutral_mesh.obj.gz", options);
  EXPECT_EQ(face.mesh.num_vertices(), 14062);
  EXPECT_EQ(face.triangle_to_face.back(), 14033);
  const MeshTopology topology = build_topology(face.mesh);
  EXPECT_EQ(topology.boundary_loops.size(), 1u);
}

TEST(MeshIoRealData, CgalOffMeshesReadAndValidate) {
  const std::pair<const char*, std::array<int, 2>> files[] = {{"cgal-hand.off.gz", {1197, 2390}},
                                                              {"cgal-head.off.gz", {1487, 2918}},
                                                              {"cgal-man.off.gz", {17495, 34986}},
                                                              {"cgal-mannequin-devil.off.gz", {12977, 25888}}};
  for (const auto& [name, counts] : files) {
    std::string message;
    LoadedMesh m;
    const mcon_status status = status_of([&] { m = read_mesh(kShared + "/meshes/cgal/" + name); }, &message);
    ASSERT_EQ(status, MCON_OK) << name << ": " << message;
    EXPECT_EQ(m.mesh.num_vertices(), counts[0]) << name;
    EXPECT_EQ(m.mesh.num_triangles(), counts[1]) << name;
  }
}

// A file with one face wound the wrong way (and one with every face inward) is repaired on reading
// and the repair is reported; before, the first was rejected as NON_MANIFOLD_EDGE.
TEST_F(MeshIo, ReversedFacesAreRepairedAndReported) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const LoadedMesh one = read_mesh(write_text("one.obj", v + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n"));
  EXPECT_EQ(one.orientation.reoriented_triangles, 1);
  EXPECT_EQ(one.orientation.inconsistent_components, 1);
  EXPECT_EQ(one.orientation.components_turned_outward, 0);
  EXPECT_EQ(one.mesh.triangles[3], (Tri{1, 2, 3}));
  const LoadedMesh inward = read_mesh(write_text("in.obj", v + "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n"));
  EXPECT_EQ(inward.orientation.reoriented_triangles, 4);
  EXPECT_EQ(inward.orientation.components_turned_outward, 1);
  EXPECT_EQ(inward.orientation.closed_components, 1);
}

// An open, consistently wound bowl facing inward: hosts are turned outward, an already-cut patch
// (the majority rule, as `macrocon embed` reads a patch file) is kept as given.
TEST_F(MeshIo, PatchFilesKeepTheirConsistentOrientation) {
  const std::string bowl = write_text("bowl.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 1 3 4\n");
  const LoadedMesh host = read_mesh(bowl);
  EXPECT_EQ(host.orientation.components_turned_outward, 1);
  EXPECT_EQ(host.orientation.reoriented_triangles, 3);
  MeshFileOptions patch_file;
  patch_file.orientation = OrientationRule::majority;
  const LoadedMesh patch = read_mesh(bowl, patch_file);
  EXPECT_EQ(patch.orientation.reoriented_triangles, 0);
  EXPECT_EQ(patch.mesh.triangles[1], (Tri{0, 3, 1}));
}

// Authoring inputs: OBJ polylines and value tables (tools/cli/entry_authoring.h reads them).
TEST_F(MeshIo, ObjPolylinesReadOpenAndClosedLines) {
  const std::string p = write_text("lines.obj",
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\n"
                                   "l 1 2 3 4 1\n"   // closed: the first vertex repeated
                                   "l -2 -1\n"       // relative indices
                                   "l 1/1 3/1\n");   // with texture indices
  const std::vector<FilePolyline> lines = read_obj_polylines(p);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_TRUE(lines[0].closed);
  EXPECT_EQ(lines[0].points.size(), 4u);
  EXPECT_EQ(lines[0].line, 6);
  EXPECT_FALSE(lines[1].closed);
  EXPECT_EQ(lines[1].points[0], mcon::Vec3(1, 1, 0));
  EXPECT_EQ(lines[1].points[1], mcon::Vec3(0, 1, 0));
  EXPECT_EQ(lines[2].points[1], mcon::Vec3(1, 1, 0));
  // The faces still read as before: `l` adds no triangle.
  EXPECT_EQ(read_mesh(write_text("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n")).mesh.num_triangles(), 1);
}

TEST_F(MeshIo, ObjPolylinesRefuseBadLines) {
  std::string message;
  EXPECT_EQ(status_of([&] { read_obj_polylines(write_text("none.obj", "v 0 0 0\nv 1 0 0\n")); }, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find("no polyline"), std::string::npos) << message;
  EXPECT_EQ(status_of([&] { read_obj_polylines(write_text("one.obj", "v 0 0 0\nl 1\n")); }, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find(":2: line has 1 vertices"), std::string::npos) << message;
  EXPECT_EQ(status_of([&] { read_obj_polylines(write_text("far.obj", "v 0 0 0\nl 1 7\n")); }, &message), MCON_ERROR_IO);
  EXPECT_NE(message.find("vertex index 7"), std::string::npos) << message;
}

TEST_F(MeshIo, CsvTableReadsHeaderRowsAndComments) {
  const ValueTable t = read_value_table(
      write_text("t.csv", "# singularities\nx, y,z\tindex\n\n1,2,3,1\n+4 5 6e0 -1  # valence 5\n"));
  ASSERT_EQ(t.columns, (std::vector<std::string>{"x", "y", "z", "index"}));
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.at(1, 0), 4.0);
  EXPECT_EQ(t.at(1, t.column("index")), -1.0);
  EXPECT_EQ(t.column("w"), -1);
}

TEST_F(MeshIo, CsvTableRefusesMalformedRows) {
  const std::pair<const char*, const char*> cases[] = {
      {"1,2\n3,4\n", "must name the columns"},
      {"a,b\n1,,2\n", "3 values, but the header names 2"},
      {"a,b\n1,\n", "column 'b': missing value"},  // a trailing comma leaves a missing value
      {"a,b\n,1\n", "missing value"},
      {"a,b\n1,x\n", "'x' is not a finite number"},
      {"a,b\n1,nan\n", "is not a finite number"},
      {"a,a\n1,2\n", "column 'a' appears twice"},
      {"# only a comment\n", "is empty"},
  };
  for (const auto& [text, expected] : cases) {
    std::string message;
    EXPECT_EQ(status_of([&] { read_value_table(write_text("bad.csv", text)); }, &message), MCON_ERROR_IO) << text;
    EXPECT_NE(message.find(expected), std::string::npos) << text << " -> " << message;
  }
  EXPECT_EQ(status_of([&] { read_value_table(write_text("t.json", "{}")); }), MCON_ERROR_IO);
}

TEST_F(MeshIo, PlyTableHasCoordinatesThenVertexProperties) {
  const ValueTable t = read_value_table(write_text(
      "t.ply",
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property double height\nproperty list uchar int skipped\nproperty int side\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 1 2 0.5 2 7 7 1\n3 4 5 1.5 0 2\n3 0 1 1\n"));
  ASSERT_EQ(t.columns, (std::vector<std::string>{"x", "y", "z", "height", "side"}));
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.at(0, 3), 0.5);
  EXPECT_EQ(t.at(1, 4), 2.0);
  EXPECT_EQ(t.at(1, 1), 4.0);
}
