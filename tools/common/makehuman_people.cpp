#include "common/makehuman_people.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <tbb/parallel_for.h>

#include "common/bench_random.h"
#include "common/morph_target.h"
#include "base/error.h"

namespace mcon::tools {

namespace {

constexpr const char* kLocalCategories[] = {"ears", "eyes",     "nose", "mouth", "head", "chin",
                                            "cheek", "forehead", "eyebrows", "neck", "armslegs"};
constexpr const char* kTargetSuffix = ".target.gz";

// Last words of opposite targets: (first, second).
constexpr std::pair<const char*, const char*> kOpposites[] = {
    {"decr", "incr"}, {"down", "up"}, {"in", "out"}, {"backward", "forward"}, {"concave", "convex"},
    {"compress", "uncompress"}};

constexpr double kLocalRange = 0.4;       // pair weights ~ U[-0.4, 0.4], one-sided ~ U[0, 0.4]
constexpr double kAsymmetryRange = 0.04;  // right side of an l-/r- pair: + U[-0.04, 0.04]

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// "l-ear-flap-decr" -> side 'l', rest "ear-flap-decr"; no side prefix -> side 0.
std::pair<char, std::string> split_side(const std::string& name) {
  if (starts_with(name, "l-") || starts_with(name, "r-")) return {name[0], name.substr(2)};
  return {0, name};
}

}  // namespace

std::vector<LocalTargetDraw> list_local_target_draws(const std::string& targets_dir) {
  namespace fs = std::filesystem;
  // Draw key -> side ('l', 'r' or 0) -> pair.
  std::map<std::string, LocalTargetDraw> draws;
  std::map<std::string, std::map<char, LocalTargetDraw::Side>> sides;
  for (const char* category : kLocalCategories) {
    const fs::path dir = fs::path(targets_dir) / category;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) fail(MCON_ERROR_IO, "missing target folder '" + dir.string() + "'");
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string file = entry.path().filename().string();
      if (file.size() <= std::char_traits<char>::length(kTargetSuffix) ||
          file.compare(file.size() - std::char_traits<char>::length(kTargetSuffix), std::string::npos,
                       kTargetSuffix) != 0)
        continue;
      const std::string name = file.substr(0, file.size() - std::char_traits<char>::length(kTargetSuffix));
      // They fold the eyelids even at weight 0.5 (bench/README.md).
      if (name.find("eyefold") != std::string::npos || name.find("epicanthus") != std::string::npos) continue;
      names.insert(name);
    }
    if (ec) fail(MCON_ERROR_IO, "cannot list '" + dir.string() + "': " + ec.message());
    for (const std::string& name : names) {
      const auto [side, rest] = split_side(name);
      const std::size_t dash = rest.rfind('-');
      const std::string stem = dash == std::string::npos ? rest : rest.substr(0, dash);
      const std::string last = dash == std::string::npos ? "" : rest.substr(dash + 1);
      const std::string prefix = side ? std::string(1, side) + "-" : "";
      bool paired = false;
      for (const auto& [first, second] : kOpposites) {
        // A pair is registered from its first member, if the second one exists.
        if (last == first && names.count(prefix + stem + "-" + second)) {
          const std::string key = std::string(category) + "/" + stem + "-" + first + "-" + second;
          draws[key].key = key;
          draws[key].opposite_pair = true;
          if (sides[key].count(side)) fail(MCON_ERROR_INVALID_ARGUMENT, "two target sets share the key '" + key + "'");
          sides[key][side] = {std::string(category) + "/" + name,
                              std::string(category) + "/" + prefix + stem + "-" + second};
          paired = true;
        } else if (last == second && names.count(prefix + stem + "-" + first)) {
          paired = true;  // registered with its first member
        }
      }
      if (paired) continue;
      const std::string key = std::string(category) + "/" + rest;
      draws[key].key = key;
      draws[key].opposite_pair = false;
      if (sides[key].count(side)) fail(MCON_ERROR_INVALID_ARGUMENT, "two target sets share the key '" + key + "'");
      sides[key][side] = {std::string(category) + "/" + name, ""};
    }
  }
  std::vector<LocalTargetDraw> out;
  for (auto& [key, draw] : draws) {
    auto& s = sides[key];
    if (s.count(0)) draw.sides.push_back(s[0]);
    if (s.count('l')) draw.sides.push_back(s['l']);
    if (s.count('r')) draw.sides.push_back(s['r']);
    // An unsided target and a sided one with the same key, or a single side, would break the
    // one-draw-per-key rule; the MakeHuman data has neither.
    if (draw.sides.size() != 1 && !(draw.sides.size() == 2 && !s.count(0)))
      fail(MCON_ERROR_INVALID_ARGUMENT, "targets of '" + key + "' are not one unsided target or an l-/r- pair");
    out.push_back(std::move(draw));
  }
  return out;
}

std::vector<TargetWeight> macro_target_weights(double gender, double age, double muscle, double body_weight,
                                               const std::array<double, 3>& ethnic) {
  const std::pair<const char*, double> genders[] = {{"female", 1.0 - gender}, {"male", gender}};
  double baby = 0, child = 0, young = 0, old = 0;
  if (age < 0.5) {
    baby = std::max(0.0, 1.0 - 5.333 * age);
    young = std::max(0.0, 3.2 * (age - 0.1875));
    child = std::max(0.0, std::min(1.0, 5.333 * age) - young);
  } else {
    old = 2.0 * age - 1.0;
    young = 1.0 - old;
  }
  const std::pair<const char*, double> ages[] = {{"baby", baby}, {"child", child}, {"young", young}, {"old", old}};
  const auto levels = [](double x) {
    const double lo = std::max(0.0, 1.0 - 2.0 * x), hi = std::max(0.0, 2.0 * x - 1.0);
    return std::array<std::pair<const char*, double>, 3>{{{"min", lo}, {"average", 1.0 - lo - hi}, {"max", hi}}};
  };
  const auto muscles = levels(muscle), weights = levels(body_weight);
  const std::pair<const char*, double> ethnics[] = {{"african", ethnic[0]}, {"asian", ethnic[1]}, {"caucasian", ethnic[2]}};

  std::vector<TargetWeight> out;
  for (const auto& [e, ew] : ethnics)
    for (const auto& [g, gw] : genders)
      for (const auto& [a, aw] : ages) {
        const double w = ew * gw * aw;
        if (w != 0.0) out.push_back({std::string("macrodetails/") + e + "-" + g + "-" + a, w});
      }
  for (const auto& [g, gw] : genders)
    for (const auto& [a, aw] : ages)
      for (const auto& [m, mw] : muscles)
        for (const auto& [b, bw] : weights) {
          const double w = gw * aw * mw * bw;
          if (w != 0.0)
            out.push_back({std::string("macrodetails/universal-") + g + "-" + a + "-" + m + "muscle-" + b + "weight", w});
        }
  return out;
}

MakeHumanPeople::MakeHumanPeople(const std::string& shared_dir)
    : targets_dir_(shared_dir + "/meshes/makehuman/targets") {
  io::MeshFileOptions options;
  options.face_end = kMakeHumanBodyFaces;
  base_ = io::read_mesh(shared_dir + "/meshes/makehuman/base.obj.gz", options);
  // Targets index the OBJ's vertices: the body must be exactly vertices 0..13379 in file order.
  bool identity = base_.mesh.num_vertices() == kMakeHumanBodyVertices;
  for (int v = 0; identity && v < base_.mesh.num_vertices(); ++v) identity = base_.mesh_to_file[v] == v;
  require(identity, MCON_ERROR_INVALID_ARGUMENT,
          "the MakeHuman body is not vertices 0.." + std::to_string(kMakeHumanBodyVertices - 1) + " of base.obj");
  draws_ = list_local_target_draws(targets_dir_);
}

PersonRecipe MakeHumanPeople::recipe(std::uint64_t seed, std::uint64_t index) const {
  const BenchRng rng(seed, index);
  PersonRecipe r;
  r.gender = rng.uniform("gender");
  r.age = rng.uniform("age", 0.375, 0.875);
  r.age_years = r.age < 0.5 ? 1.0 + 48.0 * r.age : 25.0 + 130.0 * (r.age - 0.5);
  r.muscle = rng.uniform("muscle");
  r.body_weight = rng.uniform("weight");
  // Dirichlet(1, 1, 1) = the spacings of two sorted uniforms.
  const double u1 = rng.uniform("ethnic-1"), u2 = rng.uniform("ethnic-2");
  const double lo = std::min(u1, u2), hi = std::max(u1, u2);
  r.ethnic = {lo, hi - lo, 1.0 - hi};
  r.targets = macro_target_weights(r.gender, r.age, r.muscle, r.body_weight, r.ethnic);

  for (const LocalTargetDraw& d : draws_) {
    const double v = d.opposite_pair ? rng.uniform("local:" + d.key, -kLocalRange, kLocalRange)
                                     : rng.uniform("local:" + d.key, 0.0, kLocalRange);
    const double asymmetry =
        d.sides.size() == 2 ? rng.uniform("asymmetry:" + d.key, -kAsymmetryRange, kAsymmetryRange) : 0.0;
    for (std::size_t s = 0; s < d.sides.size(); ++s) {
      const double w = s == 1 ? v + asymmetry : v;  // sides[1] is the right side of an l-/r- pair
      if (d.opposite_pair) {
        if (w > 0.0) r.targets.push_back({d.sides[s].second, w});
        else if (w < 0.0) r.targets.push_back({d.sides[s].first, -w});
      } else if (w > 0.0) {
        r.targets.push_back({d.sides[s].first, w});
      }
    }
  }
  return r;
}

TriMesh MakeHumanPeople::build(const PersonRecipe& recipe) const {
  for (const TargetWeight& t : recipe.targets)
    require(std::isfinite(t.weight), MCON_ERROR_NON_FINITE, "weight of target '" + t.target + "' is not finite");
  TriMesh mesh = base_.mesh;
  for (const TargetWeight& t : recipe.targets)
    add_morph_target(mesh.positions, load_morph_target(targets_dir_ + "/" + t.target + ".target.gz"), t.weight);
  return mesh;
}

void MakeHumanPeople::preload_targets() const {
  std::vector<std::string> paths;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(targets_dir_ + "/macrodetails", ec)) {
    const std::string path = entry.path().string();
    if (path.size() > 10 && path.compare(path.size() - 10, 10, kTargetSuffix) == 0) paths.push_back(path);
  }
  require(!ec, MCON_ERROR_IO, "cannot list '" + targets_dir_ + "/macrodetails': " + ec.message());
  for (const LocalTargetDraw& d : draws_)
    for (const auto& side : d.sides)
      for (const std::string* name : {&side.first, &side.second})
        if (!name->empty()) paths.push_back(targets_dir_ + "/" + *name + ".target.gz");
  tbb::parallel_for(std::size_t(0), paths.size(), [&](std::size_t i) { load_morph_target(paths[i]); });
}

}  // namespace mcon::tools
