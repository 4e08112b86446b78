#include "map/surface_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "map/coarse_source.h"
#include "map/descriptor_field_2d.h"
#include "base/error.h"
#include "map/injective_step.h"
#include "mesh/mesh_topology.h"
#include "mesh/point_location_2d.h"

namespace mcon {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void check_domain(const MapDomain& d, const char* name) {
  const std::string who(name);
  validate_mesh(d.mesh);
  require(d.uv.size() == d.mesh.positions.size(), MCON_ERROR_INVALID_ARGUMENT,
          who + ": uv must have one entry per vertex");
  for (const Vec2& p : d.uv)
    require(std::isfinite(p.x()) && std::isfinite(p.y()), MCON_ERROR_NON_FINITE, who + ": non-finite uv");
  require(!d.descriptor_levels.empty(), MCON_ERROR_INVALID_ARGUMENT, who + ": no descriptor level");
  for (const Eigen::MatrixXd& level : d.descriptor_levels) {
    require(level.rows() == d.mesh.num_vertices(), MCON_ERROR_INVALID_ARGUMENT,
            who + ": a descriptor level does not have one row per vertex");
    require(level.cols() >= 1, MCON_ERROR_INVALID_ARGUMENT, who + ": descriptor dimension 0");
    require(level.allFinite(), MCON_ERROR_NON_FINITE, who + ": non-finite descriptor value");
  }
  for (int t = 0; t < d.mesh.num_triangles(); ++t) {
    const Tri& tri = d.mesh.triangles[t];
    const Vec2 e1 = d.uv[tri[1]] - d.uv[tri[0]], e2 = d.uv[tri[2]] - d.uv[tri[0]];
    require(e1.x() * e2.y() - e1.y() * e2.x() > 0, MCON_ERROR_INVALID_ARGUMENT,
            who + ": uv triangle " + std::to_string(t) + " is inverted or degenerate");
  }
}


double polygon_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross2(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}

// Share of each source triangle's image inside the target's boundary polygon (convex: its
// corners lie on the unit circle in counter-clockwise order), by Sutherland-Hodgman clipping;
// the map is affine per triangle, so this is also the share of its 3D area. Triangles inside
// the polygon's inscribed circle skip the clipping.
double overlap_ratio(const SourceDisk& disk, const std::vector<Vec2>& phi, const std::vector<Vec2>& polygon) {
  double inscribed = 1;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 a = polygon[i], e = polygon[(i + 1) % polygon.size()] - a;
    inscribed = std::min(inscribed, cross2(e, -a) / e.norm());  // distance of the origin to the edge's line
  }
  double overlap = 0;
  std::vector<Vec2> poly, next;
  for (std::size_t t = 0; t < disk.triangles.size(); ++t) {
    const Tri& tri = disk.triangles[t];
    poly = {phi[tri[0]], phi[tri[1]], phi[tri[2]]};
    if (std::max({poly[0].norm(), poly[1].norm(), poly[2].norm()}) <= inscribed) {
      overlap += disk.triangle_weight[t];
      continue;
    }
    const double full = polygon_area(poly);
    for (std::size_t i = 0; i < polygon.size() && !poly.empty(); ++i) {
      const Vec2 a = polygon[i], e = polygon[(i + 1) % polygon.size()] - a;
      next.clear();
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
        const double sp = cross2(e, p - a), sq = cross2(e, q - a);  // >= 0: inside (left of the edge)
        if (sp >= 0) next.push_back(p);
        if ((sp >= 0) != (sq >= 0)) next.push_back(p + (sp / (sp - sq)) * (q - p));
      }
      poly.swap(next);
    }
    if (poly.size() >= 3 && full > 0) overlap += disk.triangle_weight[t] * std::clamp(polygon_area(poly) / full, 0.0, 1.0);
  }
  return overlap;
}


// Source and target must agree in their descriptor levels, and the options must be usable.
void check_inputs(const MapDomain& source, const MapDomain& target, const SurfaceMapOptions& options) {
  check_domain(source, "source");
  check_domain(target, "target");
  const int L = static_cast<int>(source.descriptor_levels.size());
  require(static_cast<int>(target.descriptor_levels.size()) == L, MCON_ERROR_INVALID_ARGUMENT,
          "source and target have different numbers of descriptor levels");
  for (int l = 0; l < L; ++l)
    require(source.descriptor_levels[l].cols() == target.descriptor_levels[l].cols(), MCON_ERROR_INVALID_ARGUMENT,
            "source and target descriptors differ in dimension at level " + std::to_string(l));
  require(options.sigma_scale > 0 && options.rim_band > 0 && options.rim_band < 1 &&
              options.orientation_ambiguity >= 0 && options.mirror_energy_margin >= 0 &&
              options.mirror_energy_margin < 1 &&
              options.weights.barrier_start > 0 && options.weights.descriptor >= 0 &&
              options.weights.distortion >= 0 && options.weights.area >= 0 && options.weights.injectivity >= 0,
          MCON_ERROR_INVALID_ARGUMENT, "invalid map options");
  for (double f : options.refine_sigma_factors)
    require(f > 0 && std::isfinite(f), MCON_ERROR_INVALID_ARGUMENT,
            "invalid map options: refinement sigma factors must be finite and > 0");
  require(options.refine_max_iterations >= 1, MCON_ERROR_INVALID_ARGUMENT,
          "invalid map options: refine_max_iterations must be >= 1");
  require(!options.frame_start || (options.orientation == MapOrientation::automatic &&
                                   std::isfinite(options.frame_start->angle) &&
                                   options.frame_start->translation.allFinite()),
          MCON_ERROR_INVALID_ARGUMENT, "invalid map options: a frame start needs automatic orientation and finite values");
  require(options.weights.anchor >= 0 && std::isfinite(options.weights.anchor), MCON_ERROR_INVALID_ARGUMENT,
          "invalid map options: the anchor weight must be finite and >= 0");
  require(options.anchor_decay > 0 && options.anchor_decay <= 1, MCON_ERROR_INVALID_ARGUMENT,
          "invalid map options: anchor_decay must be in (0, 1]");
  require(options.start_anchor >= 0 && std::isfinite(options.start_anchor), MCON_ERROR_INVALID_ARGUMENT,
          "invalid map options: start_anchor must be finite and >= 0");
  if (options.weights.anchor > 0) {
    const std::size_t n = source.uv.size();
    require(options.anchor.position.size() == n && options.anchor.weight.size() == n, MCON_ERROR_INVALID_ARGUMENT,
            "invalid map options: an anchor weight > 0 needs one anchor position and weight per source vertex");
    for (std::size_t v = 0; v < n; ++v)
      require(options.anchor.position[v].allFinite() && options.anchor.weight[v] >= 0 && options.anchor.weight[v] <= 1,
              MCON_ERROR_INVALID_ARGUMENT, "invalid map options: anchor positions must be finite, weights in [0, 1]");
  }
}

// The target's single boundary loop in uv, which must lie on the unit circle counter-clockwise.
std::vector<Vec2> target_boundary_polygon(const MapDomain& target) {
  std::vector<Vec2> target_polygon;
  const MeshTopology topo = build_topology(target.mesh);
  require(topo.boundary_loops.size() == 1, MCON_ERROR_NOT_A_DISK, "target: expected exactly one boundary loop");
  for (int v : topo.boundary_loops[0]) {
    require(std::abs(target.uv[v].norm() - 1.0) <= 1e-6, MCON_ERROR_INVALID_ARGUMENT,
            "target: uv boundary vertex " + std::to_string(v) + " is not on the unit circle");
    target_polygon.push_back(target.uv[v]);
  }
  require(polygon_area(target_polygon) > 0, MCON_ERROR_INVALID_ARGUMENT,
          "target: uv boundary is not counter-clockwise");
  return target_polygon;
}

void report_progress(const SurfaceMapOptions& options, double f) {
  if (options.progress && !options.progress(f)) fail(MCON_ERROR_CANCELLED, "surface map cancelled");
}

// The descriptor levels as the score reads them: the target's fields, the source's values (and
// the source as a mirrored map sees it, if chiral columns change sign) and the Gaussian widths.
struct Levels {
  std::vector<std::shared_ptr<const DescriptorField2D>> fields;  // shared with a coarse copy
  std::vector<Eigen::MatrixXd> reflected;  // the source as a mirrored map sees it
  std::vector<MatchLevel> match;
};

// One field per target level, the source values it is compared with and its Gaussian width.
Levels match_levels(const MapDomain& source, const MapDomain& target, const SurfaceMapOptions& options,
                    const TriangleLocator2D& target_locator) {
  const int L = static_cast<int>(source.descriptor_levels.size());
  Levels levels;
  levels.match.resize(L);
  for (int c : options.chiral_columns)
    require(c >= 0 && c < source.descriptor_levels[0].cols(), MCON_ERROR_INVALID_ARGUMENT,
            "chiral column " + std::to_string(c) + " is not a descriptor column");
  if (!options.chiral_columns.empty())
    for (int l = 0; l < L; ++l) {
      levels.reflected.push_back(source.descriptor_levels[l]);
      for (int c : options.chiral_columns) levels.reflected.back().col(c) *= -1.0;
    }
  for (int l = 0; l < L; ++l) {
    MatchLevel& level = levels.match[l];
    levels.fields.push_back(std::make_shared<DescriptorField2D>(target_locator, target.descriptor_levels[l]));
    level.source_values = &source.descriptor_levels[l];
    if (!levels.reflected.empty()) level.source_values_reflected = &levels.reflected[l];
    level.target_field = levels.fields.back().get();
    level.score.sigma =
        options.sigma_scale * descriptor_sigma(source.descriptor_levels[l], target.descriptor_levels[l]);
    level.score.band = options.rim_band;
  }
  return levels;
}

const Eigen::MatrixXd& source_values(const MapDomain& source, const Levels& levels, int l, bool reflected) {
  return reflected && !levels.reflected.empty() ? levels.reflected[l] : source.descriptor_levels[l];
}

constexpr double kAlignShare = 0.15;

// The best rigid (possibly mirrored) start; a forced orientation takes its own best.
RigidAlignmentResult rigid_start(const MapDomain& source, const SourceDisk& plain, const Levels& levels,
                                 const SurfaceMapOptions& options) {
  RigidAlignmentOptions alignment_options = options.alignment;
  if (options.orientation != MapOrientation::automatic) alignment_options.allow_reflection = true;  // both scored
  RigidAlignmentResult init = align_rigid(source.uv, plain.vertex_weight, levels.match, alignment_options,
                                          [&](double f) { report_progress(options, kAlignShare * f); return true; });
  if (options.frame_start) {
    // The world frame decides: its start, scored like the candidates (mean over levels).
    init.transform = *options.frame_start;
    std::vector<Vec2> moved(source.uv.size());
    for (std::size_t v = 0; v < moved.size(); ++v) moved[v] = init.transform.apply(source.uv[v]);
    double score = 0;
    for (MatchLevel level : levels.match) {
      if (init.transform.reflected && level.source_values_reflected) level.source_values = level.source_values_reflected;
      score += matching_score_sum(moved, plain.vertex_weight, level);
    }
    init.score = score / static_cast<double>(levels.match.size());
    return init;
  }
  if (options.orientation != MapOrientation::automatic) {
    // A forced orientation takes that orientation's best refined candidate.
    const bool reverse = options.orientation == MapOrientation::reverse;
    const double score = reverse ? init.score_reflected : init.score_unreflected;
    require(score >= 0, MCON_ERROR_NUMERICAL, "surface map: no rigid candidate of the requested orientation");
    init.transform = reverse ? init.best_reflected : init.best_unreflected;
    init.score = score;
  }
  return init;
}

// What every Newton stage reads. Stage s < L is descriptor level s; stage s >= L is refinement
// pass s - L at the finest level with its narrower width (sigma[s]).
struct Stages {
  const MapDomain& source;
  const Levels& levels;
  const SurfaceMapOptions& options;
  std::vector<double> sigma;  // per stage
  int L = 0;
  int R = 0;
  double level_share = 0;  // progress range of one stage
  double level_from(int l) const { return kAlignShare + l * level_share; }
};

// The Gaussian width of each stage: each level's, then the finest level's times each refinement
// factor.
std::vector<double> stage_sigmas(const Levels& levels, const SurfaceMapOptions& options) {
  const int L = static_cast<int>(levels.match.size());
  const int R = static_cast<int>(options.refine_sigma_factors.size());
  std::vector<double> sigma(L + R);
  for (int l = 0; l < L; ++l) sigma[l] = levels.match[l].score.sigma;
  for (int r = 0; r < R; ++r) sigma[L + r] = levels.match[L - 1].score.sigma * options.refine_sigma_factors[r];
  return sigma;
}

ScoreSettings stage_score(const Stages& st, int s) {
  ScoreSettings score = st.levels.match[std::min(s, st.L - 1)].score;
  score.outside = OutsideRule::nearest_rim;
  score.sigma = st.sigma[s];
  return score;
}

// Runs stage s from x; its iterations map into the progress range [progress_from, progress_to].
// energy_scale: the first level's start energy, the tolerance scale of later stages.
// start_anchor: the candidate's own start positions when SurfaceMapOptions::start_anchor > 0.
// warm: the candidate's factorization, handed from stage to stage.
NewtonReport run_level(const Stages& st, int s, const SourceDisk& disk, const MapAnchor* start_anchor,
                       Eigen::VectorXd& x, double energy_scale, double progress_from, double progress_to,
                       NewtonWarmStart& warm) {
  const SurfaceMapOptions& options = st.options;
  const int l = std::min(s, st.L - 1);
  MapEnergyWeights weights = options.weights;
  const MapAnchor* anchor = &options.anchor;
  if (start_anchor && options.weights.anchor == 0) {
    weights.anchor = options.start_anchor;
    anchor = start_anchor;
  }
  weights.anchor *= std::pow(options.anchor_decay, s);
  const MapEnergy energy(disk, *st.levels.fields[l], source_values(st.source, st.levels, l, disk.reflected),
                         stage_score(st, s), weights, anchor);
  bool cancelled = false;
  NewtonOptions newton = options.newton;
  if (s >= st.L) newton.max_iterations = std::min(newton.max_iterations, options.refine_max_iterations);
  newton.energy_scale = std::max(newton.energy_scale, energy_scale);
  const int cap = std::max(newton.max_iterations, 1);
  NewtonReport r = minimize_map_energy(energy, x, newton, [&](int it, double) {
    const double f = progress_from + (progress_to - progress_from) * std::min(1.0, static_cast<double>(it) / cap);
    if (options.progress && !options.progress(std::min(f, 0.999))) cancelled = true;
    return !cancelled;
  }, &warm);
  if (cancelled || r.reason == StopReason::cancelled) fail(MCON_ERROR_CANCELLED, "surface map cancelled");
  return r;
}

Eigen::VectorXd start_from(const MapDomain& source, const RigidTransform2D& T) {
  const int n = source.mesh.num_vertices();
  Eigen::VectorXd x(2 * n);
  for (int v = 0; v < n; ++v) x.segment<2>(2 * v) = T.apply(source.uv[v]);
  return x;
}

// One orientation's optimization: its disk, iterate and per-level reports.
struct Candidate {
  const SourceDisk* disk;
  RigidTransform2D start;
  Eigen::VectorXd x;
  std::vector<NewtonReport> reports;
  double energy_scale = 0;
  MapAnchor start_anchor;  // its start positions, when SurfaceMapOptions::start_anchor > 0
  NewtonWarmStart warm;    // its last factorization, for the next stage
};

// A candidate from its rigid start (and, with start_anchor > 0, that start as its anchor).
Candidate make_candidate(const Stages& st, const SourceDisk* disk, const RigidTransform2D& T) {
  Candidate c{disk, T, start_from(st.source, T), {}, 0, {}, {}};
  if (st.options.start_anchor > 0) {
    const int n = static_cast<int>(c.x.size() / 2);
    c.start_anchor.position.resize(n);
    for (int v = 0; v < n; ++v) c.start_anchor.position[v] = c.x.segment<2>(2 * v);
    c.start_anchor.weight.assign(n, 1.0);
  }
  return c;
}

// Runs the candidate's next level in the progress range [p0, p1].
void advance(const Stages& st, Candidate& c, double p0, double p1) {
  const int l = static_cast<int>(c.reports.size());
  c.reports.push_back(run_level(st, l, *c.disk, c.start_anchor.position.empty() ? nullptr : &c.start_anchor, c.x,
                                c.energy_scale, p0, p1, c.warm));
  if (l == 0) c.energy_scale = c.reports.back().energy.front();
}

// Both orientations, each optimized on its own; the lower energy after the compared levels
// decides, the mirrored one only by the relative margin.
Candidate better_orientation(const Stages& st, const RigidAlignmentResult& init, const SourceDisk& plain,
                             const SourceDisk& mirrored, SurfaceMap& out) {
  Candidate cp = make_candidate(st, &plain, init.best_unreflected);
  Candidate cm = make_candidate(st, &mirrored, init.best_reflected);
  const int upto = std::clamp(st.options.compared_levels, 1, st.L);
  for (int l = 0; l < upto; ++l) {
    const double mid = st.level_from(l) + 0.5 * st.level_share;
    advance(st, cp, st.level_from(l), mid);
    advance(st, cm, mid, st.level_from(l + 1));
  }
  out.orientation_compared = true;
  out.level0_energy_unreflected = cp.reports.front().energy.back();
  out.level0_energy_reflected = cm.reports.front().energy.back();
  const bool mirror_wins =
      cm.reports.back().energy.back() < (1 - st.options.mirror_energy_margin) * cp.reports.back().energy.back();
  out.alignment.transform = mirror_wins ? init.best_reflected : init.best_unreflected;
  out.alignment.score = mirror_wins ? init.score_reflected : init.score_unreflected;
  return mirror_wins ? std::move(cm) : std::move(cp);
}

// The coarse copy of the source and everything its stages read in place of the full source's:
// the descriptor rows (and their mirrored copies) and anchor positions of its vertices, its rest
// disks; the target fields are shared.
struct CoarseStages {
  CoarseSource coarse;
  std::vector<Eigen::MatrixXd> descriptor_levels;
  MapDomain domain;
  Levels levels;
  SurfaceMapOptions options;
  SourceDisk plain, mirrored;
  Stages stages;

  CoarseStages(const Stages& fine, CoarseSource c)
      : coarse(std::move(c)),
        descriptor_levels(restricted(fine.source.descriptor_levels)),
        domain{coarse.mesh, coarse.uv, descriptor_levels},
        levels(restricted_levels(fine.levels)),
        options(restricted_options(fine.options)),
        plain(make_source_disk(coarse.mesh, coarse.uv, false)),
        mirrored(make_source_disk(coarse.mesh, coarse.uv, true)),
        stages{domain, levels, options, fine.sigma, fine.L, fine.R, fine.level_share} {}

 private:
  std::vector<Eigen::MatrixXd> restricted(const std::vector<Eigen::MatrixXd>& rows) const {
    std::vector<Eigen::MatrixXd> out;
    for (const Eigen::MatrixXd& m : rows) out.push_back(coarse.restrict_rows(m));
    return out;
  }
  Levels restricted_levels(const Levels& fine) const {
    Levels l;
    l.fields = fine.fields;
    l.reflected = restricted(fine.reflected);
    l.match = fine.match;  // the stages read only its score settings
    return l;
  }
  SurfaceMapOptions restricted_options(const SurfaceMapOptions& fine) const {
    SurfaceMapOptions o = fine;
    if (!fine.anchor.position.empty()) {
      o.anchor.position.clear();
      o.anchor.weight.clear();
      for (int v : coarse.to_fine) {
        o.anchor.position.push_back(fine.anchor.position[v]);
        o.anchor.weight.push_back(fine.anchor.weight[v]);
      }
    }
    return o;
  }
};

// Hands a candidate from the coarse stages to the full source: the iterate after the last coarse
// stage, prolonged, its few folded triangles untangled; if they cannot be, the iterate after an
// earlier stage (smoother, so it folds less), the later stages to run again on the full source;
// if none, its rigid start. snapshots: (stages done, iterate), in order.
void prolong_candidate(const Stages& fine, const CoarseStages& cs, const SourceDisk& plain, const SourceDisk& mirrored,
                       const std::vector<std::pair<int, Eigen::VectorXd>>& snapshots, Candidate& c, SurfaceMap& out) {
  const SourceDisk* disk = c.disk->reflected ? &mirrored : &plain;
  Candidate f = make_candidate(fine, disk, c.start);  // its start anchor on the full source
  f.energy_scale = c.energy_scale;
  out.coarse_stages = 0;
  for (auto it = snapshots.rbegin(); it != snapshots.rend(); ++it) {
    Eigen::VectorXd x = cs.coarse.prolong(it->second);
    const int folds = count_inverted(disk->triangles, x);
    if (it == snapshots.rbegin()) out.coarse_folds = folds;
    if (folds > 0 && !untangle_folds(disk->triangles, fine.source.uv, x)) {
      out.coarse_fallback = true;
      continue;
    }
    f.x = std::move(x);
    f.reports.assign(c.reports.begin(), c.reports.begin() + it->first);
    out.coarse_stages = it->first;
    break;
  }
  if (out.coarse_stages == 0) f.energy_scale = 0;  // the full source starts over
  c = std::move(f);
}

// The stages' Newton reports into the map's per-level reports, energy history and totals.
void collect_reports(const std::vector<NewtonReport>& reports, int L, SurfaceMap& out) {
  for (int l = 0; l < static_cast<int>(reports.size()); ++l) {
    const NewtonReport& r = reports[l];
    LevelReport& lr = out.levels[l];
    lr.iterations = r.iterations;
    lr.stop_reason = r.reason;
    lr.energy_start = r.energy.front();
    lr.energy_end = r.energy.back();
    for (double e : r.energy) {
      out.energy_history.push_back(e);
      out.energy_history_level.push_back(l);
    }
    out.iterations += r.iterations;
    out.factorizations += r.factorizations;
    out.inner_iterations += r.inner_iterations;
    if (l == L - 1) out.stop_reason = r.reason;  // a refinement pass ends at its short cap by design
    out.energy = r.terms;
  }
}

// Whether both orientations are optimized: automatic orientation, both scored, and their rigid
// scores too close to tell.
bool compare_orientations(const SurfaceMapOptions& options, const RigidAlignmentResult& init) {
  return options.orientation == MapOrientation::automatic && !options.frame_start && init.score_unreflected >= 0 &&
         init.score_reflected >= 0 && options.alignment.allow_reflection &&
         std::abs(init.score_reflected - init.score_unreflected) < options.orientation_ambiguity;
}

// The candidate's remaining stages, through the last refinement pass.
void run_remaining_levels(const Stages& st, Candidate& chosen) {
  while (static_cast<int>(chosen.reports.size()) < st.L + st.R) {
    const int l = static_cast<int>(chosen.reports.size());
    advance(st, chosen, st.level_from(l), st.level_from(l + 1));
  }
}

// The energy terms of x at the finest level's width.
MapEnergyTerms finest_level_terms(const Stages& st, const SourceDisk& disk, const Eigen::VectorXd& x) {
  const int L = st.L;
  return MapEnergy(disk, *st.levels.fields[L - 1], source_values(st.source, st.levels, L - 1, disk.reflected),
                   stage_score(st, L - 1), st.options.weights, &st.options.anchor)
      .evaluate(x);
}

// phi, the correspondences in both directions and the overlap ratio.
void map_both_directions(const MapDomain& source, const MapDomain& target, const TriangleLocator2D& target_locator,
                         const SourceDisk& disk, const std::vector<Vec2>& target_polygon, const Eigen::VectorXd& x,
                         SurfaceMap& out) {
  const int n = source.mesh.num_vertices();
  out.phi.resize(n);
  for (int v = 0; v < n; ++v) out.phi[v] = x.segment<2>(2 * v);
  out.source_to_target.resize(n);
  for (int v = 0; v < n; ++v) {
    const PointLocation loc = target_locator.locate(out.phi[v]);
    out.source_to_target[v] = {loc.triangle, loc.barycentric};
  }
  out.overlap_ratio = overlap_ratio(disk, out.phi, target_polygon);
  const TriangleLocator2D deformed(out.phi, source.mesh.triangles);
  out.target_to_source.resize(target.uv.size());
  for (std::size_t w = 0; w < target.uv.size(); ++w) {
    const PointLocation loc = deformed.locate(target.uv[w]);
    out.target_to_source[w] = {loc.triangle, loc.barycentric};
  }
}

}  // namespace

SurfaceMap compute_surface_map(const MapDomain& source, const MapDomain& target, const SurfaceMapOptions& options) {
  check_inputs(source, target, options);
  const std::vector<Vec2> target_polygon = target_boundary_polygon(target);
  report_progress(options, 0.0);

  // Target fields and the per-level Gaussian widths.
  const TriangleLocator2D target_locator(target.uv, target.mesh.triangles);
  const Levels levels = match_levels(source, target, options, target_locator);
  const int L = static_cast<int>(levels.match.size());
  const int R = static_cast<int>(options.refine_sigma_factors.size());
  const Stages stages{source, levels, options, stage_sigmas(levels, options), L, R, (1 - kAlignShare) / (L + R)};
  SurfaceMap out;
  out.levels.resize(L + R);
  for (int s = 0; s < L + R; ++s) out.levels[s].sigma = stages.sigma[s];

  // 1. Rigid start.
  const auto t0 = std::chrono::steady_clock::now();
  const SourceDisk plain = make_source_disk(source.mesh, source.uv, false);
  const RigidAlignmentResult init = rigid_start(source, plain, levels, options);
  out.alignment_seconds = seconds_since(t0);
  out.alignment = init;
  out.frame_decided = options.frame_start.has_value();

  // 2. Projected Newton, smoothest level first.
  const auto t1 = std::chrono::steady_clock::now();
  const bool compare = compare_orientations(options, init);
  // The mirrored rest disk only where a mirrored candidate runs.
  const SourceDisk mirrored = (compare || init.transform.reflected) ? make_source_disk(source.mesh, source.uv, true)
                                                                    : SourceDisk{};
  // The first stages on a coarse copy of the source (at least the compared ones, never the last).
  const int n = source.mesh.num_vertices();
  int coarse_count = std::min(std::max(options.coarse_stages, compare ? options.compared_levels : 0), L + R - 1);
  if (options.coarse_stages <= 0 || n < 2 * options.coarse_vertices) coarse_count = 0;
  std::unique_ptr<CoarseStages> cs;
  if (coarse_count > 0) {
    // 0.6: a coarse disk with more vertices than that does not pay for itself.
    std::optional<CoarseSource> coarse =
        coarsen_source(source.mesh, source.uv, std::max(options.coarse_vertices, n / 4), 0.6);
    if (coarse) {
      cs = std::make_unique<CoarseStages>(stages, std::move(*coarse));
      out.coarse_vertices = cs->coarse.num_vertices();
    }
  }
  const Stages& first = cs ? cs->stages : stages;
  const SourceDisk& first_plain = cs ? cs->plain : plain;
  const SourceDisk& first_mirrored = cs ? cs->mirrored : mirrored;
  Candidate chosen =
      compare ? better_orientation(first, init, first_plain, first_mirrored, out)
              : make_candidate(first, init.transform.reflected ? &first_mirrored : &first_plain, init.transform);
  if (cs) {
    std::vector<std::pair<int, Eigen::VectorXd>> snapshots;
    if (!chosen.reports.empty()) snapshots.emplace_back(static_cast<int>(chosen.reports.size()), chosen.x);
    while (static_cast<int>(chosen.reports.size()) < coarse_count) {
      const int l = static_cast<int>(chosen.reports.size());
      advance(first, chosen, first.level_from(l), first.level_from(l + 1));
      snapshots.emplace_back(l + 1, chosen.x);
    }
    prolong_candidate(stages, *cs, plain, mirrored, snapshots, chosen, out);
  }
  const SourceDisk& disk = *chosen.disk;
  out.reflected = disk.reflected;
  run_remaining_levels(stages, chosen);
  collect_reports(chosen.reports, L, out);
  const Eigen::VectorXd& x = chosen.x;
  if (R > 0)  // the reported terms (and matching score) keep the finest level's width
    out.energy = finest_level_terms(stages, disk, x);
  out.optimization_seconds = seconds_since(t1);
  const int inverted = count_inverted(disk.triangles, x);
  require(inverted == 0, MCON_ERROR_NUMERICAL,
          "surface map: " + std::to_string(inverted) + " inverted triangles in the result");
  out.matching_score = 1.0 - out.energy.value("descriptor");

  // 3. Both directions and the overlap.
  map_both_directions(source, target, target_locator, disk, target_polygon, x, out);
  report_progress(options, 1.0);
  return out;
}

}  // namespace mcon
