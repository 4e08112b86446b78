#include "common/bench_spec.h"

#include <algorithm>
#include <cmath>

#include "json/json_file.h"
#include "base/error.h"

namespace mcon::tools {

namespace {

[[noreturn]] void bad(const std::string& where, const std::string& what) {
  fail(MCON_ERROR_INVALID_ARGUMENT, where + ": " + what);
}

// Field access that names the file and the class in every error.
const Json& field(const Json& object, const std::string& key, const std::string& where) {
  if (!object.is_object()) bad(where, "expected an object");
  const Json* member = object.find(key);
  if (member == nullptr) bad(where, "missing field \"" + key + "\"");
  return *member;
}

int int_field(const Json& object, const std::string& key, const std::string& where) {
  const Json& v = field(object, key, where);
  long long value = 0;
  try {
    value = v.as_int();
  } catch (const Error& e) {
    bad(where, "field \"" + key + "\": " + e.what());
  }
  if (value < -2147483647LL || value > 2147483647LL) bad(where, "field \"" + key + "\" is out of range");
  return static_cast<int>(value);
}

double number_field(const Json& object, const std::string& key, const std::string& where) {
  const Json& v = field(object, key, where);
  if (!v.is_number()) bad(where, "field \"" + key + "\" must be a number");
  return v.as_number();
}

const std::string& string_field(const Json& object, const std::string& key, const std::string& where) {
  const Json& v = field(object, key, where);
  if (!v.is_string()) bad(where, "field \"" + key + "\" must be a string");
  return v.as_string();
}

bool bool_field(const Json& object, const std::string& key, const std::string& where) {
  const Json& v = field(object, key, where);
  if (!v.is_bool()) bad(where, "field \"" + key + "\" must be true or false");
  return v.as_bool();
}

BenchClass read_class(const std::string& name, const Json& c, bool alternative, const std::string& where) {
  BenchClass out;
  out.name = name;
  out.alternative = alternative;
  out.center_vertex = int_field(c, "center_vertex", where);
  out.radius = number_field(c, "radius", where);
  out.fill_holes = bool_field(c, "fill_holes", where);
  out.approx_vertices = int_field(c, "approx_vertices", where);
  const std::string& side = string_field(c, "side", where);
  if (side == "left") out.side = BenchSide::Left;
  else if (side == "right") out.side = BenchSide::Right;
  else if (side == "none") out.side = BenchSide::None;
  else bad(where, "side must be left, right or none, not \"" + side + "\"");
  // Class name = part + "_l" / "_r" exactly when the class has a side.
  const auto ends_with = [&](const char* suffix) {
    return name.size() > 2 && name.compare(name.size() - 2, 2, suffix) == 0;
  };
  const bool suffix_l = ends_with("_l"), suffix_r = ends_with("_r");
  if ((out.side == BenchSide::Left) != suffix_l || (out.side == BenchSide::Right) != suffix_r)
    bad(where, "side \"" + side + "\" does not match the name's _l/_r suffix");
  out.part = out.side == BenchSide::None ? name : name.substr(0, name.size() - 2);
  if (!(out.radius > 0.0)) bad(where, "radius must be positive");
  if (out.center_vertex < 0) bad(where, "center_vertex must be >= 0");
  if (out.approx_vertices <= 0) bad(where, "approx_vertices must be positive");
  return out;
}

void read_classes(const Json& root, const char* section, bool alternative, const std::string& path,
                  std::vector<BenchClass>& out) {
  const Json* classes = root.find(section);
  if (classes == nullptr) {
    if (alternative) return;  // alternatives are optional
    bad(path, std::string("missing field \"") + section + "\"");
  }
  if (!classes->is_object()) bad(path, std::string("\"") + section + "\" must be an object");
  for (std::size_t i = 0; i < classes->size(); ++i)
    out.push_back(read_class(classes->key(i), classes->value(i), alternative,
                             path + ": class \"" + classes->key(i) + "\""));
}

void read_patch_lists(const Json& root, const char* section, bool alternative, const std::string& path,
                      std::vector<BenchPatch>& out) {
  const Json* lists = root.find(section);
  if (lists == nullptr) {
    if (alternative) return;
    bad(path, std::string("missing field \"") + section + "\"");
  }
  if (!lists->is_object()) bad(path, std::string("\"") + section + "\" must be an object");
  for (std::size_t i = 0; i < lists->size(); ++i) {
    const std::string where = path + ": patch \"" + lists->key(i) + "\"";
    const Json& list = lists->value(i);
    if (!list.is_array()) bad(where, "expected an array of vertex indices");
    BenchPatch patch;
    patch.name = lists->key(i);
    patch.alternative = alternative;
    patch.vertices.reserve(list.size());
    for (const Json& v : list.elements()) {
      if (!v.is_number() || !(v.as_number() >= 0 && v.as_number() <= 2147483647.0) ||
          v.as_number() != std::floor(v.as_number()))
        bad(where, "vertex indices must be integers in [0, 2^31)");
      patch.vertices.push_back(static_cast<int>(v.as_number()));
    }
    for (std::size_t k = 1; k < patch.vertices.size(); ++k)
      if (patch.vertices[k] <= patch.vertices[k - 1]) bad(where, "vertex indices must be sorted and unique");
    if (patch.vertices.empty()) bad(where, "empty patch");
    out.push_back(std::move(patch));
  }
}

}  // namespace

const char* bench_side_name(BenchSide side) {
  switch (side) {
    case BenchSide::Left: return "left";
    case BenchSide::Right: return "right";
    case BenchSide::None: return "none";
  }
  return "?";
}

const BenchClass& BenchSpec::find(std::string_view name) const {
  for (const auto* list : {&classes, &alternatives})
    for (const BenchClass& c : *list)
      if (c.name == name) return c;
  fail(MCON_ERROR_NOT_FOUND, "no bench class \"" + std::string(name) + "\"");
}

const BenchPatch& BenchPatches::find(std::string_view name) const {
  for (const BenchPatch& p : patches)
    if (p.name == name) return p;
  fail(MCON_ERROR_NOT_FOUND, "no bench patch \"" + std::string(name) + "\"");
}

BenchSpec read_bench_spec(const std::string& landmarks_path) {
  const Json root = read_json_file(landmarks_path);
  const std::string& path = landmarks_path;
  if (!root.is_object()) bad(path, "expected a JSON object");
  BenchSpec spec;
  spec.mesh = string_field(root, "mesh", path);
  spec.patches_file = string_field(root, "patches_file", path);
  const Json& surface = field(root, "surface", path);
  spec.surface_vertices = int_field(surface, "vertices", path + ": surface");
  spec.surface_faces = int_field(surface, "faces", path + ": surface");
  if (spec.surface_vertices <= 0 || spec.surface_faces <= 0) bad(path, "surface counts must be positive");
  read_classes(root, "classes", false, path, spec.classes);
  read_classes(root, "alternatives", true, path, spec.alternatives);
  for (const auto* list : {&spec.classes, &spec.alternatives})
    for (const BenchClass& c : *list)
      if (c.center_vertex >= spec.surface_vertices)
        bad(path + ": class \"" + c.name + "\"",
            "center_vertex " + std::to_string(c.center_vertex) + " is outside the surface's " +
                std::to_string(spec.surface_vertices) + " vertices");
  return spec;
}

BenchPatches read_bench_patches(const std::string& patches_path) {
  const Json root = read_json_file(patches_path);
  if (!root.is_object()) bad(patches_path, "expected a JSON object");
  BenchPatches out;
  out.mesh = string_field(root, "mesh", patches_path);
  read_patch_lists(root, "classes", false, patches_path, out.patches);
  read_patch_lists(root, "alternatives", true, patches_path, out.patches);
  return out;
}

BenchModelData read_bench_model(const std::string& shared_dir, const std::string& model) {
  BenchModelData data;
  const std::string landmarks = shared_dir + "/bench/" + model + "-landmarks.json";
  data.spec = read_bench_spec(landmarks);
  const std::string patches = shared_dir + "/" + data.spec.patches_file;
  data.patches = read_bench_patches(patches);
  if (data.patches.mesh != data.spec.mesh)
    bad(patches, "mesh \"" + data.patches.mesh + "\" differs from the landmarks' \"" + data.spec.mesh + "\"");
  for (const auto* list : {&data.spec.classes, &data.spec.alternatives})
    for (const BenchClass& c : *list) {
      const std::string where = patches + ": patch \"" + c.name + "\"";
      const BenchPatch* patch = nullptr;
      for (const BenchPatch& p : data.patches.patches)
        if (p.name == c.name) patch = &p;
      if (patch == nullptr) bad(where, "missing");
      if (patch->vertices.back() >= data.spec.surface_vertices) bad(where, "vertex index outside the surface");
      if (!std::binary_search(patch->vertices.begin(), patch->vertices.end(), c.center_vertex))
        bad(where, "does not contain its center vertex " + std::to_string(c.center_vertex));
    }
  return data;
}

}  // namespace mcon::tools
