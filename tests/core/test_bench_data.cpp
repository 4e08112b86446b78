// The benchmark data layer of the evaluation tools (tools/common): JSON, bench specs, random
// MakeHuman people and ICT faces, re-tessellations with exact ground truth, instance patches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <set>
#include <string>

#include "common/bench_spec.h"
#include "common/bench_random.h"
#include "common/ict_faces.h"
#include "json/json_file.h"
#include "common/makehuman_people.h"
#include "common/mesh_perturbation.h"
#include "common/morph_target.h"
#include "common/patch_instances.h"
#include "common/retessellate.h"
#include "base/error.h"
#include "mesh/mesh_topology.h"
#include "mesh/orientation.h"
#include "test_meshes.h"

using namespace mcon;
using namespace mcon::tools;

namespace {

const std::string kShared = MACROCON_SHARED_DIR;

// The models are loaded once for the whole test program (targets are cached per process anyway).
const MakeHumanPeople& people() {
  static const MakeHumanPeople p(kShared);
  return p;
}

const IctFaces& ict() {
  static const IctFaces f(kShared);
  return f;
}

std::string error_of(const std::function<void()>& f, mcon_status* status = nullptr) {
  try {
    f();
  } catch (const Error& e) {
    if (status) *status = e.status();
    return e.what();
  }
  return "";
}

double y_extent(const TriMesh& m) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& p : m.positions) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
  }
  return hi - lo;
}

bool same_positions(const TriMesh& a, const TriMesh& b) {
  if (a.positions.size() != b.positions.size()) return false;
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    if (std::memcmp(a.positions[i].data(), b.positions[i].data(), 3 * sizeof(double)) != 0) return false;
  return true;
}

std::multiset<std::array<int, 3>> canonical_triangles(const TriMesh& m) {
  std::multiset<std::array<int, 3>> out;
  for (Tri t : m.triangles) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// JSON

TEST(Json, RoundTripIsExact) {
  Json doc = Json::object();
  doc.set("name", "eye \"left\"\n\ttab\\ \x01 caf\xC3\xA9 \xF0\x9F\x99\x82");
  Json numbers = Json::array();
  for (double v : {0.0, -0.0, 1.0, -17.0, 0.1, 1.0 / 3.0, 2.0 / 3.0 * 1e-300, 5e-324, 1.7976931348623157e308,
                   9007199254740993.0, 123456789.125, -2.5e-7})
    numbers.push_back(v);
  doc.set("numbers", numbers);
  Json nested = Json::object();
  nested.set("empty_array", Json::array());
  nested.set("empty_object", Json::object());
  nested.set("flags", Json::array());
  doc.set("nested", nested);
  Json list = Json::array();
  list.push_back(true);
  list.push_back(false);
  list.push_back(nullptr);
  list.push_back(nested);
  doc.set("mixed", list);

  for (bool pretty : {true, false}) {
    const std::string text = write_json(doc, pretty);
    const Json back = parse_json(text);
    EXPECT_EQ(back, doc) << text;
    EXPECT_EQ(write_json(back, pretty), text);  // stable
    const Json& n = back.at("numbers");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const double x = n[i].as_number(), y = numbers[i].as_number();
      EXPECT_EQ(std::memcmp(&x, &y, sizeof(double)), 0) << i;
    }
  }
  const std::string compact = write_json(doc, false);
  EXPECT_EQ(compact.find(' ', compact.find("\"numbers\"")), std::string::npos);  // no whitespace in compact
  EXPECT_EQ(compact.find('\n'), std::string::npos);
  EXPECT_NE(compact.find("\\u0001"), std::string::npos);
  EXPECT_NE(compact.find("0.1,"), std::string::npos);  // shortest round-trip form
  // Member order is the insertion order.
  EXPECT_EQ(parse_json(compact).key(0), "name");
  EXPECT_EQ(parse_json(compact).key(3), "mixed");
}

TEST(Json, ParsesEscapesAndAccessors) {
  const Json v = parse_json(
      " {\"s\": \"a\\\"b\\\\c\\/d\\b\\f\\n\\r\\t\\u0041\\u00e9\\u20AC\\ud83d\\ude42\", \"i\": -12, "
      "\"e\": 1.5E+3, \"z\": 0, \"f\": -0.25e-2, \"t\": true, \"n\": null, \"a\": [1, [2, {}]]}\r\n");
  EXPECT_EQ(v.at("s").as_string(), "a\"b\\c/d\b\f\n\r\tA\xC3\xA9\xE2\x82\xAC\xF0\x9F\x99\x82");
  EXPECT_EQ(v.at("i").as_int(), -12);
  EXPECT_EQ(v.at("e").as_number(), 1500.0);
  EXPECT_EQ(v.at("f").as_number(), -0.0025);
  EXPECT_TRUE(v.at("t").as_bool());
  EXPECT_TRUE(v.at("n").is_null());
  EXPECT_EQ(v.at("a")[1][0].as_int(), 2);
  EXPECT_TRUE(v.at("a")[1][1].is_object());
  EXPECT_EQ(v.find("missing"), nullptr);

  mcon_status status = MCON_OK;
  EXPECT_NE(error_of([&] { v.at("missing"); }, &status).find("missing"), std::string::npos);
  EXPECT_EQ(status, MCON_ERROR_NOT_FOUND);
  EXPECT_NE(error_of([&] { v.at("s").as_number(); }, &status).find("string"), std::string::npos);
  EXPECT_EQ(status, MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_FALSE(error_of([&] { v.at("f").as_int(); }).empty());
  EXPECT_FALSE(error_of([&] { parse_json("1e300").as_int(); }).empty());
  EXPECT_FALSE(error_of([&] { v.at("a")[2]; }).empty());
  EXPECT_EQ(parse_json("1e-400").as_number(), 0.0);  // underflow is harmless
}

TEST(Json, MalformedInputNamesTheOffset) {
  // The offset is of the byte at which the error is found (nlohmann-json's lexer position): the
  // second digit of "01", the end of an unterminated string, the bad byte of an escape or of a
  // UTF-8 sequence; duplicate names and numbers out of range are named where they start.
  struct Case {
    const char* text;
    std::size_t offset;
  };
  const Case cases[] = {
      {"", 0},           {"  ", 2},           {"{", 1},           {"[1,]", 3},        {"[1 2]", 3},
      {"{\"a\" 1}", 5},  {"{\"a\":1,}", 7},   {"{a:1}", 1},       {"01", 1},          {"-", 1},
      {"1.", 2},         {"1e", 2},           {".5", 0},          {"+1", 0},          {"tru", 3},
      {"nul", 3},        {"\"abc", 4},        {"\"a\nb\"", 2},    {"\"\\x\"", 2},     {"\"\\u12g4\"", 5},
      {"\"\\ud800\"", 7}, {"\"\\udc00\"", 6}, {"\"\xC3\x28\"", 2}, {"\"\xED\xA0\x80\"", 2}, {"[1] x", 4},
      {"{\"a\":1,\"a\":2}", 7}, {"1e400", 0},   {"NaN", 0},         {"[1,\n  x]", 6},
      {"{\"x\\\"\":1,\"x\\\"\":2}", 9}, {"{\"x\\\\\":1,\"x\\\\\":2}", 9},  // escaped quote, backslash
  };
  for (const Case& c : cases) {
    mcon_status status = MCON_OK;
    const std::string message = error_of([&] { parse_json(c.text); }, &status);
    EXPECT_EQ(status, MCON_ERROR_INVALID_ARGUMENT) << c.text;
    EXPECT_NE(message.find("at offset " + std::to_string(c.offset) + " "), std::string::npos)
        << "input '" << c.text << "': " << message;
  }
  EXPECT_NE(error_of([] { parse_json("[1,\n  x]"); }).find("line 2, column 3"), std::string::npos);
  // The message never echoes the input's raw bytes (an invalid sequence, a control character).
  EXPECT_EQ(error_of([] { parse_json("\"\xC3\x28\""); }).find('\xC3'), std::string::npos);
  EXPECT_NE(error_of([] { parse_json("{\"a\":1,\"a\":2}"); }).find("duplicate member name \"a\""), std::string::npos);
  EXPECT_NE(error_of([] { parse_json("[1e400]"); }).find("number out of range at offset 1 "), std::string::npos);
  // Deep nesting is refused, not a stack overflow.
  EXPECT_NE(error_of([] { parse_json(std::string(100000, '[')); }).find("nesting"), std::string::npos);
  // Duplicate keys and trailing commas are errors; a valid deep-ish document is fine.
  EXPECT_NO_THROW(parse_json(std::string(200, '[') + std::string(200, ']')));
}

TEST(Json, WriterRejectsNonFiniteAndBadUtf8) {
  mcon_status status = MCON_OK;
  Json a = Json::array();
  a.push_back(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(error_of([&] { write_json(a); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_NON_FINITE);
  Json b = Json::object();
  b.set("x", std::numeric_limits<double>::infinity());
  EXPECT_FALSE(error_of([&] { write_json(b, false); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_NON_FINITE);
  EXPECT_FALSE(error_of([&] { write_json(Json("\xFF")); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_INVALID_ARGUMENT);
}

// ---------------------------------------------------------------------------------------------
// Bench specs

TEST(BenchSpec, MakeHumanAndIctFilesParse) {
  const BenchModelData mh = read_bench_model(kShared, "makehuman");
  EXPECT_EQ(mh.spec.mesh, "meshes/makehuman/base.obj.gz");
  EXPECT_EQ(mh.spec.surface_vertices, kMakeHumanBodyVertices);
  EXPECT_EQ(mh.spec.surface_faces, kMakeHumanBodyFaces);
  ASSERT_EQ(mh.spec.classes.size(), 13u);
  EXPECT_EQ(mh.spec.alternatives.size(), 2u);
  const BenchClass& eye_l = mh.spec.find("eye_l");
  EXPECT_EQ(eye_l.part, "eye");
  EXPECT_EQ(eye_l.side, BenchSide::Left);
  EXPECT_EQ(eye_l.center_vertex, 8021);
  EXPECT_DOUBLE_EQ(eye_l.radius, 0.6);
  EXPECT_FALSE(eye_l.fill_holes);
  const BenchClass& mouth = mh.spec.find("mouth");
  EXPECT_EQ(mouth.part, "mouth");
  EXPECT_EQ(mouth.side, BenchSide::None);
  EXPECT_TRUE(mouth.fill_holes);
  EXPECT_EQ(mh.spec.find("hand_r").center_vertex, 3197);
  EXPECT_TRUE(mh.spec.find("mouth_pure").alternative);
  std::set<std::string> parts;
  for (const BenchClass& c : mh.spec.classes) {
    parts.insert(c.part);
    EXPECT_EQ(static_cast<int>(mh.patches.find(c.name).vertices.size()), c.approx_vertices) << c.name;
  }
  EXPECT_EQ(parts, (std::set<std::string>{"eye", "nose", "mouth", "ear", "face", "hand", "foot", "arm"}));

  const BenchModelData ictd = read_bench_model(kShared, "ict");
  EXPECT_EQ(ictd.spec.surface_vertices, kIctSurfaceVertices);
  EXPECT_EQ(ictd.spec.surface_faces, kIctSurfaceFaces);
  ASSERT_EQ(ictd.spec.classes.size(), 7u);
  EXPECT_EQ(ictd.spec.find("nose").center_vertex, 4857);
  EXPECT_DOUBLE_EQ(ictd.spec.find("face").radius, 11.0);
  EXPECT_EQ(ictd.patches.find("face").vertices.size(), 8938u);

  mcon_status status = MCON_OK;
  EXPECT_NE(error_of([&] { mh.spec.find("tail"); }, &status).find("tail"), std::string::npos);
  EXPECT_EQ(status, MCON_ERROR_NOT_FOUND);
  EXPECT_FALSE(error_of([&] { read_bench_model(kShared, "nosuchmodel"); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_IO);
}

// ---------------------------------------------------------------------------------------------
// MakeHuman targets and people

TEST(MorphTarget, ParsesAndRejectsMalformedLines) {
  const MorphTarget t = parse_morph_target("# comment\n\n12 .5 -0.25 0\r\n3 0 0 1e-3\n", "x");
  ASSERT_EQ(t.indices, (std::vector<int>{12, 3}));
  EXPECT_EQ(t.offsets[0], Vec3(0.5, -0.25, 0));
  std::vector<Vec3> p(5, Vec3::Zero());
  add_morph_target(p, t, 2.0);  // index 12 is past the body: ignored
  EXPECT_EQ(p[3], Vec3(0, 0, 2e-3));
  for (const char* bad : {"1 2 3\n", "1 2 3 4 5\n", "-1 0 0 0\n", "a 0 0 0\n", "1 0 x 0\n", "1 nan 0 0\n"}) {
    mcon_status status = MCON_OK;
    const std::string message = error_of([&] { parse_morph_target(std::string("# h\n") + bad, "file.target"); }, &status);
    EXPECT_EQ(status, MCON_ERROR_IO) << bad;
    EXPECT_NE(message.find("file.target' line 2"), std::string::npos) << message;
  }
  // Parsed once per process: the second load returns the same object.
  const std::string path = kShared + "/meshes/makehuman/targets/nose/nose-trans-up.target.gz";
  EXPECT_EQ(&load_morph_target(path), &load_morph_target(path));
  EXPECT_GT(load_morph_target(path).indices.size(), 100u);
}

TEST(MakeHumanPeople, LocalTargetsFollowTheRecipe) {
  int pairs = 0, one_sided = 0, lr = 0;
  for (const LocalTargetDraw& d : people().local_draws()) {
    (d.opposite_pair ? pairs : one_sided) += static_cast<int>(d.sides.size());
    if (d.sides.size() == 2) {
      ++lr;
      EXPECT_NE(d.sides[0].first.find("/l-"), std::string::npos) << d.key;
      EXPECT_NE(d.sides[1].first.find("/r-"), std::string::npos) << d.key;
    }
    for (const auto& s : d.sides) {
      EXPECT_EQ(s.first.find("eyefold"), std::string::npos);
      EXPECT_EQ(s.first.find("epicanthus"), std::string::npos);
    }
  }
  EXPECT_EQ(pairs, 197);  // bench/README.md
  EXPECT_EQ(one_sided, 16);
  EXPECT_EQ(lr, 64);  // 60 l-/r- opposite pairs + 4 ear shapes
}

TEST(MakeHumanPeople, MacroWeightsArePartitionsOfOne) {
  for (const double age : {0.375, 0.45, 0.5, 0.7, 0.875}) {
    const auto w = macro_target_weights(0.3, age, 0.8, 0.1, {0.2, 0.5, 0.3});
    double ethnic_sum = 0, universal_sum = 0;
    for (const TargetWeight& t : w) {
      EXPECT_GT(t.weight, 0.0);
      (t.target.find("universal") != std::string::npos ? universal_sum : ethnic_sum) += t.weight;
    }
    EXPECT_NEAR(ethnic_sum, 1.0, 1e-12) << age;
    EXPECT_NEAR(universal_sum, 1.0, 1e-12) << age;
  }
  // Old at the top of the range, no baby or child above 0.5.
  for (const TargetWeight& t : macro_target_weights(1.0, 0.875, 1.0, 0.0, {0, 0, 1})) {
    EXPECT_EQ(t.target.find("female"), std::string::npos);
    EXPECT_EQ(t.target.find("baby"), std::string::npos);
    EXPECT_EQ(t.target.find("child"), std::string::npos);
  }
  const auto w = macro_target_weights(1.0, 0.875, 1.0, 0.0, {0, 0, 1});
  ASSERT_EQ(w.size(), 4u);
  EXPECT_EQ(w[0].target, "macrodetails/caucasian-male-young");
  EXPECT_NEAR(w[0].weight, 0.25, 1e-12);
  EXPECT_EQ(w[3].target, "macrodetails/universal-male-old-maxmuscle-minweight");
  EXPECT_NEAR(w[3].weight, 0.75, 1e-12);
}

TEST(MakeHumanPeople, PeopleAreDeterministicDistinctAndPlausible) {
  const MakeHumanPeople& mh = people();
  const TriMesh& base = mh.base().mesh;
  EXPECT_EQ(base.num_vertices(), kMakeHumanBodyVertices);
  EXPECT_EQ(base.num_triangles(), 2 * kMakeHumanBodyFaces);
  EXPECT_NEAR(y_extent(base), 16.6589, 1e-3);  // bench/README.md units

  const TriMesh p1 = mh.person(7, 1);
  const TriMesh p0 = mh.person(7, 0);
  EXPECT_TRUE(same_positions(mh.person(7, 1), p1));  // independent of what was made before
  EXPECT_EQ(p1.triangles, base.triangles);           // shared connectivity: identity ground truth
  EXPECT_FALSE(same_positions(p0, p1));
  EXPECT_FALSE(same_positions(mh.person(8, 1), p1));

  const PersonRecipe r = mh.recipe(7, 1);
  EXPECT_GE(r.age, 0.375);
  EXPECT_LT(r.age, 0.875);
  EXPECT_NEAR(r.ethnic[0] + r.ethnic[1] + r.ethnic[2], 1.0, 1e-15);
  std::set<std::string> names;
  for (const TargetWeight& t : r.targets) {
    EXPECT_TRUE(names.insert(t.target).second) << t.target;
    if (t.target.rfind("macrodetails/", 0) != 0) {
      EXPECT_LE(t.weight, 0.44 + 1e-12) << t.target;
    }
  }
  EXPECT_GT(names.size(), 200u);  // 197 pairs + some one-sided + macro

  // Heights over a few people (bench/README.md: 15.1-18.0 over 30 people); some spread.
  double lo = 100, hi = 0;
  for (std::uint64_t i = 0; i < 6; ++i) {
    const double h = y_extent(i == 0 ? p0 : mh.person(7, i));
    EXPECT_GT(h, 15.0) << i;
    EXPECT_LT(h, 18.0) << i;
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  EXPECT_GT(hi - lo, 0.2);
}

// ---------------------------------------------------------------------------------------------
// ICT faces

TEST(IctFaces, FacesAreDeterministicAndClipped) {
  const IctFaces& f = ict();
  EXPECT_EQ(f.neutral().mesh.num_vertices(), kIctSurfaceVertices);
  EXPECT_EQ(f.neutral().mesh.num_triangles(), 2 * kIctSurfaceFaces);
  const MeshTopology topo = build_topology(f.neutral().mesh);
  EXPECT_EQ(topo.boundary_loops.size(), 1u);  // the neck cut
  EXPECT_EQ(euler_characteristic(f.neutral().mesh, topo), 1);

  const TriMesh a = f.face(3, 5);
  EXPECT_TRUE(same_positions(a, f.face(3, 5)));
  EXPECT_FALSE(same_positions(a, f.face(3, 6)));
  EXPECT_FALSE(same_positions(a, f.face(4, 5)));
  EXPECT_FALSE(same_positions(a, f.neutral().mesh));
  EXPECT_EQ(a.triangles, f.neutral().mesh.triangles);

  // Coefficients: N(0, 1) clipped to +-2.5.
  double sum = 0, sum2 = 0;
  int n = 0;
  for (std::uint64_t i = 0; i < 200; ++i)
    for (const double c : IctFaces::coefficients(11, i)) {
      EXPECT_LE(std::fabs(c), kIctCoefficientClip);
      sum += c;
      sum2 += c * c;
      ++n;
    }
  EXPECT_NEAR(sum / n, 0.0, 0.1);
  EXPECT_NEAR(sum2 / n, 1.0, 0.1);
  // Building from explicit coefficients: unit coefficient k gives identity k.
  IctCoefficients c{};
  c[0] = 1.0;
  const TriMesh id0 = f.build(c);
  double max_offset = 0;
  for (int v = 0; v < id0.num_vertices(); ++v)
    max_offset = std::max(max_offset, (id0.positions[v] - f.neutral().mesh.positions[v]).norm());
  EXPECT_NEAR(max_offset, 1.52, 0.01);  // shared/meshes/SOURCES.md: largest displacement of identity000
}

// ---------------------------------------------------------------------------------------------
// Re-tessellation

// An n x n quad grid, bent into a half cylinder, triangulated as the readers do: quad a,b,c,d ->
// a,b,c + a,c,d (consecutive), with each triangle's quad index.
struct QuadGrid {
  TriMesh mesh;
  std::vector<int> triangle_to_face;
};

QuadGrid make_quad_grid(int n) {
  QuadGrid g;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double angle = M_PI * i / (n - 1);
      g.mesh.positions.emplace_back(-std::cos(angle), static_cast<double>(j) / (n - 1), std::sin(angle));
    }
  int face = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i, ++face) {
      const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      g.mesh.triangles.push_back({a, b, c});
      g.mesh.triangles.push_back({a, c, d});
      g.triangle_to_face.insert(g.triangle_to_face.end(), {face, face});
    }
  return g;
}

TEST(Retessellate, RediagonalizationKeepsVerticesAndChangesTriangles) {
  const io::LoadedMesh& base = people().base();
  const TriMesh person = people().person(2, 0);
  const Retessellation all = rediagonalize(person, base.triangle_to_face, DiagonalPattern::All);
  EXPECT_TRUE(same_positions(all.mesh, person));  // the vertex set is unchanged
  EXPECT_EQ(all.mesh.num_triangles(), person.num_triangles());
  EXPECT_GT(all.changed, kMakeHumanBodyFaces * 95 / 100);
  EXPECT_EQ(all.to_original.size(), person.positions.size());
  EXPECT_NO_THROW(validate_mesh(all.mesh));
  EXPECT_EQ(euler_characteristic(all.mesh, build_topology(all.mesh)), 2);
  // Exactly the re-split quads have other triangles.
  const auto before = canonical_triangles(person), after = canonical_triangles(all.mesh);
  int common = 0;
  for (const auto& t : after) common += static_cast<int>(before.count(t));
  EXPECT_EQ(common, 2 * (kMakeHumanBodyFaces - all.changed));
  EXPECT_NEAR(total_area(all.mesh), total_area(person), 0.02 * total_area(person));
}

TEST(Retessellate, DiagonalPatternsAndPatches) {
  const QuadGrid g = make_quad_grid(21);  // 400 quads
  const Retessellation all = rediagonalize(g.mesh, g.triangle_to_face, DiagonalPattern::All);
  EXPECT_EQ(all.changed, 400);
  EXPECT_EQ(all.mesh.triangles[0], (Tri{0, 1, 21}));  // a,b,c,d = 0,1,22,21 -> a,b,d + b,c,d
  EXPECT_EQ(all.mesh.triangles[1], (Tri{1, 22, 21}));
  const Retessellation alt = rediagonalize(g.mesh, g.triangle_to_face, DiagonalPattern::Alternate);
  EXPECT_EQ(alt.changed, 200);
  EXPECT_EQ(alt.mesh.triangles[0], g.mesh.triangles[0]);  // face 0 keeps its diagonal, face 1 not
  EXPECT_NE(alt.mesh.triangles[2], g.mesh.triangles[2]);
  const Retessellation r1 = rediagonalize(g.mesh, g.triangle_to_face, DiagonalPattern::Random, 5);
  const Retessellation r2 = rediagonalize(g.mesh, g.triangle_to_face, DiagonalPattern::Random, 5);
  const Retessellation r3 = rediagonalize(g.mesh, g.triangle_to_face, DiagonalPattern::Random, 6);
  EXPECT_EQ(r1.mesh.triangles, r2.mesh.triangles);
  EXPECT_NE(r1.mesh.triangles, r3.mesh.triangles);
  EXPECT_NEAR(r1.changed, 200, 40);
  for (const auto* r : {&all, &alt, &r1}) {
    EXPECT_TRUE(same_positions(r->mesh, g.mesh));
    EXPECT_NEAR(total_area(r->mesh), total_area(g.mesh), 0.01);
  }

  // A patch cut through quads: the halves stay, the whole quads follow the same per-face choice.
  TriMesh patch;
  std::vector<int> patch_faces;
  patch.positions = g.mesh.positions;
  for (int t = 1; t < 401; ++t) {  // starts and ends with half a quad
    patch.triangles.push_back(g.mesh.triangles[t]);
    patch_faces.push_back(g.triangle_to_face[t]);
  }
  remove_unreferenced_vertices(patch);
  const Retessellation rp = rediagonalize(patch, patch_faces, DiagonalPattern::Random, 5);
  EXPECT_EQ(rp.mesh.triangles.front(), patch.triangles.front());
  EXPECT_EQ(rp.mesh.triangles.back(), patch.triangles.back());
  int flipped_in_range = 0;
  for (int f = 1; f < 200; ++f) flipped_in_range += r1.mesh.triangles[2 * f] != g.mesh.triangles[2 * f];
  EXPECT_EQ(rp.changed, flipped_in_range);

  // A concave quad keeps its diagonal: the other one would fold a triangle over.
  QuadGrid bad = make_quad_grid(2);
  // a, b, d, c = vertices 0, 1, 2, 3; c is a reflex corner.
  bad.mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.2, 0.2, 0)};
  EXPECT_EQ(rediagonalize(bad.mesh, bad.triangle_to_face, DiagonalPattern::All).changed, 0);

  mcon_status status = MCON_OK;
  EXPECT_FALSE(error_of([&] { rediagonalize(g.mesh, {1, 2, 3}, DiagonalPattern::All); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_INVALID_ARGUMENT);
}

TEST(Retessellate, DecimationOfAWholeBodyKeepsExactSurvivors) {
  const TriMesh person = people().person(2, 1);
  const std::vector<int> keep = {297, 537, 3197};  // nose, mouth and right hand centers
  DecimationOptions options;
  options.keep = keep;
  const Retessellation d = decimate(person, 42, options);
  const int removed = person.num_vertices() - d.mesh.num_vertices();
  EXPECT_EQ(removed, d.changed);
  EXPECT_GE(removed, 0.2 * person.num_vertices() - 1);
  EXPECT_LE(removed, 0.4 * person.num_vertices() + 1);
  EXPECT_NO_THROW(validate_mesh(d.mesh));
  const MeshTopology topo = build_topology(d.mesh);
  EXPECT_TRUE(topo.boundary_loops.empty());
  EXPECT_EQ(euler_characteristic(d.mesh, topo), 2);  // still a closed genus-0 surface
  ASSERT_EQ(d.to_original.size(), d.mesh.positions.size());
  for (std::size_t v = 0; v < d.to_original.size(); ++v) {
    if (v > 0) {
      ASSERT_LT(d.to_original[v - 1], d.to_original[v]);
    }
    ASSERT_EQ(std::memcmp(d.mesh.positions[v].data(), person.positions[d.to_original[v]].data(), 3 * sizeof(double)), 0);
  }
  for (const int k : keep) EXPECT_TRUE(std::binary_search(d.to_original.begin(), d.to_original.end(), k)) << k;
  // No triangle turned inside out: the enclosed volume barely changes.
  const auto volume = [](const TriMesh& m) {
    double v = 0;
    for (const Tri& t : m.triangles) v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]])) / 6;
    return v;
  };
  EXPECT_NEAR(volume(d.mesh), volume(person), 0.05 * std::fabs(volume(person)));
}

TEST(Retessellate, DecimationOfAPatchKeepsItsBoundary) {
  // A jittered grid stands in for a patch: a disk with a boundary loop.
  const TriMesh grid = test_meshes::make_grid(30, 1.0, 0.3);
  const MeshTopology before = build_topology(grid);
  DecimationOptions options;
  options.min_fraction = options.max_fraction = 0.3;
  const Retessellation d = decimate(grid, 1, options);
  EXPECT_EQ(d.changed, static_cast<int>(std::lround(0.3 * grid.num_vertices())));
  const MeshTopology after = build_topology(d.mesh);
  ASSERT_EQ(after.boundary_loops.size(), 1u);
  EXPECT_EQ(euler_characteristic(d.mesh, after), 1);
  std::vector<int> loop_before = before.boundary_loops[0], loop_after;
  for (const int v : after.boundary_loops[0]) loop_after.push_back(d.to_original[v]);
  std::sort(loop_before.begin(), loop_before.end());
  std::sort(loop_after.begin(), loop_after.end());
  EXPECT_EQ(loop_after, loop_before);  // every boundary vertex and edge survives
  for (int t = 0; t < d.mesh.num_triangles(); ++t) EXPECT_GT(triangle_normal(d.mesh, t).z(), 0.5) << t;
  EXPECT_NEAR(total_area(d.mesh), 1.0, 1e-9);  // a planar disk keeps its area exactly
  for (std::size_t v = 0; v < d.to_original.size(); ++v)
    ASSERT_EQ(d.mesh.positions[v], grid.positions[d.to_original[v]]);

  // Seeded: same seed, same mesh; another seed, another one. The default fraction is in [0.2, 0.4].
  const Retessellation again = decimate(grid, 1, options);
  EXPECT_EQ(again.mesh.triangles, d.mesh.triangles);
  EXPECT_EQ(again.to_original, d.to_original);
  EXPECT_NE(decimate(grid, 2, options).to_original, d.to_original);
  std::set<int> removed_counts;
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const int removed = decimate(grid, seed).changed;
    EXPECT_GE(removed, 0.2 * grid.num_vertices() - 1);
    EXPECT_LE(removed, 0.4 * grid.num_vertices() + 1);
    removed_counts.insert(removed);
  }
  EXPECT_GT(removed_counts.size(), 1u);

  mcon_status status = MCON_OK;
  options.keep = {grid.num_vertices()};
  EXPECT_FALSE(error_of([&] { decimate(grid, 1, options); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_INDEX_OUT_OF_RANGE);
  options.keep.clear();
  options.min_fraction = 0.5;
  options.max_fraction = 0.4;
  EXPECT_FALSE(error_of([&] { decimate(grid, 1, options); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_INVALID_ARGUMENT);
}

// ---------------------------------------------------------------------------------------------
// Instance patches

TEST(PatchInstances, RadiusScalesWithThePatchArea) {
  const BenchModelData mh = read_bench_model(kShared, "makehuman");
  const io::LoadedMesh& base = people().base();
  const BenchClass& nose = mh.spec.find("nose");
  const std::vector<int>& verts = mh.patches.find("nose").vertices;
  const InstancePatch same = instance_patch(nose, verts, base.mesh, base.mesh, base.triangle_to_face);
  EXPECT_EQ(same.center_vertex, 297);
  EXPECT_DOUBLE_EQ(same.scale, 1.0);
  EXPECT_DOUBLE_EQ(same.radius, 0.5);

  // A uniformly scaled body scales the radius by the same factor.
  TriMesh big = base.mesh;
  for (Vec3& p : big.positions) p *= 1.1;
  EXPECT_NEAR(instance_patch(nose, verts, base.mesh, big, base.triangle_to_face).radius, 0.55, 1e-12);

  // Random people: within the README's range over 30 people, with some margin.
  const TriMesh p = people().person(7, 2);
  for (const char* name : {"eye_r", "hand_l", "face"}) {
    const InstancePatch ip =
        instance_patch(mh.spec.find(name), mh.patches.find(name).vertices, base.mesh, p, base.triangle_to_face);
    EXPECT_GT(ip.scale, 0.8) << name;
    EXPECT_LT(ip.scale, 1.2) << name;
    EXPECT_DOUBLE_EQ(ip.radius, mh.spec.find(name).radius * ip.scale);
    // Whole faces or single triangles: almost the same scale.
    EXPECT_NEAR(instance_patch(mh.spec.find(name), mh.patches.find(name).vertices, base.mesh, p).scale, ip.scale, 0.01);
  }

  mcon_status status = MCON_OK;
  TriMesh other = base.mesh;
  std::swap(other.triangles[0], other.triangles[1]);
  EXPECT_FALSE(error_of([&] { instance_patch(nose, verts, base.mesh, other); }, &status).empty());
  EXPECT_EQ(status, MCON_ERROR_INVALID_ARGUMENT);
}

TEST(BenchRng, DrawsDependOnlyOnSeedStreamAndCounter) {
  const BenchRng a(1, 2), b(1, 2), c(1, 3), d(2, 2);
  EXPECT_EQ(a.bits(5), b.bits(5));
  EXPECT_NE(a.bits(5), c.bits(5));
  EXPECT_NE(a.bits(5), d.bits(5));
  EXPECT_NE(a.bits(5), a.bits(6));
  // Uniforms in [lo, hi) with the right mean; names map to fixed counters.
  double sum = 0;
  for (std::uint64_t i = 0; i < 10000; ++i) {
    const double u = a.uniform(i, -0.4, 0.4);
    ASSERT_GE(u, -0.4);
    ASSERT_LT(u, 0.4);
    sum += u;
  }
  EXPECT_NEAR(sum / 10000, 0.0, 0.01);
  EXPECT_EQ(a.uniform("gender"), a.uniform(stable_hash("gender")));
  EXPECT_EQ(stable_hash("a"), 0xAF63DC4C8601EC8Cull);  // FNV-1a reference value
}

TEST(MeshPerturbation, FlipWindingReversesEveryTriangleAndTheRepairUndoesIt) {
  const TriMesh sphere = test_meshes::make_icosphere(3);
  MeshPerturbation flip;
  flip.flip_winding = true;
  EXPECT_EQ(flip.describe(), "flip-winding");
  PerturbedMesh p = perturb_mesh(sphere, flip, 1);
  ASSERT_EQ(p.mesh.triangles.size(), sphere.triangles.size());
  for (std::size_t t = 0; t < sphere.triangles.size(); ++t)
    EXPECT_EQ(p.mesh.triangles[t], (Tri{sphere.triangles[t][0], sphere.triangles[t][2], sphere.triangles[t][1]}));
  EXPECT_EQ(p.mesh.positions, sphere.positions);
  EXPECT_EQ(orient_and_validate(p.mesh).components_turned_outward, 1);
  EXPECT_EQ(p.mesh.triangles, sphere.triangles);
}

TEST(MeshPerturbation, NoiseIsSeededAndScaledByTheMeanEdgeLength) {
  const TriMesh sphere = test_meshes::make_icosphere(4);
  MeshPerturbation noise;
  noise.noise = 0.25;
  const PerturbedMesh a = perturb_mesh(sphere, noise, 7), b = perturb_mesh(sphere, noise, 7),
                      c = perturb_mesh(sphere, noise, 8);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_NE(a.mesh.positions, c.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, sphere.triangles);
  double sum2 = 0;
  for (int v = 0; v < sphere.num_vertices(); ++v) sum2 += (a.mesh.positions[v] - sphere.positions[v]).squaredNorm();
  const double std_per_coordinate = std::sqrt(sum2 / (3.0 * sphere.num_vertices()));
  EXPECT_NEAR(std_per_coordinate / mean_edge_length(sphere), 0.25, 0.02);  // 7686 draws
}

TEST(MeshPerturbation, DensityResamplesTheSameSurface) {
  const TriMesh sphere = test_meshes::make_icosphere(3);  // 642 vertices
  MeshPerturbation dense;
  dense.density = 4;
  const PerturbedMesh up = perturb_mesh(sphere, dense, 3);
  EXPECT_NEAR(up.mesh.num_vertices(), 4 * 642, 0.01 * 4 * 642);
  for (int v = 0; v < up.mesh.num_vertices(); ++v)
    if (up.to_original[v] >= 0) {
      EXPECT_EQ(up.mesh.positions[v], sphere.positions[up.to_original[v]]);
    }
  TriMesh checked = up.mesh;
  EXPECT_EQ(orient_and_validate(checked).reoriented_triangles, 0);
  EXPECT_NEAR(total_area(up.mesh), total_area(sphere), 1e-9);  // midpoints lie on the old faces

  MeshPerturbation sparse;
  sparse.density = 0.5;
  const PerturbedMesh down = perturb_mesh(sphere, sparse, 3, {17});
  EXPECT_LE(down.mesh.num_vertices(), 0.55 * 642);
  EXPECT_GE(perturbed_vertex(down, 17), 0);  // kept
  EXPECT_EQ(down.mesh.positions[perturbed_vertex(down, 17)], sphere.positions[17]);
  EXPECT_EQ(sparse.describe(), "density 0.5");
}

TEST(MeshPerturbation, BadOptionsAreRejected) {
  for (const double noise : {-0.1, 11.0, std::numeric_limits<double>::quiet_NaN()}) {
    MeshPerturbation p;
    p.noise = noise;
    EXPECT_THROW(check_perturbation(p), Error);
  }
  for (const double density : {0.0, 0.01, 17.0, std::numeric_limits<double>::infinity()}) {
    MeshPerturbation p;
    p.density = density;
    EXPECT_THROW(check_perturbation(p), Error);
  }
  EXPECT_EQ(MeshPerturbation{}.describe(), "clean");
}
