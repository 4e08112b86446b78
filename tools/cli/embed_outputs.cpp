// `macrocon embed`'s files and summary (embed_stages.h, stages 5 and 6): target mesh units
// throughout (host = center + radius * p).
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <tuple>
#include <utility>

#include "embed_stages.h"
#include "guide_turning.h"
#include "json/json_file.h"

namespace mcon::cli {
namespace {

void write_polylines_obj(const std::string& path, const std::vector<std::vector<Vec3>>& lines,
                         const std::vector<bool>& closed) {
  std::ostringstream s;
  s.precision(9);
  s << "# macrocon embed: polylines as OBJ lines\n";
  for (const auto& line : lines)
    for (const Vec3& x : line) s << "v " << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
  std::size_t first = 1;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    s << 'l';
    for (std::size_t k = 0; k < lines[i].size(); ++k) s << ' ' << first + k;
    if (closed[i]) s << ' ' << first;
    s << '\n';
    first += lines[i].size();
  }
  io::write_file_maybe_gz(path, s.str());
}

// The target patch in host units with the transferred per-vertex fields.
void write_target_ply(const std::string& ply, const EmbedPatches& e, const EmbedTransfer& x) {
  const PatchGeometry& g = e.target_geometry;
  TriMesh target_host = g.mesh;
  for (Vec3& v : target_host.positions) v = g.to_host(v);
  std::vector<io::VertexAttribute> attributes = field_attributes(x.fields);
  io::VertexAttribute out_attr{"outside", 1, {}}, host_vertex{"host_vertex", 1, {}};
  const macrocon::HostVertices host = e.target.host_vertices();
  for (std::size_t w = 0; w < host.v0.size(); ++w) {
    out_attr.values.push_back(x.outside[w]);
    const std::uint32_t h = host.t[w] < 0.5 ? host.v0[w] : host.v1[w];
    host_vertex.values.push_back(host.v0[w] == MCON_INVALID_INDEX ? -1.0
                                                                  : static_cast<double>(e.target_mesh.mesh_to_file[h]));
  }
  attributes.push_back(std::move(out_attr));
  attributes.push_back(std::move(host_vertex));
  io::write_ply(ply, target_host, attributes);
  // The same triangles as OBJ with exact doubles (QuadWild reads OBJ), next to the PLY.
  io::write_obj(ply.substr(0, ply.size() - 4) + ".obj", target_host);
}

// The mapped singularities as the table `library build --singularities` reads (x, y, z, index in
// target mesh units); those the map sends outside the target are left out (the summary counts them).
void write_singularities_csv(const std::string& path, const EmbedTransfer& x) {
  std::ostringstream s;
  s.precision(17);
  s << "x,y,z,index\n";
  for (std::size_t i = 0; i < x.singularities.size(); ++i) {
    if (x.singularities.triangles[i] == MCON_INVALID_INDEX) continue;
    const double* p = &x.singularities.xyz[3 * i];
    s << p[0] << ',' << p[1] << ',' << p[2] << ',' << x.source.singularities[i].index_quarters << '\n';
  }
  io::write_file_maybe_gz(path, s.str());
}

// The traced polylines in target host units, in trace order; `feature` marks the traces of features.
struct HostLines {
  std::vector<std::vector<Vec3>> lines;
  std::vector<bool> closed, feature;
};

HostLines traced_in_host_units(const EmbedTransfer& x) {
  HostLines h;
  std::size_t at = 0;
  for (std::size_t i = 0; i < x.traced.sizes.size(); ++i) {
    std::vector<Vec3> line;
    for (std::size_t k = 0; k < x.traced.sizes[i]; ++k, ++at)
      line.emplace_back(x.traced.points.xyz[3 * at], x.traced.points.xyz[3 * at + 1], x.traced.points.xyz[3 * at + 2]);
    h.lines.push_back(std::move(line));
    h.closed.push_back(x.traced.closed[i] != 0);
    h.feature.push_back(x.traced.inputs[i] >= x.source.guide_count);
  }
  return h;
}

// The traced guides (`features` false) or the traced features as an OBJ of lines.
void write_traced_obj(const std::string& path, const HostLines& traced, bool features) {
  std::vector<std::vector<Vec3>> lines;
  std::vector<bool> closed;
  for (std::size_t i = 0; i < traced.lines.size(); ++i)
    if (traced.feature[i] == features) {
      lines.push_back(traced.lines[i]);
      closed.push_back(traced.closed[i]);
    }
  write_polylines_obj(path, lines, closed);
}

// The source's polylines in source host units.
std::vector<std::vector<Vec3>> source_in_host_units(const EmbedPatches& e, const EmbedTransfer& x) {
  std::vector<std::vector<Vec3>> out;
  for (const macrocon::Polyline& in : x.source.polylines) {
    std::vector<Vec3> line;
    for (const mcon_surface_point& q : in.points)
      line.push_back(e.source_geometry.to_host(e.source_geometry.position(q)));
    out.push_back(std::move(line));
  }
  return out;
}

std::vector<bool> closed_flags(const std::vector<macrocon::Polyline>& lines) {
  std::vector<bool> out;
  for (const macrocon::Polyline& l : lines) out.push_back(l.closed);
  return out;
}

void compute_cut(const EmbedOptions& o, const EmbedPatches& e, const EmbedTransfer& x, EmbedCut& c) {
  const auto t0 = std::chrono::steady_clock::now();
  c.cut = macrocon::CutMesh::cut(e.target, x.traced.set, o.snap, std::nullopt, static_cast<std::uint32_t>(o.fair_passes));
  c.info = c.cut.info();
  const std::vector<double> xyz = c.cut.positions();
  const std::vector<std::uint32_t> triangles = c.cut.triangles(), edges = c.cut.guide_edges();
  for (std::size_t v = 0; 3 * v < xyz.size(); ++v)
    c.host_units.positions.emplace_back(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
  for (std::size_t t = 0; 3 * t < triangles.size(); ++t)
    c.host_units.triangles.push_back({static_cast<int>(triangles[3 * t]), static_cast<int>(triangles[3 * t + 1]),
                                      static_cast<int>(triangles[3 * t + 2])});
  for (std::size_t i = 0; 2 * i < edges.size(); ++i)
    c.guide_edges.push_back({static_cast<int>(edges[2 * i]), static_cast<int>(edges[2 * i + 1])});
  c.guides = c.cut.guides();
  const std::vector<double> directions = c.cut.cross_field();
  for (std::size_t t = 0; 3 * t < directions.size(); ++t)
    c.field.emplace_back(directions[3 * t], directions[3 * t + 1], directions[3 * t + 2]);
  c.seconds = seconds_since(t0);
}

// The cut patch's vertex attributes: the transferred fields, 'outside' and 'guide' (1 on a guide edge).
std::vector<io::VertexAttribute> cut_attributes(const EmbedPatches& e, const EmbedTransfer& x, const EmbedCut& c) {
  CutHostPoints host;
  std::tie(host.triangles, host.barycentric) = c.cut.host_points();
  host.patch_triangles = e.target.triangles();
  std::vector<io::VertexAttribute> attributes = field_attributes(carry_fields(c.cut, host, x.fields));
  const std::vector<std::uint8_t> outside = carry_labels(host, x.outside);
  io::VertexAttribute out_attr{"outside", 1, {}}, guide{"guide", 1, {}};
  std::vector<double> on_guide(c.host_units.positions.size(), 0.0);
  for (const auto& edge : c.guide_edges)
    on_guide[static_cast<std::size_t>(edge[0])] = on_guide[static_cast<std::size_t>(edge[1])] = 1.0;
  for (std::size_t w = 0; w < on_guide.size(); ++w) {
    out_attr.values.push_back(outside[w]);
    guide.values.push_back(on_guide[w]);
  }
  attributes.push_back(std::move(out_attr));
  attributes.push_back(std::move(guide));
  return attributes;
}

tools::Json cut_summary(const EmbedCut& c) {
  tools::Json j = tools::Json::object();
  j.set("vertices", c.info.vertex_count);
  j.set("triangles", c.info.triangle_count);
  j.set("guide_edges", c.info.guide_edge_count);
  j.set("input_triangles_cut", c.info.cut_triangle_count);
  j.set("min_angle_created_degrees", c.info.min_angle_created);
  j.set("min_angle_of_cut_input_degrees", c.info.min_angle_of_cut_input);
  j.set("snapped_to_vertices", c.info.snapped_to_vertices);
  j.set("merged_crossings", c.info.merged_crossings);
  j.set("dropped_points", c.info.dropped_points);
  j.set("shortcuts", c.info.shortcuts);
  j.set("moved_vertices", c.info.moved_vertices);
  j.set("faired_vertices", c.info.faired_vertices);
  j.set("seconds", c.seconds);
  return j;
}

// Where the constraints came from, the fields transferred and where each singularity landed.
tools::Json source_summary(const EmbedPatches& e, const EmbedTransfer& x) {
  using tools::Json;
  Json j = Json::object();
  j.set("kind", e.entry ? "library_entry" : "mesh (synthetic constraints)");
  if (e.entry) {
    j.set("entry_id", std::to_string(e.entry->id));
    j.set("entry_name", e.entry->name);
    j.set("entry_class", e.entry->class_label);
  }
  Json fields = Json::array();
  for (const macrocon::VertexField& f : x.fields) fields.push_back(f.name);
  j.set("fields", fields);
  Json singularities = Json::array();
  for (std::size_t i = 0; i < x.singularities.size(); ++i) {
    const bool on_target = x.singularities.triangles[i] != MCON_INVALID_INDEX;
    Json s = Json::object();
    s.set("index_quarters", x.source.singularities[i].index_quarters);
    s.set("on_target", on_target);
    if (on_target) {
      Json xyz = Json::array();
      for (std::size_t k = 0; k < 3; ++k) xyz.push_back(x.singularities.xyz[3 * i + k]);
      s.set("position", xyz);
    }
    singularities.push_back(s);
  }
  j.set("singularities", singularities);
  return j;
}

const char* stop_reason_name(std::uint32_t reason) {
  switch (reason) {
    case MCON_MAP_STOP_CONVERGED:
      return "converged";
    case MCON_MAP_STOP_STALLED:
      return "stalled";
    case MCON_MAP_STOP_ITERATION_CAP:
      return "iteration_cap";
    case MCON_MAP_STOP_CANCELLED:
      return "cancelled";
    default:
      return "unknown";
  }
}

tools::Json timings_summary(const EmbedMap& m, const EmbedTransfer& x, double patch_seconds,
                            std::chrono::steady_clock::time_point t_start) {
  tools::Json timings = tools::Json::object();
  timings.set("patches", patch_seconds);
  timings.set("map", m.map_seconds);
  timings.set("alignment", m.info.alignment_seconds);
  timings.set("optimization", m.info.optimization_seconds);
  timings.set("transfer", x.transfer_seconds);  // the next four together
  timings.set("source_constraints", x.source_field_seconds);
  timings.set("fields", x.field_seconds);
  timings.set("polylines", x.polyline_seconds);
  timings.set("cross_field", x.cross_field_seconds);
  timings.set("total", seconds_since(t_start));
  return timings;
}

tools::Json files_summary(const EmbedFiles& f) {
  tools::Json files = tools::Json::object();
  files.set("target_ply", f.ply);
  files.set("target_obj", f.ply.substr(0, f.ply.size() - 4) + ".obj");
  files.set("guides_obj", f.obj);
  files.set("source_guides_obj", f.src_obj);
  if (!f.features_obj.empty()) files.set("features_obj", f.features_obj);
  if (!f.singularities_csv.empty()) files.set("singularities_csv", f.singularities_csv);
  files.set("rosy", f.rosy);
  return files;
}

}  // namespace

EmbedFiles write_embed_files(const std::string& out_dir, const EmbedPatches& e, const EmbedTransfer& x) {
  std::filesystem::create_directories(out_dir);
  EmbedFiles f;
  f.ply = out_dir + "/target.ply";
  f.obj = out_dir + "/guides.obj";
  f.src_obj = out_dir + "/source_guides.obj";
  f.rosy = out_dir + "/target.rosy";
  f.summary_path = out_dir + "/summary.json";
  write_target_ply(f.ply, e, x);
  // Traced guides and traced features go to their own files; the source's all to one.
  const HostLines traced = traced_in_host_units(x);
  f.traced_points = x.traced.points.size();
  write_traced_obj(f.obj, traced, false);
  if (x.source.polylines.size() > x.source.guide_count) {
    f.features_obj = out_dir + "/features.obj";
    write_traced_obj(f.features_obj, traced, true);
  }
  write_polylines_obj(f.src_obj, source_in_host_units(e, x), closed_flags(x.source.polylines));
  if (!x.source.singularities.empty()) {
    f.singularities_csv = out_dir + "/singularities.csv";
    write_singularities_csv(f.singularities_csv, x);
  }
  macrocon::write_rosy(e.target, x.cross_field, f.rosy);
  return f;
}

EmbedCut cut_and_write(const EmbedOptions& o, const EmbedPatches& e, const EmbedTransfer& x) {
  EmbedCut c;
  compute_cut(o, e, x, c);
  c.obj = o.out_dir + "/target_cut.obj";
  c.ply = o.out_dir + "/target_cut.ply";
  c.sharp = o.out_dir + "/target_cut.sharp";
  c.rosy = o.out_dir + "/target_cut.rosy";
  io::write_obj(c.obj, c.host_units);
  io::write_ply(c.ply, c.host_units, cut_attributes(e, x, c));
  io::write_sharp(c.sharp, c.host_units, c.guide_edges);
  io::write_rosy(c.rosy, c.host_units, c.field);
  // The cut guides as OBJ lines through the cut mesh's own vertices (same numbering as target_cut.obj).
  c.guides_obj = o.out_dir + "/target_cut_guides.obj";
  // 17 digits: the vertices read back as target_cut.obj's (std::to_string would keep 6 decimals).
  std::ostringstream lines;
  lines.precision(17);
  lines << "# macrocon embed: the guides as chains of target_cut.obj's edges\n";
  for (const Vec3& v : c.host_units.positions) lines << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const std::vector<std::uint32_t>& chain : c.guides) {
    if (chain.size() < 2) continue;
    lines << 'l';
    for (std::uint32_t v : chain) lines << ' ' << v + 1;
    lines << '\n';
  }
  io::write_file_maybe_gz(c.guides_obj, lines.str());
  return c;
}

// Turning per length in host units (per unit length of the mesh files), so patches of different
// radii compare: the source's polylines, their traces and (with --cut-guides) the cut chains. The
// first two are measured on the normalized patches (exact points there, no host offset to round).
tools::Json turning_summary(const EmbedPatches& e, const EmbedTransfer& x, const EmbedCut* c) {
  std::vector<std::vector<Vec3>> source, traced;
  for (const macrocon::Polyline& in : x.source.polylines) {
    std::vector<Vec3> line;
    for (const mcon_surface_point& q : in.points) line.push_back(e.source_geometry.position(q));
    source.push_back(std::move(line));
  }
  std::size_t at = 0;
  for (std::uint32_t size : x.traced.sizes) {
    std::vector<Vec3> line;
    for (std::uint32_t k = 0; k < size; ++k, ++at) {
      const double* b = &x.traced.points.barycentric[3 * at];
      line.push_back(e.target_geometry.position({x.traced.points.triangles[at], {b[0], b[1], b[2]}}));
    }
    traced.push_back(std::move(line));
  }
  std::vector<bool> traced_closed(x.traced.closed.begin(), x.traced.closed.end());
  tools::Json j = tools::Json::object();
  const double s = mean_turning(source, closed_flags(x.source.polylines)) / e.source_geometry.radius,
               t = mean_turning(traced, traced_closed) / e.target_geometry.radius;
  j.set("source", s);
  j.set("traced", t);
  j.set("traced_ratio", s > 0 ? t / s : 0.0);
  if (c) {
    std::vector<std::vector<Vec3>> cut;
    std::vector<bool> cut_closed;
    for (const std::vector<std::uint32_t>& chain : c->guides) {
      std::vector<Vec3> line;
      for (std::uint32_t v : chain) line.push_back(c->host_units.positions[v]);
      // A closed chain repeats its first vertex: drop it and measure it closed.
      const bool is_closed = chain.size() > 2 && chain.front() == chain.back();
      if (is_closed) line.pop_back();
      cut.push_back(std::move(line));
      cut_closed.push_back(is_closed);
    }
    const double k = mean_turning(cut, cut_closed);
    j.set("cut", k);
    j.set("cut_ratio", s > 0 ? k / s : 0.0);
  }
  return j;
}

// 6. Summary.
tools::Json embed_summary(const EmbedOptions& o, const EmbedPatches& e, const EmbedMap& m, const EmbedTransfer& x,
                          const EmbedFiles& f, double patch_seconds, std::chrono::steady_clock::time_point t_start) {
  using tools::Json;
  const mcon_map_info& info = m.info;
  Json energies = Json::object();
  energies.set("total", info.energy_total);
  for (const auto& [name, value] : m.map.energy_terms()) energies.set(name, value);
  Json summary = Json::object();
  summary.set("source_vertices", info.source_vertex_count);
  summary.set("target_vertices", info.target_vertex_count);
  summary.set("source_vertices_inside", info.source_vertices_inside);
  summary.set("target_vertices_inside", info.target_vertices_inside);
  summary.set("overlap", info.overlap_ratio);
  summary.set("matching_score", info.matching_score);
  summary.set("alignment_score", info.alignment_score);
  summary.set("energies", energies);
  summary.set("iterations", info.iterations);
  summary.set("levels", info.levels);
  summary.set("stop_reason", stop_reason_name(info.stop_reason));
  summary.set("reflected", info.reflected != 0);
  // The evidence of the orientation call, for a host that offers a "flip" (--orientation).
  summary.set("orientation", o.orientation);
  summary.set("landmarks", static_cast<double>(m.landmarks));
  summary.set("up_hints", o.source_up.has_value());
  summary.set("up_from_entry", o.up_from_entry);
  summary.set("alignment_score_unreflected", info.alignment_score_unreflected);
  summary.set("alignment_score_reflected", info.alignment_score_reflected);
  summary.set("orientation_compared", info.orientation_compared != 0);
  summary.set("level0_energy_unreflected", info.level0_energy_unreflected);
  summary.set("level0_energy_reflected", info.level0_energy_reflected);
  summary.set("flips", info.flipped_triangles);
  std::size_t features_out = 0;
  for (std::uint32_t input : x.traced.inputs) features_out += input >= x.source.guide_count;
  summary.set("guides_in", x.source.guide_count);
  summary.set("guides_out", x.traced.inputs.size() - features_out);
  summary.set("features_in", x.source.polylines.size() - x.source.guide_count);
  summary.set("features_out", features_out);
  summary.set("source_constraints", source_summary(e, x));
  summary.set("guide_points_out", f.traced_points);
  summary.set("center_on_target", x.center_on_target);
  summary.set("timings", timings_summary(m, x, patch_seconds, t_start));
  summary.set("files", files_summary(f));
  return summary;
}

// With --cut-guides: the cut's summary, its files and QuadWild's command lines for it.
void add_cut_summary(const EmbedCut& cut, tools::Json& summary) {
  summary.set("cut", cut_summary(cut));
  tools::Json files = summary.at("files");
  files.set("cut_obj", cut.obj);
  files.set("cut_ply", cut.ply);
  files.set("cut_sharp", cut.sharp);
  files.set("cut_rosy", cut.rosy);
  files.set("cut_guides_obj", cut.guides_obj);
  summary.set("files", files);
  // Run in the output folder; <quadwild> is its build.
  tools::Json commands = tools::Json::array();
  commands.push_back(
      std::string("quadwild target_cut.obj 2 target_cut.rosy target_cut.sharp "
                  "<quadwild>/config/prep_config/basic_setup.txt"));
  commands.push_back(
      std::string("quad_from_patches target_cut_rem_p0.obj 123 "
                  "<quadwild>/config/main_config/flow_noalign_lemon.txt"));
  summary.set("quadwild_commands", commands);
}

void print_report(const EmbedOptions& o, const EmbedMap& m, const EmbedTransfer& x, const EmbedFiles& f,
                  const EmbedCut* cut) {
  const mcon_map_info& info = m.info;
  std::printf("map: %zu -> %zu vertices, overlap %.3f, %u iterations (%s), %s, %u flips, %.2f s\n",
              info.source_vertex_count, info.target_vertex_count, info.overlap_ratio, info.iterations,
              stop_reason_name(info.stop_reason), info.reflected ? "reflected" : "not reflected",
              info.flipped_triangles, m.map_seconds);
  std::printf(
      "constraints: %zu guides and features in, %zu out (%zu points), %zu singularities, %zu fields; files in %s\n",
      x.source.polylines.size(), x.traced.inputs.size(), f.traced_points, x.source.singularities.size(),
      x.fields.size(), o.out_dir.c_str());
  if (cut)
    std::printf("cut: %zu vertices, %zu triangles, %zu guide edges, smallest angle made %.1f degrees\n",
                cut->info.vertex_count, cut->info.triangle_count, cut->info.guide_edge_count,
                cut->info.min_angle_created);
}

}  // namespace mcon::cli
