#include "common/mapping_benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

#include <tbb/task_arena.h>

#include "common/bench_spec.h"
#include "common/ict_faces.h"
#include "common/makehuman_people.h"
#include "common/patch_instances.h"
#include "common/retessellate.h"
#include "common/thesis_gradient_descent.h"
#include "descriptors/curvature_descriptors.h"
#include "base/error.h"
#include "patch/geodesic_disk_patch.h"
#include "operators/heat_geodesics.h"
#include "base/parallel_blocks.h"
#include "map/patch_map.h"
#include "map/similarity_icp.h"
#include "mesh/point_location_2d.h"

namespace mcon::tools {

const char* const kMappingMethods[4] = {"macrocon", "rigid", "thesis", "proximity"};
// Weight of each ground-truth guidance column of the `oracle` method (3 channels, each std 1).
constexpr double kOracleGuidanceWeight = 3.0;
// The `landmarks` method: the weight of each distance column (4 landmarks: 1 and 0.5 measured
// alike on the default run, 2.78 and 2.77 mean eps x 100).
constexpr double kLandmarkGuidanceWeight = 1.0;
const char* const kMappingParts[8] = {"eye", "nose", "mouth", "ear", "face", "hand", "foot", "arm"};

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const BenchClass* find_class(const BenchSpec& spec, const std::string& name) {
  for (const BenchClass& c : spec.classes)
    if (c.name == name) return &c;
  return nullptr;
}

// One model's data: the base mesh, its instances, the bench classes and the mirror involution.
struct Model {
  std::string name;
  BenchModelData bench;
  std::unique_ptr<MakeHumanPeople> people;
  std::unique_ptr<IctFaces> faces;
  std::vector<int> mirror;  // base vertex -> vertex nearest to its mirror image (x -> -x)

  const io::LoadedMesh& base() const { return people ? people->base() : faces->neutral(); }
  TriMesh instance(std::uint64_t seed, int index) const {
    return people ? people->person(seed, static_cast<std::uint64_t>(index))
                  : faces->face(seed, static_cast<std::uint64_t>(index));
  }
};

// The mirror involution by nearest mirrored vertex: MakeHuman is exactly x -> -x symmetric, ICT
// to 0.005 cm (shared/bench/README.md). A uniform grid keeps it near-linear.
std::vector<int> mirror_map(const TriMesh& mesh) {
  const int n = mesh.num_vertices();
  Vec3 lo = mesh.positions[0], hi = lo;
  for (const Vec3& p : mesh.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double cell = std::max((hi - lo).maxCoeff() / 64.0, 1e-9);
  auto key = [&](const Vec3& p, int dx, int dy, int dz) {
    const long ix = static_cast<long>(std::floor((p.x() - lo.x()) / cell)) + dx;
    const long iy = static_cast<long>(std::floor((p.y() - lo.y()) / cell)) + dy;
    const long iz = static_cast<long>(std::floor((p.z() - lo.z()) / cell)) + dz;
    return (ix * 1000003L + iy) * 1000033L + iz;
  };
  std::multimap<long, int> grid;
  for (int v = 0; v < n; ++v) grid.emplace(key(mesh.positions[v], 0, 0, 0), v);
  std::vector<int> out(n, -1);
  for (int v = 0; v < n; ++v) {
    const Vec3 q(-mesh.positions[v].x(), mesh.positions[v].y(), mesh.positions[v].z());
    double best = 1e300;
    for (int r = 1; out[v] < 0 || r <= 1; ++r) {
      for (int dx = -r; dx <= r; ++dx)
        for (int dy = -r; dy <= r; ++dy)
          for (int dz = -r; dz <= r; ++dz) {
            auto range = grid.equal_range(key(q, dx, dy, dz));
            for (auto it = range.first; it != range.second; ++it) {
              const double d = (mesh.positions[it->second] - q).squaredNorm();
              if (d < best || (d == best && it->second < out[v])) {
                best = d;
                out[v] = it->second;
              }
            }
          }
      if (r > 64) break;
    }
  }
  return out;
}

Model load_model(const std::string& shared, const std::string& name) {
  Model m;
  m.name = name;
  m.bench = read_bench_model(shared, name);
  if (name == "makehuman")
    m.people = std::make_unique<MakeHumanPeople>(shared);
  else
    m.faces = std::make_unique<IctFaces>(shared);
  const io::LoadedMesh& base = m.base();
  for (int v = 0; v < base.mesh.num_vertices(); ++v)
    require(base.mesh_to_file[v] == v, MCON_ERROR_INVALID_ARGUMENT,
            "eval-mapping: the " + name + " surface does not keep the file's vertex numbering");
  return m;
}

struct CutPatch {
  Patch patch;
  std::vector<int> host;  // patch vertex -> instance vertex (original numbering), -1 if none
};

CutPatch cut(const Model& model, const BenchClass& cls, const TriMesh& instance, const TriMesh* decimated,
             const std::vector<int>* to_original) {
  const io::LoadedMesh& base = model.base();
  const InstancePatch ip =
      instance_patch(cls, model.bench.patches.find(cls.name).vertices, base.mesh, instance, base.triangle_to_face);
  PatchOptions po;
  po.radius = ip.radius;
  po.fill_holes = cls.fill_holes;
  po.center.vertex = cls.center_vertex;
  if (decimated) {
    const auto it = std::find(to_original->begin(), to_original->end(), cls.center_vertex);
    require(it != to_original->end(), MCON_ERROR_NUMERICAL, "eval-mapping: decimation removed the patch center");
    po.center.vertex = static_cast<int>(it - to_original->begin());
  }
  CutPatch out{extract_geodesic_disk(decimated ? *decimated : instance, po), {}};
  out.host.assign(out.patch.mesh.positions.size(), -1);
  for (std::size_t v = 0; v < out.host.size(); ++v) {
    const HostPoint& h = out.patch.host_vertex[v];
    if (h.v0 >= 0 && h.v0 == h.v1) out.host[v] = decimated ? (*to_original)[h.v0] : h.v0;
  }
  return out;
}

int flipped(const TriMesh& mesh, const std::vector<Vec2>& phi, bool reflected) {
  int count = 0;
  for (const Tri& t : mesh.triangles) {
    const Vec2 e1 = phi[t[1]] - phi[t[0]], e2 = phi[t[2]] - phi[t[0]];
    const double a = e1.x() * e2.y() - e1.y() * e2.x();
    if ((reflected ? -a : a) <= 0) ++count;
  }
  return count;
}

double patch_area(const TriMesh& mesh) {
  double a = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) a += triangle_area(mesh, t);
  return a;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::vector<MappingSlot> mapping_slots(const std::string& shared_dir, const std::vector<std::string>& parts) {
  for (const std::string& p : parts)
    require(std::find_if(std::begin(kMappingParts), std::end(kMappingParts),
                         [&](const char* k) { return p == k; }) != std::end(kMappingParts),
            MCON_ERROR_INVALID_ARGUMENT, "eval-mapping: unknown class '" + p + "'");
  std::vector<MappingSlot> slots;
  for (const char* model : {"makehuman", "ict"}) {
    const BenchModelData data = read_bench_model(shared_dir, model);
    for (const char* part : kMappingParts) {
      if (!parts.empty() && std::find(parts.begin(), parts.end(), part) == parts.end()) continue;
      const std::string p(part);
      if (find_class(data.spec, p + "_r") && find_class(data.spec, p + "_l")) {
        slots.push_back({model, p, false, p + "_r", p + "_r"});
        slots.push_back({model, p, true, p + "_r", p + "_l"});
      } else if (find_class(data.spec, p)) {
        slots.push_back({model, p, false, p, p});
      }
    }
  }
  return slots;
}

namespace {

void validate_mapping_options(const MappingEvalOptions& options) {
  require(options.pairs >= 0 && options.threads >= 1 && options.alignment_samples >= 1 &&
              options.thesis_iterations >= 0 && options.max_evaluated_vertices >= 1 && options.landmarks >= 1 &&
              options.landmarks <= 64,
          MCON_ERROR_INVALID_ARGUMENT, "eval-mapping: invalid options");
  for (const std::string& m : options.methods)
    require(m == "macrocon" || m == "rigid" || m == "thesis" || m == "proximity" || m == "macrocon-frame" ||
                m == "frame-rigid" || m == "macrocon-up" || m == "oracle" || m == "landmarks",
            MCON_ERROR_INVALID_ARGUMENT, "eval-mapping: unknown method '" + m + "'");
}

bool wants(const MappingEvalOptions& options, const char* m) {
  return std::find(options.methods.begin(), options.methods.end(), m) != options.methods.end();
}

// The model of `slot`, loaded (with its mirror involution if any slot of it is mirrored) on first use.
const Model& model_for(std::map<std::string, Model>& models, const MappingEvalOptions& options,
                       const std::vector<MappingSlot>& slots, const MappingSlot& slot) {
  if (!models.count(slot.model)) {
    Model m = load_model(options.shared_dir, slot.model);
    bool any_mirror = false;
    for (const MappingSlot& s : slots) any_mirror = any_mirror || (s.model == slot.model && s.mirrored);
    if (any_mirror) m.mirror = mirror_map(m.base().mesh);
    models.emplace(slot.model, std::move(m));
  }
  return models.at(slot.model);
}

struct PairPatches {
  CutPatch src, dst;
};

struct PerturbedTarget {
  TriMesh mesh;
  std::vector<int> to_original;  // perturbed vertex -> instance vertex, -1 for a subdivision vertex
};

// The decimated target as a user's scan or export would hand it over: perturbed, then oriented and
// validated as mcon_mesh_create does. The vertex identities go through both steps, so the ground
// truth (same instance vertex) still holds; noise moves a vertex off the clean surface by design.
PerturbedTarget perturbed_target(const Retessellation& re, const MappingEvalOptions& options, int center_vertex, int i,
                                 int attempt) {
  const auto it = std::find(re.to_original.begin(), re.to_original.end(), center_vertex);
  require(it != re.to_original.end(), MCON_ERROR_NUMERICAL, "eval-mapping: decimation removed the patch center");
  const int center = static_cast<int>(it - re.to_original.begin());
  PerturbedMesh p = user_mesh(re.mesh, options.perturbation,
                              options.seed * 2000003ull + static_cast<std::uint64_t>(i) + 104729ull * attempt, {center});
  PerturbedTarget out{std::move(p.mesh), {}};
  out.to_original.resize(p.to_original.size());
  for (std::size_t v = 0; v < p.to_original.size(); ++v)
    out.to_original[v] = p.to_original[v] >= 0 ? re.to_original[static_cast<std::size_t>(p.to_original[v])] : -1;
  return out;
}

PairPatches cut_pair_patches(const Model& model, const MappingEvalOptions& options, const MappingSlot& slot, int i,
                             MappingPairResult& res) {
  const BenchClass& src_cls = model.bench.spec.find(slot.source_class);
  const BenchClass& dst_cls = model.bench.spec.find(slot.target_class);
  // A scaled-radius ball can still stop being a disk on a rare person or decimation (the
  // forearm wraps into a ring, bench/README.md); such a pair moves on to the next people
  // (2i + 1000k, 2i + 1 + 1000k), deterministically.
  PairPatches out;
  for (int attempt = 0;; ++attempt) {
    res.person_a = 2 * i + 1000 * attempt;
    res.person_b = res.person_a + 1;
    try {
      const TriMesh a = model.instance(options.seed, res.person_a);
      const TriMesh b = model.instance(options.seed, res.person_b);
      DecimationOptions dec;
      dec.keep = {dst_cls.center_vertex};
      const Retessellation re =
          decimate(b, options.seed * 1000003ull + static_cast<std::uint64_t>(i) + 7919ull * attempt, dec);
      out.src = cut(model, src_cls, a, nullptr, nullptr);
      if (options.perturbation.active()) {
        const PerturbedTarget t = perturbed_target(re, options, dst_cls.center_vertex, i, attempt);
        out.dst = cut(model, dst_cls, b, &t.mesh, &t.to_original);
      } else {
        out.dst = cut(model, dst_cls, b, &re.mesh, &re.to_original);
      }
      break;
    } catch (const Error& e) {
      // A perturbed target may also fail numerically or as a mesh; the next people may not.
      const bool retry = e.status() == MCON_ERROR_NOT_A_DISK || options.perturbation.active();
      if (!retry || attempt >= 4) throw;
      if (options.log) options.log("pair " + std::to_string(i) + ": " + e.what() + "; next people");
    }
  }
  res.source_vertices = out.src.patch.mesh.num_vertices();
  res.target_vertices = out.dst.patch.mesh.num_vertices();
  return out;
}

struct GroundTruth {
  std::vector<int> sources, truths;  // evaluated source patch vertex -> its true target patch vertex
};

// Ground truth: source vertex -> target patch vertex of the same (mirrored) body vertex.
GroundTruth ground_truth(const Model& model, const MappingSlot& slot, const PairPatches& pp,
                         const MappingEvalOptions& options, MappingPairResult& res) {
  const CutPatch& src = pp.src;
  const CutPatch& dst = pp.dst;
  std::map<int, int> target_of_host;
  for (std::size_t w = 0; w < dst.host.size(); ++w)
    if (dst.host[w] >= 0) target_of_host.emplace(dst.host[w], static_cast<int>(w));
  std::vector<int> sources, truths;
  for (std::size_t v = 0; v < src.host.size(); ++v) {
    if (src.host[v] < 0) continue;
    const int truth = slot.mirrored ? model.mirror[static_cast<std::size_t>(src.host[v])] : src.host[v];
    const auto it = target_of_host.find(truth);
    if (it == target_of_host.end()) continue;
    sources.push_back(static_cast<int>(v));
    truths.push_back(it->second);
  }
  res.ground_truth_vertices = static_cast<int>(sources.size());
  if (static_cast<int>(sources.size()) > options.max_evaluated_vertices) {
    const double stride = static_cast<double>(sources.size()) / options.max_evaluated_vertices;
    std::vector<int> s2, t2;
    for (int k = 0; k < options.max_evaluated_vertices; ++k) {
      const std::size_t idx = static_cast<std::size_t>(std::floor(k * stride));
      s2.push_back(sources[idx]);
      t2.push_back(truths[idx]);
    }
    sources.swap(s2);
    truths.swap(t2);
  }
  return {std::move(sources), std::move(truths)};
}

// Every method's map of the source patch vertices, and whether it reverses orientation.
struct PairMaps {
  std::map<std::string, std::vector<Vec2>> phi;
  std::map<std::string, bool> reflected;
  std::map<std::string, std::map<std::string, double>> signals;  // candidate confidence signals
  RigidAlignmentOptions alignment;  // the rigid search options, shared by the guided methods
};

// Candidate signals for a map's confidence (issue 14), each oriented so that larger means more
// confident: the matching score, the overlap, the margin between the best plain and mirrored
// rigid starts, and (with a world frame) minus the anchor's RMS displacement and minus the angle
// between the frame start and the descriptor search's best start of the same orientation.
std::map<std::string, double> map_signals(const SurfaceMap& m) {
  std::map<std::string, double> s;
  s["matching_score"] = m.matching_score;
  s["overlap"] = m.overlap_ratio;
  s["rigid_margin"] = std::abs(m.alignment.score_unreflected - m.alignment.score_reflected);
  // How much better the kept orientation's level-0 energy was than the other's, relative to it.
  if (m.orientation_compared) {
    const double lo = std::min(m.level0_energy_unreflected, m.level0_energy_reflected);
    const double hi = std::max(m.level0_energy_unreflected, m.level0_energy_reflected);
    s["orientation_margin"] = hi > 0 ? (hi - lo) / hi : 0.0;
  }
  if (m.frame_decided) {
    s["anchor_rms"] = -std::sqrt(std::max(0.0, m.energy.value("anchor")));
    const RigidTransform2D& d = m.alignment.transform.reflected ? m.alignment.best_reflected : m.alignment.best_unreflected;
    s["start_agreement"] = -std::abs(std::remainder(m.alignment.transform.angle - d.angle, 2 * M_PI));
  }
  return s;
}

// Forward/backward consistency (a confidence candidate, MappingEvalOptions::cycle_signal): map
// the target onto the source with the same options, follow each source vertex forward and back,
// and take the median distance from where it started, in the source disk (radius 1). A map whose
// optimum is ambiguous tends to land elsewhere from the other side; a consistently wrong pair
// (both ways rotated by opposite angles) goes unnoticed, which is what the measurement tells.
void add_cycle_signal(const PairPatches& pp, const SurfaceMap& forward, const PatchMapOptions& options,
                      std::map<std::string, double>& signals) {
  const SurfaceMap back = map_patches(pp.dst.patch, pp.src.patch, options);
  const TriangleLocator2D target(pp.dst.patch.uv, pp.dst.patch.mesh.triangles);
  std::vector<double> d;
  d.reserve(forward.phi.size());
  int hint = -1;
  for (std::size_t v = 0; v < forward.phi.size(); ++v) {
    const PointLocation at = target.locate_nearest(forward.phi[v], 4.0, hint);
    if (at.triangle < 0) continue;
    hint = at.triangle;
    const Tri& t = pp.dst.patch.mesh.triangles[static_cast<std::size_t>(at.triangle)];
    const Vec2 q = at.barycentric[0] * back.phi[static_cast<std::size_t>(t[0])] +
                   at.barycentric[1] * back.phi[static_cast<std::size_t>(t[1])] +
                   at.barycentric[2] * back.phi[static_cast<std::size_t>(t[2])];
    d.push_back((q - pp.src.patch.uv[v]).norm());
  }
  if (d.empty()) return;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  signals["cycle"] = -d[d.size() / 2];
  signals["backward_matching_score"] = back.matching_score;
}

// The maps: macrocon, rigid and thesis, all from one map_patches call's rigid start.
PairMaps unguided_maps(const PairPatches& pp, const MappingEvalOptions& options, MappingPairResult& res) {
  const CutPatch& src = pp.src;
  const CutPatch& dst = pp.dst;
  PairMaps maps;
  PatchMapOptions mo;
  mo.map.alignment.samples = options.alignment_samples;
  mo.map.alignment.seed = options.seed;
  mo.map.newton.reuse_factorization = !options.plain_newton;
  if (!wants(options, "macrocon")) mo.map.newton.max_iterations = 0;  // the rigid start only
  maps.alignment = mo.map.alignment;
  const auto t0 = std::chrono::steady_clock::now();
  const SurfaceMap map = map_patches(src.patch, dst.patch, mo);
  const double map_seconds = seconds_since(t0);
  const RigidTransform2D T = map.alignment.transform;
  {
    std::ostringstream o;
    o << "rigid scores plain " << fmt(map.alignment.score_unreflected) << " mirrored "
      << fmt(map.alignment.score_reflected);
    if (map.orientation_compared)
      o << ", level-0 energies plain " << fmt(map.level0_energy_unreflected) << " mirrored "
        << fmt(map.level0_energy_reflected);
    res.orientation_note = o.str();
  }
  if (wants(options, "macrocon")) {
    maps.phi["macrocon"] = map.phi;
    maps.reflected["macrocon"] = map.reflected;
    maps.signals["macrocon"] = map_signals(map);
    if (options.cycle_signal) add_cycle_signal(pp, map, mo, maps.signals["macrocon"]);
    res.methods["macrocon"].seconds = map_seconds;
    res.methods["macrocon"].iterations = map.iterations;
  }
  std::vector<Vec2> rigid(src.patch.uv.size());
  for (std::size_t v = 0; v < rigid.size(); ++v) rigid[v] = T.apply(src.patch.uv[v]);
  if (wants(options, "rigid")) {
    maps.phi["rigid"] = rigid;
    maps.reflected["rigid"] = T.reflected;
    res.methods["rigid"].seconds = map.alignment_seconds;
  }
  if (wants(options, "thesis")) {
    ThesisDescentOptions to;
    to.iterations = options.thesis_iterations;
    const ThesisDescentResult th = thesis_gradient_descent(
        src.patch.mesh, src.patch.uv, mean_curvature_descriptor(src.patch.mesh), dst.patch.mesh, dst.patch.uv,
        mean_curvature_descriptor(dst.patch.mesh), rigid, T.reflected, to);
    maps.phi["thesis"] = th.phi;
    maps.reflected["thesis"] = T.reflected;
    res.methods["thesis"].seconds = map.alignment_seconds + th.seconds;
    res.methods["thesis"].iterations = th.iterations;
  }
  return maps;
}

// The proximity baseline (what a DCC user does today): similarity ICP of the source patch onto the
// target patch in host coordinates (map/similarity_icp.h), then each source vertex's closest
// target surface point, expressed in the target's disk coordinates. For a mirrored pair the user
// knows the sides and mirrors the source (x -> -x, the models' left-right axis) first.
void run_proximity(const PairPatches& pp, bool mirrored, PairMaps& maps, MappingPairResult& res) {
  const auto t0 = std::chrono::steady_clock::now();
  TriMesh source = host_mesh(pp.src.patch);
  if (mirrored)
    for (Vec3& p : source.positions) p.x() = -p.x();
  const SimilarityIcpResult icp = similarity_icp(source, host_mesh(pp.dst.patch));
  std::vector<Vec2> phi(icp.closest.size());
  for (std::size_t v = 0; v < phi.size(); ++v) {
    const Tri& t = pp.dst.patch.mesh.triangles[icp.closest[v].triangle];
    const Vec3& b = icp.closest[v].barycentric;
    phi[v] = b[0] * pp.dst.patch.uv[t[0]] + b[1] * pp.dst.patch.uv[t[1]] + b[2] * pp.dst.patch.uv[t[2]];
  }
  maps.phi["proximity"] = std::move(phi);
  maps.reflected["proximity"] = mirrored;
  res.methods["proximity"].seconds = seconds_since(t0);
  res.methods["proximity"].iterations = icp.iterations;
}

// macrocon-frame: the SDK's map with the 3D-aligned start (PatchMapOptions::use_world_frame),
// the source mirrored x -> -x first for a mirrored pair, as for proximity.
void run_frame(const MappingEvalOptions& options, const PairPatches& pp, bool mirrored, PairMaps& maps,
               std::map<std::string, MethodPairResult>& res) {
  PatchMapOptions fo;
  fo.map.alignment = maps.alignment;
  fo.use_world_frame = true;
  fo.map.newton.reuse_factorization = !options.plain_newton;
  fo.world_frame_mirror = mirrored;
  if (options.frame_anchor >= 0) fo.world_frame_anchor = options.frame_anchor;
  if (options.frame_anchor_decay > 0) fo.map.anchor_decay = options.frame_anchor_decay;
  const auto t0 = std::chrono::steady_clock::now();
  const SurfaceMap fm = map_patches(pp.src.patch, pp.dst.patch, fo);
  maps.phi["macrocon-frame"] = fm.phi;
  maps.reflected["macrocon-frame"] = fm.reflected;
  maps.signals["macrocon-frame"] = map_signals(fm);
  if (options.cycle_signal) add_cycle_signal(pp, fm, fo, maps.signals["macrocon-frame"]);
  res["macrocon-frame"].seconds = seconds_since(t0);
  res["macrocon-frame"].iterations = fm.iterations;
  // frame-rigid: that start alone (what `rigid` is to macrocon).
  std::vector<Vec2> start(pp.src.patch.uv.size());
  for (std::size_t v = 0; v < start.size(); ++v) start[v] = fm.alignment.transform.apply(pp.src.patch.uv[v]);
  maps.phi["frame-rigid"] = std::move(start);
  maps.reflected["frame-rigid"] = fm.alignment.transform.reflected;
  res["frame-rigid"].seconds = fm.alignment_seconds;
}

// macrocon-up: the frame-free map with both up hints +y (the models' up axis; PatchMapOptions::
// source_up / target_up). An up direction cannot tell a part from its mirror image, so a mirrored
// pair is mapped with the orientation reversed, as a host that knows the sides would (the same
// knowledge proximity gets). A patch whose normal at the center is (nearly) +y gets no hint, as a
// host would omit it (noted in the pair's orientation note).
void run_up(const MappingEvalOptions& options, const PairPatches& pp, bool mirrored, PairMaps& maps,
            std::map<std::string, MethodPairResult>& res, std::string& note) {
  PatchMapOptions uo;
  uo.map.alignment = maps.alignment;
  if (mirrored) uo.map.orientation = MapOrientation::reverse;
  if (options.up_anchor >= 0) uo.up_start_anchor = options.up_anchor;
  uo.source_up = Vec3(0, 1, 0);
  uo.map.newton.reuse_factorization = !options.plain_newton;
  uo.target_up = Vec3(0, 1, 0);
  const auto t0 = std::chrono::steady_clock::now();
  SurfaceMap um;
  try {
    um = map_patches(pp.src.patch, pp.dst.patch, uo);
  } catch (const Error& e) {
    if (e.status() != MCON_ERROR_INVALID_ARGUMENT || std::string(e.what()).find("up vector") == std::string::npos) throw;
    note += note.empty() ? "no up hint (normal)" : "; no up hint (normal)";
    uo.source_up.reset();
    uo.target_up.reset();
    um = map_patches(pp.src.patch, pp.dst.patch, uo);
  }
  maps.phi["macrocon-up"] = um.phi;
  maps.reflected["macrocon-up"] = um.reflected;
  maps.signals["macrocon-up"] = map_signals(um);
  if (options.cycle_signal) add_cycle_signal(pp, um, uo, maps.signals["macrocon-up"]);
  res["macrocon-up"].seconds = seconds_since(t0);
  res["macrocon-up"].iterations = um.iterations;
}

// A guided method: the SDK's map with host guidance channels (PatchMapOptions).
void run_guided(const char* name, const PairPatches& pp, const Eigen::MatrixXd& gs, const Eigen::MatrixXd& gt,
                double weight, PairMaps& maps, MappingPairResult& res) {
  PatchMapOptions oo;  // the full map (unguided_maps runs no Newton iterations when macrocon is not asked for)
  oo.map.alignment = maps.alignment;
  oo.source_guidance = &gs;
  oo.target_guidance = &gt;
  oo.guidance_weight = weight;
  const auto to = std::chrono::steady_clock::now();
  const SurfaceMap gm = map_patches(pp.src.patch, pp.dst.patch, oo);
  maps.phi[name] = gm.phi;
  maps.reflected[name] = gm.reflected;
  res.methods[name].seconds = seconds_since(to);
  res.methods[name].iterations = gm.iterations;
}

// The oracle's guidance = the base-mesh position of every vertex's true correspondent (the
// source's mirrored for a mirrored pair): descriptors without ambiguity, so what is left of the
// error is the optimizer's and the distortion prior's share.
Eigen::MatrixXd oracle_guidance(const Model& model, const std::vector<int>& host, bool mirror) {
  const TriMesh& base = model.base().mesh;
  Eigen::MatrixXd g(static_cast<Eigen::Index>(host.size()), 3);
  Vec3 mean = Vec3::Zero();
  int known = 0;
  for (std::size_t v = 0; v < host.size(); ++v) {
    if (host[v] < 0) continue;
    const int h = mirror ? model.mirror[static_cast<std::size_t>(host[v])] : host[v];
    g.row(static_cast<Eigen::Index>(v)) = base.positions[static_cast<std::size_t>(h)].transpose();
    mean += base.positions[static_cast<std::size_t>(h)];
    ++known;
  }
  mean /= std::max(known, 1);
  for (std::size_t v = 0; v < host.size(); ++v)
    if (host[v] < 0) g.row(static_cast<Eigen::Index>(v)) = mean.transpose();
  return g;
}

// What an artist can give: a few corresponding points clicked on both meshes (here true
// pairs, spread by farthest-point sampling over the source), and as guidance the geodesic
// distance from each, computed on each patch.
void run_landmarks(const PairPatches& pp, const GroundTruth& gt_pairs, const MappingEvalOptions& options,
                   PairMaps& maps, MappingPairResult& res) {
  const CutPatch& src = pp.src;
  const CutPatch& dst = pp.dst;
  const std::vector<int>& sources = gt_pairs.sources;
  const std::vector<int>& truths = gt_pairs.truths;
  const HeatGeodesics src_heat(src.patch.mesh), dst_heat(dst.patch.mesh);
  const int count = std::min(options.landmarks, static_cast<int>(sources.size()));
  Eigen::MatrixXd gs(src.patch.mesh.num_vertices(), count), gt(dst.patch.mesh.num_vertices(), count);
  Eigen::VectorXd nearest = src_heat.from_point(src.patch.center.triangle, src.patch.center.barycentric);
  for (int k = 0; k < count; ++k) {
    int best = 0;  // the evaluated source vertex farthest from the center and the picks so far
    for (int c = 1; c < static_cast<int>(sources.size()); ++c)
      if (nearest[sources[c]] > nearest[sources[best]]) best = c;
    gs.col(k) = src_heat.from_vertices({sources[best]});
    gt.col(k) = dst_heat.from_vertices({truths[best]});
    nearest = nearest.cwiseMin(gs.col(k));
  }
  run_guided("landmarks", pp, gs, gt, kLandmarkGuidanceWeight, maps, res);
}

// Where each evaluated point lands, per method, then one heat solve per true vertex: each
// method's eps per evaluated point (-1 if it lands outside the target).
std::map<std::string, std::vector<double>> landing_eps(const PairPatches& pp, const GroundTruth& gt_pairs,
                                                       const PairMaps& maps, const TriangleLocator2D& locator,
                                                       MappingPairResult& res) {
  const CutPatch& dst = pp.dst;
  const std::vector<int>& sources = gt_pairs.sources;
  const std::vector<int>& truths = gt_pairs.truths;
  std::map<std::string, std::vector<PointLocation>> landed;
  for (auto& [name, p] : maps.phi) {
    std::vector<PointLocation>& l = landed[name];
    l.resize(sources.size());
    for_each_block(static_cast<int>(sources.size()), 64, [&](int begin, int end, int) {
      for (int k = begin; k < end; ++k) l[k] = locator.locate(p[sources[k]]);
    });
  }
  const HeatGeodesics heat(dst.patch.mesh);
  const double scale = 1.0 / std::sqrt(patch_area(dst.patch.mesh));
  res.target_edge_eps = scale * mean_edge_length(dst.patch.mesh);
  std::map<std::string, std::vector<double>> eps;
  for (auto& [name, l] : landed) eps[name].assign(sources.size(), -1.0);
  for_each_block(static_cast<int>(sources.size()), 8, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      bool needed = false;
      for (auto& [name, l] : landed) needed = needed || l[k].triangle >= 0;
      if (!needed) continue;
      const Eigen::VectorXd d = heat.from_vertices({truths[k]});
      for (auto& [name, l] : landed) {
        if (l[k].triangle < 0) continue;
        const Tri& t = dst.patch.mesh.triangles[l[k].triangle];
        eps[name][k] = scale * std::max(0.0, l[k].barycentric[0] * d[t[0]] + l[k].barycentric[1] * d[t[1]] +
                                                 l[k].barycentric[2] * d[t[2]]);
      }
    }
  });
  return eps;
}

// Each method's scores: eps statistics, flips and overlap (source vertex area mapped inside the target).
void score_methods(const PairPatches& pp, const PairMaps& maps, const TriangleLocator2D& locator,
                   std::map<std::string, std::vector<double>>& eps, MappingPairResult& res) {
  const CutPatch& src = pp.src;
  const Eigen::VectorXd va = [&] {
    Eigen::VectorXd areas = Eigen::VectorXd::Zero(src.patch.mesh.num_vertices());
    for (int t = 0; t < src.patch.mesh.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) areas[src.patch.mesh.triangles[t][k]] += triangle_area(src.patch.mesh, t) / 3;
    return areas;
  }();
  for (auto& [name, p] : maps.phi) {
    MethodPairResult& r = res.methods[name];
    double sum = 0;
    int within = 0, count = 0;
    for (double e : eps[name]) {
      if (e < 0) continue;
      sum += e;
      within += e <= 0.05;
      ++count;
    }
    r.evaluated = count;
    r.mean_eps = count ? sum / count : 0.0;
    r.within_0_05 = count ? static_cast<double>(within) / count : 0.0;
    r.reflected = maps.reflected.at(name);
    r.flipped_triangles = flipped(src.patch.mesh, p, r.reflected);
    double inside = 0;
    for (std::size_t v = 0; v < p.size(); ++v)
      if (locator.locate(p[v]).triangle >= 0) inside += va[static_cast<Eigen::Index>(v)];
    r.overlap = inside / va.sum();
  }
}

// One pair: cut both patches, find the ground truth, run every method and score it.
void evaluate_pair(const Model& model, const MappingSlot& slot, int i, const MappingEvalOptions& options,
                   MappingPairResult& res) {
  const PairPatches pp = cut_pair_patches(model, options, slot, i, res);
  const GroundTruth truth = ground_truth(model, slot, pp, options, res);
  PairMaps maps = unguided_maps(pp, options, res);
  if (wants(options, "proximity")) run_proximity(pp, slot.mirrored, maps, res);
  if (wants(options, "macrocon-frame") || wants(options, "frame-rigid"))
    run_frame(options, pp, slot.mirrored, maps, res.methods);
  if (wants(options, "macrocon-up")) run_up(options, pp, slot.mirrored, maps, res.methods, res.orientation_note);
  if (wants(options, "oracle"))
    run_guided("oracle", pp, oracle_guidance(model, pp.src.host, slot.mirrored), oracle_guidance(model, pp.dst.host, false),
               kOracleGuidanceWeight, maps, res);
  if (wants(options, "landmarks") && !truth.sources.empty()) run_landmarks(pp, truth, options, maps, res);
  const TriangleLocator2D locator(pp.dst.patch.uv, pp.dst.patch.mesh.triangles);
  std::map<std::string, std::vector<double>> eps = landing_eps(pp, truth, maps, locator, res);
  score_methods(pp, maps, locator, eps, res);
}

void log_pair(const MappingEvalOptions& options, int i, const MappingSlot& slot, const MappingPairResult& res) {
  std::ostringstream line;
  line << "pair " << i << " " << slot.model << " " << slot.source_class << " -> " << slot.target_class
       << " (" << res.source_vertices << " -> " << res.target_vertices << " vertices, "
       << res.ground_truth_vertices << " with ground truth, target edge eps100 "
       << fmt(100 * res.target_edge_eps) << "):";
  for (const auto& [name, r] : res.methods)
    line << " " << name << (r.reflected ? " (mirrored)" : "") << " eps100 " << fmt(100 * r.mean_eps) << " within " << fmt(r.within_0_05) << " flips "
         << r.flipped_triangles << " overlap " << fmt(r.overlap) << " " << fmt(r.seconds) << "s it "
         << r.iterations << ";";
  if (!res.orientation_note.empty()) line << " (" << res.orientation_note << ")";
  options.log(line.str());
}

}  // namespace

std::vector<MappingPairResult> run_mapping_evaluation(const MappingEvalOptions& options,
                                                      std::vector<std::string>* uncut_pairs) {
  validate_mapping_options(options);
  const std::vector<MappingSlot> slots = mapping_slots(options.shared_dir, options.parts);
  require(!slots.empty(), MCON_ERROR_INVALID_ARGUMENT, "eval-mapping: no class selected");
  const int makehuman_slots = static_cast<int>(
      std::count_if(slots.begin(), slots.end(), [](const MappingSlot& s) { return s.model == "makehuman"; }));
  const int pairs = options.pairs > 0 ? options.pairs : (makehuman_slots > 0 ? makehuman_slots : static_cast<int>(slots.size()));

  tbb::task_arena arena(options.threads);
  std::map<std::string, Model> models;
  std::vector<MappingPairResult> results;
  for (int i = 0; i < pairs; ++i) {
    const MappingSlot& slot = slots[static_cast<std::size_t>(i) % slots.size()];
    const Model& model = model_for(models, options, slots, slot);
    MappingPairResult res;
    res.slot = slot;
    res.person_a = 2 * i;
    res.person_b = 2 * i + 1;
    try {
      arena.execute([&] { evaluate_pair(model, slot, i, options, res); });
    } catch (const Error& e) {
      // Under a perturbation a target can stay uncuttable on every retry (noise of a fraction of
      // an edge opens pockets): that pair is reported, not averaged.
      if (!options.perturbation.active() || uncut_pairs == nullptr) throw;
      uncut_pairs->push_back("pair " + std::to_string(i) + " " + slot.source_class + " -> " + slot.target_class + ": " +
                             e.what());
      if (options.log) options.log(uncut_pairs->back());
      if (options.progress) options.progress(static_cast<double>(i + 1) / pairs);
      continue;
    }
    if (options.log) log_pair(options, i, slot, res);
    if (options.progress) options.progress(static_cast<double>(i + 1) / pairs);
    results.push_back(std::move(res));
  }
  return results;
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

Json summary(const std::vector<const MethodPairResult*>& rs) {
  double eps = 0, within = 0, overlap = 0;
  int flips = 0;
  std::vector<double> secs, its;
  for (const MethodPairResult* r : rs) {
    eps += r->mean_eps;
    within += r->within_0_05;
    overlap += r->overlap;
    flips += r->flipped_triangles;
    secs.push_back(r->seconds);
    its.push_back(r->iterations);
  }
  const double n = rs.empty() ? 1.0 : static_cast<double>(rs.size());
  Json m = Json::object();
  m.set("mean_eps100", 100 * eps / n);
  m.set("within_0_05", within / n);
  m.set("flipped_triangles", flips);
  m.set("overlap", overlap / n);
  m.set("seconds_median", median(secs));
  m.set("iterations_median", median(its));
  return m;
}

}  // namespace

Json mapping_evaluation_json(const std::vector<MappingPairResult>& pairs, const std::vector<std::string>& methods) {
  Json out = Json::object();
  out.set("pairs", static_cast<int>(pairs.size()));
  Json ms = Json::object();
  for (const std::string& m : methods) {
    std::vector<const MethodPairResult*> all;
    std::map<std::string, std::vector<const MethodPairResult*>> by_part;
    for (const MappingPairResult& p : pairs) {
      const auto it = p.methods.find(m);
      if (it == p.methods.end()) continue;
      all.push_back(&it->second);
      by_part[p.slot.part].push_back(&it->second);
    }
    Json entry = Json::object();
    entry.set("overall", summary(all));
    Json per = Json::object();
    for (const char* part : kMappingParts)
      if (by_part.count(part)) per.set(part, summary(by_part[part]));
    entry.set("per_class", per);
    ms.set(m, entry);
  }
  out.set("methods", ms);
  std::map<std::string, std::vector<double>> edges;
  for (const MappingPairResult& p : pairs) {
    edges["overall"].push_back(100 * p.target_edge_eps);
    edges[p.slot.part].push_back(100 * p.target_edge_eps);
  }
  auto mean = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  };
  Json resolution = Json::object();
  resolution.set("overall", mean(edges["overall"]));
  Json per = Json::object();
  for (const char* part : kMappingParts)
    if (edges.count(part)) per.set(part, mean(edges[part]));
  resolution.set("per_class", per);
  out.set("target_edge_eps100", resolution);
  return out;
}

// ---- Cross-family pairs (MakeHuman <-> ICT), scored on semantic landmarks ----

namespace {

// The semantic landmarks of bench/semantic-landmarks.json: per name, the vertex on each model.
struct SemanticLandmarks {
  std::vector<std::string> names;                             // file order
  std::map<std::string, std::map<std::string, int>> vertex;  // model -> name -> base vertex
};

SemanticLandmarks read_semantic_landmarks(const std::string& shared) {
  const Json json = read_json_file(shared + "/bench/semantic-landmarks.json");
  SemanticLandmarks out;
  const Json& mh = json.at("models").at("makehuman").at("vertices");
  for (std::size_t k = 0; k < mh.size(); ++k) out.names.push_back(mh.key(k));
  for (const char* model : {"makehuman", "ict"}) {
    const Json& v = json.at("models").at(model).at("vertices");
    for (const std::string& name : out.names) out.vertex[model][name] = static_cast<int>(v.at(name).as_int());
  }
  return out;
}

// The same landmark on the other side ("_r" <-> "_l"); unsided names stay.
std::string other_side(const std::string& name) {
  const std::size_t n = name.size();
  if (n > 2 && name.compare(n - 2, 2, "_r") == 0) return name.substr(0, n - 2) + "_l";
  if (n > 2 && name.compare(n - 2, 2, "_l") == 0) return name.substr(0, n - 2) + "_r";
  return name;
}

int patch_vertex_of_host(const CutPatch& patch, int host) {
  const auto it = std::find(patch.host.begin(), patch.host.end(), host);
  return it == patch.host.end() ? -1 : static_cast<int>(it - patch.host.begin());
}

// The landmarks inside both patches: source patch vertex, true target patch vertex, and name.
struct LandmarkPairs {
  std::vector<int> sources, truths;
  std::vector<std::string> names;
};

LandmarkPairs landmarks_in_both(const SemanticLandmarks& lm, const CrossFamilySlot& slot, const PairPatches& pp) {
  LandmarkPairs out;
  for (const std::string& name : lm.names) {
    const int s = patch_vertex_of_host(pp.src, lm.vertex.at(slot.source_model).at(name));
    const std::string truth_name = slot.mirrored ? other_side(name) : name;
    const int t = patch_vertex_of_host(pp.dst, lm.vertex.at(slot.target_model).at(truth_name));
    if (s < 0 || t < 0) continue;
    out.sources.push_back(s);
    out.truths.push_back(t);
    out.names.push_back(name);
  }
  return out;
}

// Orientation check on the target, in its world frame (+x the subject's left, +y up): a landmark
// pair whose true separation along x or y is at least kOrientationSeparation x the target's
// geodesic radius and at least half of the pair's distance is "checked" on that axis; it is
// inverted if the mapped landmarks' separation along the axis has the opposite sign.
constexpr double kOrientationSeparation = 0.08;
// A gross failure: a pair whose median landmark eps exceeds this (issue 14's definition).
constexpr double kGrossFailureEps = 0.15;

void check_orientation(const std::vector<Vec3>& mapped, const std::vector<Vec3>& truth, double radius,
                       const std::vector<std::string>& names, CrossFamilyMethodResult& r) {
  for (std::size_t a = 0; a < truth.size(); ++a)
    for (std::size_t b = a + 1; b < truth.size(); ++b)
      for (int axis = 0; axis < 2; ++axis) {
        const Vec3 d = truth[b] - truth[a];
        if (std::abs(d[axis]) < kOrientationSeparation * radius || std::abs(d[axis]) < 0.5 * d.norm()) continue;
        ++r.checked_pairs;
        if ((mapped[b][axis] - mapped[a][axis]) * d[axis] >= 0) continue;
        ++r.inverted_pairs;
        if (!r.inverted.empty()) r.inverted += ", ";
        r.inverted += names[a] + "/" + names[b] + (axis == 0 ? " (x)" : " (y)");
      }
}

// One method's landmark scores: eps = geodesic distance on the target between the mapped and the
// true landmark / sqrt(target patch area); a landmark mapped outside the target is first moved
// to the nearest target point (it still counts).
void score_landmarks(const PairPatches& pp, const LandmarkPairs& lp, const std::vector<Vec2>& phi,
                     const TriangleLocator2D& locator, const std::vector<Eigen::VectorXd>& distances,
                     CrossFamilyMethodResult& r) {
  const TriMesh host = host_mesh(pp.dst.patch);
  const double scale = 1.0 / std::sqrt(patch_area(pp.dst.patch.mesh));
  std::vector<Vec3> mapped, truth;
  for (std::size_t k = 0; k < lp.sources.size(); ++k) {
    const PointLocation l = locator.locate_nearest(phi[lp.sources[k]], 1e300);
    const Tri& t = pp.dst.patch.mesh.triangles[l.triangle];
    const Eigen::VectorXd& d = distances[k];
    const Vec3& w = l.barycentric;
    r.landmark_eps.push_back(scale * std::max(0.0, w[0] * d[t[0]] + w[1] * d[t[1]] + w[2] * d[t[2]]));
    mapped.push_back(w[0] * host.positions[t[0]] + w[1] * host.positions[t[1]] + w[2] * host.positions[t[2]]);
    truth.push_back(host.positions[lp.truths[k]]);
  }
  check_orientation(mapped, truth, pp.dst.patch.radius, lp.names, r);
}

PairPatches cut_cross_family(const Model& src_model, const Model& dst_model, const MappingEvalOptions& options,
                             const CrossFamilySlot& slot, int i, CrossFamilyPairResult& res) {
  PairPatches out;
  for (int attempt = 0;; ++attempt) {
    res.person_a = 2 * i + 1000 * attempt;
    res.person_b = res.person_a + 1;
    try {
      const TriMesh a = src_model.instance(options.seed, res.person_a);
      const TriMesh b = dst_model.instance(options.seed, res.person_b);
      out.src = cut(src_model, src_model.bench.spec.find(slot.source_class), a, nullptr, nullptr);
      out.dst = cut(dst_model, dst_model.bench.spec.find(slot.target_class), b, nullptr, nullptr);
      return out;
    } catch (const Error& e) {
      if (e.status() != MCON_ERROR_NOT_A_DISK || attempt >= 4) throw;
      if (options.log) options.log("cross-family pair " + std::to_string(i) + ": " + e.what() + "; next people");
    }
  }
}

void evaluate_cross_family_pair(const Model& src_model, const Model& dst_model, const SemanticLandmarks& lm,
                                const MappingEvalOptions& options, int i, CrossFamilyPairResult& res) {
  const PairPatches pp = cut_cross_family(src_model, dst_model, options, res.slot, i, res);
  const LandmarkPairs lp = landmarks_in_both(lm, res.slot, pp);
  res.landmarks = lp.names;
  MappingPairResult scratch;
  PairMaps maps = unguided_maps(pp, options, scratch);
  if (wants(options, "proximity")) run_proximity(pp, res.slot.mirrored, maps, scratch);
  if (wants(options, "macrocon-frame") || wants(options, "frame-rigid"))
    run_frame(options, pp, res.slot.mirrored, maps, scratch.methods);
  if (wants(options, "macrocon-up")) run_up(options, pp, res.slot.mirrored, maps, scratch.methods, scratch.orientation_note);
  res.orientation_note = scratch.orientation_note;
  const TriangleLocator2D locator(pp.dst.patch.uv, pp.dst.patch.mesh.triangles);
  const HeatGeodesics heat(pp.dst.patch.mesh);
  std::vector<Eigen::VectorXd> distances(lp.truths.size());
  for_each_block(static_cast<int>(lp.truths.size()), 1, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) distances[k] = heat.from_vertices({lp.truths[k]});
  });
  for (const auto& [name, phi] : maps.phi) {
    CrossFamilyMethodResult& r = res.methods[name];
    r.reflected = maps.reflected.at(name);
    r.seconds = scratch.methods[name].seconds;
    if (maps.signals.count(name)) r.signals = maps.signals.at(name);
    score_landmarks(pp, lp, phi, locator, distances, r);
  }
}

}  // namespace

std::vector<CrossFamilySlot> cross_family_slots(const std::vector<std::string>& parts) {
  std::vector<CrossFamilySlot> slots;
  for (const char* part : {"eye", "nose", "mouth", "ear", "face"}) {
    if (!parts.empty() && std::find(parts.begin(), parts.end(), part) == parts.end()) continue;
    const std::string p(part);
    const bool sided = p == "eye" || p == "ear";
    for (const auto& [from, to] : {std::pair<const char*, const char*>{"makehuman", "ict"}, {"ict", "makehuman"}}) {
      if (sided) {
        slots.push_back({from, to, p, false, p + "_r", p + "_r"});
        slots.push_back({from, to, p, true, p + "_r", p + "_l"});
      } else {
        slots.push_back({from, to, p, false, p, p});
      }
    }
  }
  return slots;
}

std::vector<CrossFamilyPairResult> run_cross_family_evaluation(const MappingEvalOptions& options) {
  validate_mapping_options(options);
  for (const std::string& m : options.methods)
    require(m == "macrocon" || m == "rigid" || m == "thesis" || m == "proximity" || m == "macrocon-frame" ||
                m == "frame-rigid" || m == "macrocon-up",
            MCON_ERROR_INVALID_ARGUMENT,
            "eval-mapping --cross-family: method '" + m + "' needs in-family ground truth");
  const std::vector<CrossFamilySlot> slots = cross_family_slots(options.parts);
  const SemanticLandmarks lm = read_semantic_landmarks(options.shared_dir);
  std::map<std::string, Model> models;
  for (const char* name : {"makehuman", "ict"}) models.emplace(name, load_model(options.shared_dir, name));
  tbb::task_arena arena(options.threads);
  std::vector<CrossFamilyPairResult> results;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    CrossFamilyPairResult res;
    res.slot = slots[i];
    arena.execute([&] {
      evaluate_cross_family_pair(models.at(res.slot.source_model), models.at(res.slot.target_model), lm, options,
                                 static_cast<int>(i), res);
    });
    if (options.log) {
      std::ostringstream line;
      line << "cross-family " << i << " " << res.slot.source_model << " " << res.slot.source_class << " -> "
           << res.slot.target_model << " " << res.slot.target_class << " (" << res.landmarks.size() << " landmarks):";
      for (const auto& [name, r] : res.methods) {
        line << " " << name << (r.reflected ? " (mirrored)" : "") << " median eps100 "
             << fmt(100 * median(r.landmark_eps)) << " inverted " << r.inverted_pairs << "/" << r.checked_pairs
             << (r.inverted.empty() ? "" : " [" + r.inverted + "]") << " " << fmt(r.seconds) << "s;";
      }
      if (!res.orientation_note.empty()) line << " (" << res.orientation_note << ")";
      options.log(line.str());
    }
    if (options.progress) options.progress(static_cast<double>(i + 1) / static_cast<double>(slots.size()));
    results.push_back(std::move(res));
  }
  return results;
}

namespace {

bool gross_failure(const CrossFamilyMethodResult& r) {
  return !r.landmark_eps.empty() && median(r.landmark_eps) > kGrossFailureEps;
}

// ROC AUC of each signal for telling the pairs that are not gross failures (positives) from those
// that are: the probability that a random positive scores higher than a random negative (ties
// count half; Mann-Whitney U / (P N)). Null when a class is empty.
Json signal_auc(const std::vector<const CrossFamilyMethodResult*>& rs) {
  Json out = Json::object();
  if (rs.empty() || rs.front()->signals.empty()) return out;
  for (const auto& entry : rs.front()->signals) {
    const std::string& name = entry.first;
    std::vector<double> good, bad;
    for (const CrossFamilyMethodResult* r : rs) {
      const auto it = r->signals.find(name);
      if (it == r->signals.end()) continue;
      (gross_failure(*r) ? bad : good).push_back(it->second);
    }
    if (good.empty() || bad.empty()) {
      out.set(name, Json());
      continue;
    }
    double u = 0;
    for (double g : good)
      for (double b : bad) u += g > b ? 1.0 : (g == b ? 0.5 : 0.0);
    out.set(name, u / static_cast<double>(good.size() * bad.size()));
  }
  return out;
}

Json cross_family_summary(const std::vector<const CrossFamilyMethodResult*>& rs) {
  std::vector<double> all, pair_means, secs;
  int gross = 0, wrong = 0;
  for (const CrossFamilyMethodResult* r : rs) {
    double sum = 0;
    for (double e : r->landmark_eps) {
      all.push_back(e);
      sum += e;
    }
    pair_means.push_back(r->landmark_eps.empty() ? 0.0 : sum / static_cast<double>(r->landmark_eps.size()));
    gross += gross_failure(*r);
    wrong += r->inverted_pairs > 0;
    secs.push_back(r->seconds);
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
  };
  Json m = Json::object();
  m.set("pairs", static_cast<int>(rs.size()));
  m.set("mean_eps100", 100 * mean(pair_means));
  m.set("landmark_mean_eps100", 100 * mean(all));
  m.set("median_eps100", 100 * median(all));
  m.set("gross_failures", rs.empty() ? 0.0 : static_cast<double>(gross) / static_cast<double>(rs.size()));
  m.set("orientation_errors", wrong);
  m.set("seconds_median", median(secs));
  return m;
}

Json cross_family_case(const CrossFamilyPairResult& p, const std::vector<std::string>& methods) {
  Json c = Json::object();
  c.set("source", p.slot.source_model + " " + p.slot.source_class);
  c.set("target", p.slot.target_model + " " + p.slot.target_class);
  c.set("mirrored", p.slot.mirrored);
  c.set("landmarks", static_cast<int>(p.landmarks.size()));
  Json ms = Json::object();
  for (const std::string& m : methods) {
    const auto it = p.methods.find(m);
    if (it == p.methods.end()) continue;
    const CrossFamilyMethodResult& r = it->second;
    double sum = 0;
    for (double e : r.landmark_eps) sum += e;
    Json e = Json::object();
    e.set("mean_eps100", r.landmark_eps.empty() ? 0.0 : 100 * sum / static_cast<double>(r.landmark_eps.size()));
    e.set("median_eps100", 100 * median(r.landmark_eps));
    e.set("reflected", r.reflected);
    e.set("checked_pairs", r.checked_pairs);
    e.set("inverted_pairs", r.inverted_pairs);
    e.set("inverted", r.inverted);
    if (!r.signals.empty()) {
      Json sig = Json::object();
      for (const auto& [name, value] : r.signals) sig.set(name, value);
      e.set("signals", sig);
    }
    ms.set(m, e);
  }
  c.set("methods", ms);
  return c;
}

}  // namespace

Json cross_family_json(const std::vector<CrossFamilyPairResult>& pairs, const std::vector<std::string>& methods) {
  Json out = Json::object();
  out.set("pairs", static_cast<int>(pairs.size()));
  Json ms = Json::object();
  for (const std::string& m : methods) {
    std::vector<const CrossFamilyMethodResult*> all;
    std::map<std::string, std::vector<const CrossFamilyMethodResult*>> by_part;
    for (const CrossFamilyPairResult& p : pairs) {
      const auto it = p.methods.find(m);
      if (it == p.methods.end()) continue;
      all.push_back(&it->second);
      by_part[p.slot.part].push_back(&it->second);
    }
    Json entry = Json::object();
    entry.set("overall", cross_family_summary(all));
    if (!all.empty() && !all.front()->signals.empty()) entry.set("signal_roc_auc", signal_auc(all));
    Json per = Json::object();
    for (const char* part : kMappingParts)
      if (by_part.count(part)) per.set(part, cross_family_summary(by_part[part]));
    entry.set("per_class", per);
    ms.set(m, entry);
  }
  out.set("methods", ms);
  Json cases = Json::array();
  for (const CrossFamilyPairResult& p : pairs) cases.push_back(cross_family_case(p, methods));
  out.set("cases", cases);
  return out;
}

}  // namespace mcon::tools
