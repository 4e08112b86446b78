// Macrocon sample (C++17 wrapper, macrocon.hpp): the plugin integration pattern of
// samples/c/transfer_fields.c, plus the constraints a quad mesher needs: the entry's guide and
// feature polylines re-traced on the region, and a cross field that follows them, written as a
// QuadWild `.rosy` next to the region's triangles.
//
//   transfer_guides LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT_PREFIX
//
// writes OUT_PREFIX.ply (the host with the transferred per-vertex fields), OUT_PREFIX_guides.obj
// (polylines as OBJ 'l' elements, host units), OUT_PREFIX_region.obj + OUT_PREFIX_region.rosy
// (`quadwild region.obj region.rosy` remeshes the region along the guides).
//
// Every failing SDK call throws macrocon::Error (status + the SDK's message); objects release
// their handles in their destructors, so the only explicit cleanup is macrocon::shutdown() after
// every object is gone. The OBJ reader / PLY writer (samples/common) are sample helpers.
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "macrocon/macrocon.hpp"
#include "sample_mesh.h"

namespace {

// The host as the sample helper reads it, owned by a vector-backed struct.
struct HostMesh {
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  std::size_t vertex_count() const { return positions.size() / 3; }
};

HostMesh read_host(const std::string& path) {
  sample_mesh m;
  char error[512];
  if (sample_mesh_read_obj(path.c_str(), &m, error, sizeof(error)) != 0) throw std::runtime_error(error);
  HostMesh h;
  h.positions.assign(m.positions, m.positions + 3 * m.vertex_count);
  h.indices.assign(m.indices, m.indices + 3 * m.triangle_count);
  sample_mesh_free(&m);
  return h;
}

void write_guides_obj(const std::string& path, const macrocon::PolylineSet& guides) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  const macrocon::SurfacePoints points = guides.points();  // xyz in the region's host units
  const std::vector<std::uint32_t> sizes = guides.sizes();
  const std::vector<std::uint8_t> closed = guides.closed();
  char line[96];
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\n", points.xyz[3 * i], points.xyz[3 * i + 1], points.xyz[3 * i + 2]);
    out << line;
  }
  std::size_t first = 1;
  for (std::size_t p = 0; p < sizes.size(); ++p) {
    out << 'l';
    for (std::uint32_t k = 0; k < sizes[p]; ++k) out << ' ' << first + k;
    if (closed[p]) out << ' ' << first;
    out << '\n';
    first += sizes[p];
  }
}

// The region's triangles in host units (host = center + radius * p), the faces the .rosy numbers.
void write_region_obj(const std::string& path, const macrocon::Patch& region) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
  const mcon_patch_info info = region.info();
  const std::vector<double> p = region.positions();
  const std::vector<std::uint32_t> t = region.triangles();
  char line[96];
  for (std::size_t v = 0; v < info.vertex_count; ++v) {
    std::snprintf(line, sizeof(line), "v %.9g %.9g %.9g\n", info.center[0] + info.radius * p[3 * v],
                  info.center[1] + info.radius * p[3 * v + 1], info.center[2] + info.radius * p[3 * v + 2]);
    out << line;
  }
  for (std::size_t f = 0; f < info.triangle_count; ++f)
    out << "f " << t[3 * f] + 1 << ' ' << t[3 * f + 1] + 1 << ' ' << t[3 * f + 2] + 1 << '\n';
}

int run(const std::string& library_path, const std::string& host_path, std::uint32_t center_vertex, double radius,
        const std::string& prefix) {
  if (!macrocon::is_compatible())
    throw std::runtime_error("libmacrocon " + macrocon::library_version().to_string() +
                             " is not ABI-compatible with this build (" + macrocon::header_version().to_string() + ")");
  const HostMesh host_arrays = read_host(host_path);

  const macrocon::Context context;
  const macrocon::Mesh host = macrocon::Mesh::from_arrays(context, host_arrays.positions, host_arrays.indices);
  const macrocon::Patch region = macrocon::Patch::extract(host, macrocon::PatchOptions::at_vertex(center_vertex, radius));
  const macrocon::Library library = macrocon::Library::open(context, library_path);

  // Suggestions, best first.
  const std::vector<macrocon::QueryHit> hits = library.query(region, 3);
  if (hits.empty()) throw std::runtime_error("the library is empty");
  for (std::size_t i = 0; i < hits.size(); ++i)
    std::printf("suggestion %zu: id %llu, class %s, distance %.4f\n", i + 1, static_cast<unsigned long long>(hits[i].id),
                library.entry_string(hits[i].index, MCON_ENTRY_CLASS_LABEL, 0).c_str(), hits[i].distance);

  // The best entry as a patch, and the re-embedding map onto the region.
  const std::size_t best = hits.front().index;
  const mcon_library_entry_info info = library.entry_info(best);
  const macrocon::EntryData entry = library.entry(best);
  const macrocon::Patch source = macrocon::patch_from_arrays(
      context, library.entry_positions(best), library.entry_triangles(best), info.center.face,
      {{info.center.barycentric[0], info.center.barycentric[1], info.center.barycentric[2]}},
      {{info.source_origin[0], info.source_origin[1], info.source_origin[2]}}, info.source_scale);
  const macrocon::Map map = macrocon::Map::compute(source, region);
  const mcon_map_info m = map.info();
  std::printf("using %s (licence %s): overlap %.3f, matching score %.3f, %s, %u flipped triangles\n",
              entry.name.c_str(), entry.licence.c_str(), m.overlap_ratio, m.matching_score,
              m.reflected ? "mirrored" : "not mirrored", m.flipped_triangles);

  // Fields onto the region, then onto the host vertices the region keeps (v0 == v1, t == 0).
  const macrocon::HostVertices links = region.host_vertices();
  const std::vector<std::uint8_t> outside = map.outside_mask();
  const std::size_t nh = host_arrays.vertex_count(), nr = links.v0.size();
  auto carries_value = [&](std::size_t i) {
    return links.v0[i] == links.v1[i] && links.v0[i] != MCON_INVALID_INDEX && links.t[i] == 0 && !outside[i];
  };
  std::vector<std::vector<double>> host_values;
  std::vector<sample_ply_attribute> attributes;
  host_values.emplace_back(nh, 0.0);
  for (std::size_t i = 0; i < nr; ++i)
    if (carries_value(i)) host_values[0][links.v0[i]] = 1;
  for (const macrocon::VertexField& field : entry.fields) {
    std::vector<double> values;
    if (field.kind == MCON_FIELD_INTEGER_LABEL) {
      for (std::int32_t l : map.transfer_labels(field.dimension, field.labels, -1)) values.push_back(l);
    } else {
      values = map.transfer_field(static_cast<mcon_field_kind>(field.kind), field.dimension, field.values);
    }
    std::vector<double> on_host(nh * field.dimension, 0.0);
    for (std::size_t i = 0; i < nr; ++i)
      if (carries_value(i))
        for (std::uint32_t c = 0; c < field.dimension; ++c)
          on_host[links.v0[i] * field.dimension + c] = values[i * field.dimension + c];
    host_values.push_back(std::move(on_host));
  }
  attributes.push_back({"macro_mask", 1, host_values[0].data()});
  for (std::size_t f = 0; f < entry.fields.size(); ++f)
    attributes.push_back({entry.fields[f].name.c_str(), entry.fields[f].dimension, host_values[f + 1].data()});
  sample_mesh out_mesh{const_cast<float*>(host_arrays.positions.data()), const_cast<std::uint32_t*>(host_arrays.indices.data()),
                       nh, host_arrays.indices.size() / 3};
  if (sample_ply_write((prefix + ".ply").c_str(), &out_mesh, attributes.data(), attributes.size()) != 0)
    throw std::runtime_error("cannot write '" + prefix + ".ply'");

  // Guides and features: mapped through the map and re-traced on the region's triangles.
  std::vector<std::uint32_t> triangles, sizes;
  std::vector<double> barycentric;
  std::vector<std::uint8_t> closed;
  for (const macrocon::Polyline& line : entry.polylines) {
    for (const mcon_surface_point& p : line.points) {
      triangles.push_back(p.face);
      barycentric.insert(barycentric.end(), {p.barycentric[0], p.barycentric[1], p.barycentric[2]});
    }
    sizes.push_back(static_cast<std::uint32_t>(line.points.size()));
    closed.push_back(line.closed ? 1 : 0);
  }
  const macrocon::PolylineSet guides = map.transfer_polylines(triangles, barycentric, sizes, closed);
  write_guides_obj(prefix + "_guides.obj", guides);

  // A cross field on the region that follows them, for QuadWild.
  const macrocon::CrossField cross = macrocon::compute_cross_field(region, guides);
  write_region_obj(prefix + "_region.obj", region);
  macrocon::write_rosy(region, cross.directions, prefix + "_region.rosy");
  std::printf("%zu fields onto the host, %zu of %zu polylines re-traced (%zu points), cross field on %zu triangles -> %s.*\n",
              entry.fields.size(), guides.polyline_count(), entry.polylines.size(), guides.point_count(),
              cross.confidence.size(), prefix.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: transfer_guides LIBRARY.mclb HOST.obj[.gz] CENTER_VERTEX RADIUS OUT_PREFIX\n");
    return 2;
  }
  int status = 1;
  try {
    status = run(argv[1], argv[2], static_cast<std::uint32_t>(std::stoul(argv[3])), std::stod(argv[4]), argv[5]);
  } catch (const macrocon::Error& e) {
    // A plugin shows this to the user; NOT_A_DISK means "try a smaller radius".
    std::fprintf(stderr, "transfer_guides: %s: %s\n", macrocon::status_name(e.status()).c_str(), e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "transfer_guides: %s\n", e.what());
  }
  // Every macrocon object above has been destroyed by now.
  mcon_shutdown();
  return status;
}
