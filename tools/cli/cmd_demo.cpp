// `macrocon demo`: the whole job on the bundled data, through the public C API (the same calls a
// plugin makes): the bundled MakeHuman body is queried at a few regions against the starter
// constraint library, the best match is re-embedded onto each region, its fields, guides and a
// guide-aligned cross field are transferred, and everything is written to --out:
//   <region>.ply          the region patch (host units) with the transferred per-vertex fields
//   <region>.obj          the same triangles for QuadWild, with <region>.rosy (its cross field)
//   <region>_guides.obj   the transferred guide and feature polylines ('l' elements)
// No ../shared data is needed. The starter library is found at bin/../share/macrocon/starter.mclb
// (build tree and installed layout alike) unless --library says otherwise.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "command/args.h"
#include "command/progress_bar.h"
#include "io/mesh_io.h"
#include "macrocon/macrocon.hpp"
#include "sdk_arrays.h"

namespace mcon::cli {
namespace {

using macrocon::check;

struct Region {
  const char* name;
  std::uint32_t center_vertex;
  double radius;
};

// Regions of the bundled body at other radii than the library entries, so the maps are not
// identities; the eye is queried on the left, where the library's nearest entries are both eyes.
const Region kRegions[] = {
    {"eye_l", 8021, 0.55}, {"mouth", 537, 0.6}, {"nose", 297, 0.45}, {"hand_r", 3197, 1.2}};
// --whole-host adds the other eye (vertex 1329 is 8021 mirrored in x), so both eyes, the nose,
// the mouth and the hand go into one field of the whole body.
const Region kOtherEye = {"eye_r", 1329, 0.55};

template <typename T, mcon_status (*Release)(T)>
struct Releaser {
  void operator()(T h) const { Release(h); }
};
using LibraryRef = std::unique_ptr<mcon_library_t, Releaser<mcon_library, mcon_library_release>>;
using MapRef = std::unique_ptr<mcon_map_t, Releaser<mcon_map, mcon_map_release>>;
using PolylinesRef = std::unique_ptr<mcon_polyline_set_t, Releaser<mcon_polyline_set, mcon_polyline_set_release>>;

std::string default_library_path() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "share/macrocon/starter.mclb";
  return (exe.parent_path().parent_path() / "share" / "macrocon" / "starter.mclb").string();
}

std::string entry_string(mcon_library lib, std::size_t index, mcon_entry_string which, std::size_t item = 0) {
  std::size_t size = 0;
  check(mcon_library_get_entry_string(lib, index, which, item, nullptr, 0, &size));
  std::string s(size, '\0');
  check(mcon_library_get_entry_string(lib, index, which, item, s.data(), s.size(), nullptr));
  s.resize(size > 0 ? size - 1 : 0);
  return s;
}

// The library entry as an mcon_patch (its arrays, center and frame).
macrocon::Patch entry_patch(const macrocon::Context& ctx, mcon_library lib, std::size_t index,
                            mcon_library_entry_info& info) {
  check(mcon_library_entry_info_init(&info));
  check(mcon_library_get_entry_info(lib, index, &info));
  std::vector<double> xyz(3 * info.vertex_count);
  std::vector<std::uint32_t> tris(3 * info.triangle_count);
  check(mcon_library_get_entry_positions(lib, index, xyz.data(), xyz.size()));
  check(mcon_library_get_entry_triangles(lib, index, tris.data(), tris.size()));
  mcon_mesh_desc d;
  check(mcon_mesh_desc_init(&d));
  d.positions = xyz.data();
  d.position_type = MCON_SCALAR_FLOAT64;
  d.vertex_count = info.vertex_count;
  d.indices = tris.data();
  d.triangle_count = info.triangle_count;
  mcon_patch_frame frame;
  check(mcon_patch_frame_init(&frame));
  frame.center_triangle = info.center.face;
  for (int k = 0; k < 3; ++k) {
    frame.center_barycentric[k] = info.center.barycentric[k];
    frame.origin[k] = info.source_origin[k];
  }
  frame.scale = info.source_scale;
  mcon_patch p = nullptr;
  check(mcon_patch_create_from_arrays(ctx.get(), &d, &frame, &p));
  return macrocon::Patch::adopt(p);
}

// Every polyline of the entry, mapped onto the target and re-traced there.
PolylinesRef transfer_polylines(mcon_library lib, std::size_t index, const mcon_library_entry_info& info,
                                mcon_map map) {
  std::vector<std::uint32_t> triangles, sizes;
  std::vector<double> bary;
  std::vector<std::uint8_t> closed;
  for (std::size_t i = 0; i < info.polyline_count; ++i) {
    std::uint32_t kind = 0, is_closed = 0;
    std::size_t count = 0;
    check(mcon_library_get_entry_polyline(lib, index, i, &kind, &is_closed, &count, nullptr, 0));
    std::vector<mcon_surface_point> pts(count);
    check(mcon_library_get_entry_polyline(lib, index, i, nullptr, nullptr, nullptr, pts.data(), pts.size()));
    for (const auto& p : pts) {
      triangles.push_back(p.face);
      bary.insert(bary.end(), {p.barycentric[0], p.barycentric[1], p.barycentric[2]});
    }
    sizes.push_back(static_cast<std::uint32_t>(count));
    closed.push_back(is_closed ? 1 : 0);
  }
  mcon_polyline_set set = nullptr;
  check(mcon_map_transfer_polylines(map, triangles.data(), bary.data(), triangles.size(), sizes.data(),
                                    closed.data(), sizes.size(), &set));
  return PolylinesRef(set);
}

// Writes the polylines as OBJ 'l' elements; returns the number of polylines.
std::size_t write_polylines_obj(const std::string& path, mcon_polyline_set set) {
  std::size_t lines = 0, points = 0;
  check(mcon_polyline_set_get_counts(set, &lines, &points));
  std::vector<std::uint32_t> sizes(lines);
  std::vector<std::uint8_t> closed(lines);
  std::vector<double> xyz(3 * points);
  check(mcon_polyline_set_get_polylines(set, sizes.data(), closed.data(), nullptr, lines));
  check(mcon_polyline_set_get_points(set, nullptr, nullptr, xyz.data(), points));
  std::ofstream out(path);
  require(static_cast<bool>(out), MCON_ERROR_IO, "cannot write '" + path + "'");
  out << "# guide and feature polylines transferred by `macrocon demo`\n";
  char buf[96];
  for (std::size_t i = 0; i < points; ++i) {
    std::snprintf(buf, sizeof(buf), "v %.9g %.9g %.9g\n", xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    out << buf;
  }
  std::size_t first = 1;
  for (std::size_t l = 0; l < lines; ++l) {
    out << "l";
    for (std::uint32_t k = 0; k < sizes[l]; ++k) out << ' ' << first + k;
    if (closed[l]) out << ' ' << first;
    out << '\n';
    first += sizes[l];
  }
  require(static_cast<bool>(out), MCON_ERROR_IO, "cannot write '" + path + "'");
  return lines;
}

// The guides cut into the region: QuadWild's .obj/.rosy/.sharp, every guide on mesh edges.
void write_cut_guides(const macrocon::Patch& region, mcon_polyline_set lines, const mcon_guide_cut_options& options,
                      const std::string& base) {
  mcon_cut_mesh raw_cut = nullptr;
  check(mcon_patch_cut_guides(region.get(), lines, &options, &raw_cut));
  const std::unique_ptr<mcon_cut_mesh_t, Releaser<mcon_cut_mesh, mcon_cut_mesh_release>> cut(raw_cut);
  check(mcon_cut_mesh_write_quadwild(cut.get(), (base + "_cut").c_str()));
  mcon_cut_mesh_info cinfo;
  check(mcon_cut_mesh_info_init(&cinfo));
  check(mcon_cut_mesh_get_info(cut.get(), &cinfo));
  std::printf("  guides cut in: %zu triangles, %zu guide edges, smallest angle made %.1f degrees (of the cut "
              "region triangles %.1f) -> %s_cut.{obj,rosy,sharp}\n",
              cinfo.triangle_count, cinfo.guide_edge_count, cinfo.min_angle_created, cinfo.min_angle_of_cut_input,
              base.c_str());
}

// Every region's guides cut into the whole body: one mesh, one field, one .sharp for QuadWild.
void write_whole_host(const macrocon::Mesh& body, const std::vector<PolylinesRef>& sets,
                      const mcon_guide_cut_options& options, const std::string& out_dir) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<mcon_polyline_set> raw;
  for (const PolylinesRef& s : sets) raw.push_back(s.get());
  mcon_cut_mesh raw_cut = nullptr;
  check(mcon_mesh_cut_guides(body.get(), raw.data(), raw.size(), &options, &raw_cut));
  const std::unique_ptr<mcon_cut_mesh_t, Releaser<mcon_cut_mesh, mcon_cut_mesh_release>> cut(raw_cut);
  const std::string base = out_dir + "/body_whole";
  check(mcon_cut_mesh_write_quadwild(cut.get(), base.c_str()));
  mcon_cut_mesh_info cinfo;
  check(mcon_cut_mesh_info_init(&cinfo));
  check(mcon_cut_mesh_get_info(cut.get(), &cinfo));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("whole body: %zu regions' guides cut in (%zu guides, %zu guide edges, smallest angle made %.1f degrees, "
              "%u points on filled holes dropped), one cross field over %zu triangles, %.2f s -> "
              "%s.{obj,rosy,sharp,quadwild.json}\n",
              sets.size(), cinfo.guide_count, cinfo.guide_edge_count, cinfo.min_angle_created, cinfo.unplaced_points,
              cinfo.triangle_count, seconds, base.c_str());
}

// Runs one region; returns false if the result fails a sanity check (printed). With `cut`, the
// guides are cut into the region with those options; with `keep`, they are appended to it.
bool run_region(const macrocon::Context& ctx, const macrocon::Mesh& body, mcon_library lib, const Region& r,
                const std::string& out_dir, const mcon_guide_cut_options* cut, std::vector<PolylinesRef>* keep,
                bool progress_bar) {
  const auto t0 = std::chrono::steady_clock::now();
  const macrocon::Patch region = macrocon::Patch::extract(body, macrocon::PatchOptions::at_vertex(r.center_vertex, r.radius));
  const mcon_patch_info rinfo = region.info();

  std::uint64_t ids[3];
  std::uint32_t indices[3];
  double distances[3];
  std::size_t found = 0;
  check(mcon_library_query(lib, region.get(), 3, ids, indices, distances, 3, &found));
  require(found > 0, MCON_ERROR_NOT_FOUND, "the starter library is empty");
  std::printf("%s (vertex %u, radius %.2f, %zu vertices): suggestions", r.name, r.center_vertex, r.radius,
              rinfo.vertex_count);
  for (std::size_t i = 0; i < found; ++i)
    std::printf("%s %s #%llu (%.3f)", i ? "," : "", entry_string(lib, indices[i], MCON_ENTRY_CLASS_LABEL).c_str(),
                static_cast<unsigned long long>(ids[i]), distances[i]);
  std::printf("\n");

  const std::size_t best = indices[0];
  mcon_library_entry_info einfo;
  const macrocon::Patch source = entry_patch(ctx, lib, best, einfo);
  mcon_map_options mo;
  check(mcon_map_options_init(&mo));
  // The C API's progress callback drives the CLI's bar (a plugin would drive its host's).
  ProgressBar bar(std::string("  map ") + r.name, progress_bar);
  mo.progress = [](void* user, double f) -> std::int32_t { return static_cast<ProgressBar*>(user)->update(f) ? 1 : 0; };
  mo.progress_user_data = &bar;
  mcon_map raw_map = nullptr;
  check(mcon_map_compute(source.get(), region.get(), &mo, &raw_map));
  bar.finish();
  const MapRef map(raw_map);
  mcon_map_info minfo;
  check(mcon_map_info_init(&minfo));
  check(mcon_map_get_info(map.get(), &minfo));

  // Fields onto the region's vertices.
  const std::size_t nr = rinfo.vertex_count;
  std::vector<io::VertexAttribute> attributes;
  std::vector<std::uint8_t> outside(nr);
  check(mcon_map_get_outside_mask(map.get(), outside.data(), nr));
  io::VertexAttribute mask{"macro_mask", 1, {}};
  for (std::uint8_t o : outside) mask.values.push_back(o ? 0.0 : 1.0);
  attributes.push_back(mask);
  for (std::size_t f = 0; f < einfo.field_count; ++f) {
    std::uint32_t kind = 0, dim = 0;
    check(mcon_library_get_entry_field(lib, best, f, &kind, &dim, nullptr, nullptr, 0));
    io::VertexAttribute a{entry_string(lib, best, MCON_ENTRY_FIELD_NAME, f), static_cast<int>(dim), {}};
    const std::size_t ns = einfo.vertex_count * dim;
    a.values.resize(nr * dim);
    if (kind == MCON_FIELD_INTEGER_LABEL) {
      std::vector<std::int32_t> src(ns), dst(nr * dim);
      check(mcon_library_get_entry_field(lib, best, f, nullptr, nullptr, nullptr, src.data(), ns));
      check(mcon_map_transfer_labels(map.get(), dim, src.data(), ns, -1, dst.data(), dst.size()));
      for (std::size_t i = 0; i < dst.size(); ++i) a.values[i] = dst[i];
    } else {
      std::vector<double> src(ns);
      check(mcon_library_get_entry_field(lib, best, f, nullptr, nullptr, src.data(), nullptr, ns));
      check(mcon_map_transfer_field(map.get(), static_cast<mcon_field_kind>(kind), dim, src.data(), ns,
                                    a.values.data(), a.values.size()));
    }
    if (dim <= 3) attributes.push_back(std::move(a));  // PLY attributes of up to 3 components
  }

  // Guides and features, and a cross field that follows them (QuadWild's .rosy).
  PolylinesRef lines = transfer_polylines(lib, best, einfo, map.get());
  std::vector<double> directions(3 * rinfo.triangle_count);
  mcon_cross_field_options co;
  check(mcon_cross_field_options_init(&co));
  check(mcon_patch_compute_cross_field(region.get(), lines.get(), &co, directions.data(), nullptr,
                                       rinfo.triangle_count));

  // The region in host units: host = center + radius * p.
  const TriMesh mesh = file_mesh(region, rinfo.radius, rinfo.center);
  const std::string base = out_dir + "/" + r.name;
  io::write_ply(base + ".ply", mesh, attributes);
  io::write_obj(base + ".obj", mesh);
  check(mcon_patch_write_rosy(region.get(), directions.data(), rinfo.triangle_count, (base + ".rosy").c_str()));
  const std::size_t polylines = write_polylines_obj(base + "_guides.obj", lines.get());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::printf("  re-embedded %s #%llu: overlap %.2f, matching score %.3f, %s, %u flips; %zu fields, %zu "
              "polylines, %.2f s -> %s.{ply,obj,rosy}, %s_guides.obj\n",
              entry_string(lib, best, MCON_ENTRY_CLASS_LABEL).c_str(), static_cast<unsigned long long>(ids[0]),
              minfo.overlap_ratio, minfo.matching_score, minfo.reflected ? "mirrored" : "direct",
              minfo.flipped_triangles, attributes.size() - 1, polylines, seconds, base.c_str(), base.c_str());
  if (cut) write_cut_guides(region, lines.get(), *cut, base);
  if (keep) keep->push_back(PolylinesRef(lines.release()));
  const bool ok = minfo.flipped_triangles == 0 && minfo.overlap_ratio > 0.5;
  if (!ok) std::printf("  %s: the re-embedding looks wrong (flips or overlap below 0.5)\n", r.name);
  return ok;
}

const char* kUsage =
    "usage: macrocon demo [--data DIR] [--library FILE.mclb] [--out DIR] [--cut-guides] [--whole-host] [--snap F]\n"
    "                     [--fair-passes N] [--quiet | --progress]\n"
    "Queries the bundled MakeHuman body at a few regions against the starter constraint library,\n"
    "re-embeds the best match and writes PLY/OBJ/.rosy results to --out (default demo-out).\n"
    "--cut-guides also cuts the transferred guides into each region and writes QuadWild's inputs\n"
    "<region>_cut.obj, .rosy and .sharp (guides on mesh edges, as feature edges); crossings closer than\n"
    "--snap F (default 0.25) edge lengths to a vertex snap to it; --fair-passes N (default 3, 0 = off)\n"
    "passes of fairing then straighten the chains on the surface.\n"
    "--whole-host also queries the other eye and cuts every region's guides into the whole body:\n"
    "body_whole.obj, .rosy (one field over every face), .sharp and .quadwild.json.\n"
    "Each map draws a progress bar on stderr when it is a terminal; --quiet hides it, --progress draws\n"
    "it anyway.\n";

int run_demo(const Args& args) {
  static const OptionHelp help{
      {"data", "folder of the bundled sample data (default: the source tree's samples/data)"},
      {"out", "output folder (default demo-out)"},
      {"library", "the constraint library to query (default: the starter library)"},
      {"snap", "with --cut-guides / --whole-host: crossings this close to a vertex snap to it (default 0.25)"},
      {"fair-passes", "with --cut-guides / --whole-host: passes of chain fairing, 0 = off (default 3)"},
      {"cut-guides", "also cut each region's guides into it and write QuadWild's inputs"},
      {"whole-host", "also cut every region's guides into the whole body"},
  };
  const ArgParser p(args, {"data", "out", "library", "snap", "fair-passes"}, {"cut-guides", "whole-host", "quiet", "progress"},
                    kUsage, help);
  mcon_guide_cut_options cut_options;
  check(mcon_guide_cut_options_init(&cut_options));
  require(p.flag("cut-guides") || p.flag("whole-host") || !p.has("snap"), MCON_ERROR_INVALID_ARGUMENT,
          "--snap needs --cut-guides or --whole-host");
  cut_options.snap_fraction = p.number("snap", cut_options.snap_fraction);
  require(cut_options.snap_fraction >= 0 && cut_options.snap_fraction <= 0.45, MCON_ERROR_INVALID_ARGUMENT,
          "--snap must be in [0, 0.45] (a fraction of an edge length)");
  require(p.flag("cut-guides") || p.flag("whole-host") || !p.has("fair-passes"), MCON_ERROR_INVALID_ARGUMENT,
          "--fair-passes needs --cut-guides or --whole-host");
  const long fair_passes = p.integer("fair-passes", cut_options.fair_passes);
  require(fair_passes >= 0 && fair_passes <= 100, MCON_ERROR_INVALID_ARGUMENT,
          "--fair-passes must be 0 (no chain fairing) to 100");
  cut_options.fair_passes = static_cast<std::uint32_t>(fair_passes);
  const mcon_guide_cut_options* cut = p.flag("cut-guides") ? &cut_options : nullptr;
  const std::string data = p.get("data", MACROCON_SAMPLE_DATA_DIR);
  const std::string out_dir = p.get("out", "demo-out");
  const std::string library_path = p.get("library", default_library_path());
  std::filesystem::create_directories(out_dir);

  const auto t0 = std::chrono::steady_clock::now();
  int failures = 0;
  {
    const io::LoadedMesh body_file = io::read_mesh(data + "/makehuman-body.obj.gz");
    const macrocon::Context ctx;
    const macrocon::Mesh body = sdk_mesh(ctx, body_file.mesh);
    mcon_library raw = nullptr;
    check(mcon_library_open(ctx.get(), library_path.c_str(), &raw));
    const LibraryRef lib(raw);
    std::size_t entries = 0;
    check(mcon_library_get_count(lib.get(), &entries));
    std::printf("body: %zu vertices, %zu triangles (MakeHuman, CC0); library %s: %zu entries\n", body.vertex_count(),
                body.triangle_count(), library_path.c_str(), entries);
    const bool whole = p.flag("whole-host");
    std::vector<Region> regions(std::begin(kRegions), std::end(kRegions));
    if (whole) regions.insert(regions.begin() + 1, kOtherEye);
    std::vector<PolylinesRef> sets;
    for (const Region& r : regions) {
      // Region vertices are file numbers; the bundled body has no unreferenced vertices.
      try {
        if (!run_region(ctx, body, lib.get(), r, out_dir, cut, whole ? &sets : nullptr, progress_wanted(p))) ++failures;
      } catch (const macrocon::Error& e) {
        std::printf("  %s failed: %s: %s\n", r.name, macrocon::status_name(e.status()).c_str(), e.what());
        ++failures;
      }
    }
    if (whole) {
      try {
        write_whole_host(body, sets, cut_options, out_dir);
      } catch (const macrocon::Error& e) {
        std::printf("  whole body failed: %s: %s\n", macrocon::status_name(e.status()).c_str(), e.what());
        ++failures;
      }
    }
  }
  macrocon::shutdown();
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("demo finished in %.2f s with %d failure(s); results in %s/\n", total, failures, out_dir.c_str());
  return failures == 0 ? 0 : 1;
}

const Registration registration{"demo", "query, re-embed and transfer on the bundled sample data", run_demo};

}  // namespace
}  // namespace mcon::cli
