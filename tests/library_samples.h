// Small, valid constraint libraries for the library tests and the fuzzer's seed corpus: every
// kind of constraint and field, and values that catch lossy round trips (-0.0, subnormals).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "library/constraint_library.h"
#include "test_meshes.h"

namespace mcon::test_samples {

// d = 2, k = 3, two rings: histograms of 6 values. A custom descriptor: built-in ones fix d.
inline RetrievalConfig sample_config() {
  RetrievalConfig c;
  c.descriptor = "custom:test";
  c.dimension = 2;
  c.normalization_mean = {0.5, -0.0};
  c.normalization_scale = {2.0, 0.125};
  c.vocabulary_size = 3;
  c.vocabulary = {0.1, -0.2, 1.0 / 3.0, 0.0, -1.5, 2.5e-310};
  c.sigma_bof = 0.3;
  c.rings = 2;
  c.seed = 0x0123456789abcdefull;
  return c;
}

// A disk patch (make_disk(rings): 19 vertices for 2 rings, 7 for 1) with `id`; with `full`, every
// constraint type and field kind.
inline MacroConstraint sample_entry(const RetrievalConfig& config, std::uint64_t id, int rings, bool full,
                                    const std::string& name = "nose_07") {
  MacroConstraint e;
  e.id = id;
  e.name = name;
  e.class_label = "nose";
  set_entry_mesh(e, test_meshes::make_disk(rings));
  const std::size_t n = e.vertex_count();
  e.center = {0, {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}};
  e.source_scale = 0.031;
  e.source_origin = {1.25, -0.0, 3.0e-5};
  if (full) {
    e.tags = {"face", "symmetric", ""};
    e.author = "Vendor GmbH";
    e.licence = "CC-BY-4.0";
    e.guides.push_back({{{0, {1, 0, 0}}, {1, {0.25, 0.25, 0.5}}, {2, {0, -0.0, 1}}}, false});
    e.features.push_back({{{3, {0.5, 0.5, 0}}, {4, {0.2, 0.3, 0.5}}, {5, {0, 0.5, 0.5}}}, true});
    e.singularities.push_back({{0, {0.5, 0.25, 0.25}}, 1});
    e.singularities.push_back({{2, {0.1, 0.1, 0.8}}, -1});
    VertexField sizing{"sizing", FieldKind::scalar, 1, {}, {}};
    VertexField direction{"direction", FieldKind::tangent_vector, 3, {}, {}};
    VertexField normal{"normal", FieldKind::vector3, 3, {}, {}};
    VertexField uv{"uv", FieldKind::uv, 2, {}, {}};
    VertexField region{"region", FieldKind::integer_label, 1, {}, {}};
    for (std::size_t v = 0; v < n; ++v) {
      sizing.values.push_back(0.5f + static_cast<float>(v));
      direction.values.insert(direction.values.end(), {1.0f, 0.0f, -0.0f});
      normal.values.insert(normal.values.end(), {0.0f, 0.0f, 1.0f});
      uv.values.insert(uv.values.end(), {e.positions[3 * v], e.positions[3 * v + 1]});
      region.labels.push_back(static_cast<std::int32_t>(v % 3) - 1);
    }
    e.fields = {sizing, direction, normal, uv, region};
  }
  for (std::size_t i = 0; i < n * config.dimension; ++i)
    e.descriptors.push_back(i % 5 == 0   ? -0.0f
                            : i % 7 == 0 ? std::numeric_limits<float>::denorm_min()
                                         : 0.1f * static_cast<float>(i) - 1.0f);
  for (std::size_t i = 0; i < config.histogram_length(); ++i) e.histogram.push_back(0.125f * static_cast<float>(i));
  return e;
}

// Two entries: a full 19-vertex one (id 7) and a minimal 7-vertex one (id 9).
inline ConstraintLibrary sample_library() {
  ConstraintLibrary lib(sample_config());
  lib.set_name("Faces");
  lib.set_description("Sample library for tests");
  lib.add_entry(sample_entry(lib.retrieval(), 7, 2, true));
  lib.add_entry(sample_entry(lib.retrieval(), 9, 1, false, "eye_corner_01"));
  return lib;
}

// The smallest interesting library (for byte-by-byte corruption loops): one 7-vertex full entry.
inline ConstraintLibrary tiny_library() {
  ConstraintLibrary lib(sample_config());
  lib.add_entry(sample_entry(lib.retrieval(), 3, 1, true, "tip"));
  return lib;
}

}  // namespace mcon::test_samples
