// The re-embedding objective (thesis eq. 4.15), reformulated to be continuous so that a
// projected Newton method can minimize it. x holds the deformed source disk phi(f(v)) of every
// source vertex (x0, y0, x1, y1, ...); all terms are integrals over the source's 3D area,
// normalized by the total area:
//
//  descriptor   E_d = sum_v A_v (1 - score_v(x_v))                     (thesis eq. 4.8 / 4.14)
//    The Gaussian matching score of matching_score.h: a squared descriptor distance inside a
//    robust (Welsch) kernel, windowed to 0 at the target's rim. Points outside the target pay
//    the maximum cost 1 instead of 0, so shrinking the overlap is never rewarded (§4.1.4), and
//    init (eq. 4.14) and refinement optimize the same quantity.
//  distortion   E_l = sum_t A_t (|J|^2 / (2 det J) - 1)                 (replaces eq. 4.10)
//    The conformal (MIPS) distortion of phi with respect to the source's own disk
//    parametrization, J = J_phi per source triangle. Chosen over the thesis' LSCM of
//    J_g^-1 J_phi J_f because (1) it depends on x only through the source triangles, so it is
//    smooth (the thesis' term jumps at every target edge, which broke its line search); (2) it
//    is zero for the rigid start and scale invariant, so it allows the isotropic scaling the
//    thesis wants but, unlike LSCM, does not reward shrinking; (3) it is well conditioned on
//    strongly distorted parametrizations (hands, feet) because each triangle is measured against
//    its own rest shape. Since f and g come from the same parametrization method on similar
//    geometry, a phi that is conformal in the plane keeps g^-1 o phi o f close to g^-1 o f.
//  area         E_a = sum_t A_t ((det J + 1 / det J) / 2 - 1)
//    The conformal term alone lets the scale vary freely from place to place, so the descriptor
//    term could conformally squeeze whole regions (e.g. the source's strip beyond the target's
//    rim, whose descriptors resemble the rim's) into the target at no cost. This term resists
//    scale change in both directions (~ (log det J)^2 / 2 near 1) and is +infinity at
//    inversion; a small weight still allows the feature size differences the thesis wants.
//  injectivity  E_f = sum_t A_t b(det J / s_f),  b(q) = -(q - 1)^2 log q for q < 1, else 0
//    A C2 version of the truncated log barrier of eq. 4.12: +infinity at inversion (so phi
//    stays locally injective), no effect while the area ratio stays above s_f.
//  anchor       E_p = sum_v A_v m_v |x_v - p_v|^2                      (not in the thesis)
//    A pull towards given positions p_v (MapAnchor): with a shared world frame, where the 3D
//    closest-point map puts each source vertex (docs/design.md §11). The descriptor term alone
//    can leave that start's basin (two eyes: start 6.5 -> optimized 37 eps x 100); the anchor keeps
//    the map near what proximity transfer gives and lets the descriptors refine it. m_v in [0, 1]
//    drops vertices the anchor does not know (their closest point on the target's rim). Weight 0
//    (the default) leaves the energy as it was.
//
// The Hessian model is per element, each projected to positive semi-definite (docs/design.md §2).
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

#include "map/matching_score.h"
#include "mesh/mesh.h"

namespace mcon {

struct MapEnergyWeights {
  double descriptor = 1.0;     // alpha_d
  double distortion = 0.15;    // alpha_l: conformal (angle) distortion
  double area = 0.15;          // alpha_a: area distortion
  double injectivity = 0.01;   // alpha_f
  double barrier_start = 0.5;  // s_f: area ratio det J_phi below which the barrier acts
  double anchor = 0.0;         // alpha_p: pull towards MapAnchor positions (0 = off)
};

// Where the anchor term pulls each source vertex: a position in the target disk's plane and a
// weight m_v in [0, 1] (0 = not anchored).
struct MapAnchor {
  std::vector<Vec2> position;
  std::vector<double> weight;
};

// The terms of the energy, in evaluation and summation order: the descriptor term (per source
// vertex) first, then the terms of the Jacobian J of phi on each source triangle, then the
// anchor (per source vertex; last so that the indices of the older terms stay). The table lives
// in map_energy.cpp; a new triangle term is one row there plus its weight in MapEnergyWeights.
using TriangleEnergy = double (*)(const Eigen::Matrix2d& J, const MapEnergyWeights& weights,
                                  Eigen::Vector4d* gradient, Eigen::Matrix4d* hessian);
enum class MapTermDomain { descriptor, triangle, anchor };
struct MapEnergyTerm {
  const char* name;
  double MapEnergyWeights::*weight;
  MapTermDomain domain;
  TriangleEnergy triangle_energy;  // nullptr unless domain == triangle
};
const std::vector<MapEnergyTerm>& map_energy_terms();
// Index of the term named `name` in map_energy_terms(); -1 if there is none.
int map_energy_term_index(const char* name);

struct MapEnergyTerms {
  std::vector<double> values;  // unweighted, one per map_energy_terms() entry
  double total = 0;            // weighted sum; +infinity if a triangle is inverted
  // The unweighted value of the term named `name` (a name from map_energy_terms()).
  double value(const char* name) const;
};

// The source disk as the energy sees it: rest triangles (the source's uv, mirrored for a
// reflected map with the triangles' corner order reversed, so every rest triangle is positive)
// and 3D area weights.
struct SourceDisk {
  int num_vertices = 0;
  std::vector<Tri> triangles;                 // corner order used for x (reversed if reflected)
  std::vector<Eigen::Matrix2d> rest_inverse;  // inverse of the rest edge matrix [e1 e2]
  std::vector<double> triangle_weight;        // A_t / A (3D areas)
  std::vector<double> vertex_weight;          // A_v / A (one third of incident triangles)
  bool reflected = false;
};

// Throws INVALID_ARGUMENT if uv has the wrong size or an inverted/degenerate triangle,
// NON_FINITE on NaN/inf.
SourceDisk make_source_disk(const TriMesh& mesh, const std::vector<Vec2>& uv, bool reflected);

// The rest positions (uv, or uv mirrored across the x axis for a reflected disk).
std::vector<Vec2> rest_positions(const std::vector<Vec2>& uv, bool reflected);

// Per-element energies of a 2x2 Jacobian as functions of vec(J) = (J00, J01, J10, J11).
// Return +infinity for det J <= 0; gradient and Hessian are written if non-null.
double conformal_distortion(const Eigen::Matrix2d& J, Eigen::Vector4d* gradient, Eigen::Matrix4d* hessian);
double area_distortion(const Eigen::Matrix2d& J, Eigen::Vector4d* gradient, Eigen::Matrix4d* hessian);
double injectivity_barrier(const Eigen::Matrix2d& J, double barrier_start, Eigen::Vector4d* gradient,
                           Eigen::Matrix4d* hessian);

// d vec(J) / d (x_a, y_a, x_b, y_b, x_c, y_c) for J = [x_b - x_a, x_c - x_a] * rest_inverse.
Eigen::Matrix<double, 4, 6> jacobian_map(const Eigen::Matrix2d& rest_inverse);

// Projects a symmetric matrix to the nearest positive semi-definite one (negative eigenvalues
// clamped to 0).
Eigen::Matrix4d project_psd(const Eigen::Matrix4d& h);
Eigen::Matrix2d project_psd(const Eigen::Matrix2d& h);

// J = U diag(s1, s2) V^T with U and V^T rotations (closed form; s2 < 0 if det J < 0).
void rotations_of_svd(const Eigen::Matrix2d& J, Eigen::Matrix2d& U, Eigen::Matrix2d& Vt);
// project_psd for the Hessian h (in vec(J)) of an isotropic energy at J, in closed form: false (h
// unchanged) if h is not block diagonal in J's twist / flip / scaling basis, i.e. not isotropic.
bool project_psd_isotropic(const Eigen::Matrix2d& J, Eigen::Matrix4d& h);
// An element Hessian's projection: h if positive definite, else project_psd_isotropic, else
// project_psd.
Eigen::Matrix4d project_psd_element(const Eigen::Matrix4d& h, const Eigen::Matrix2d& J);

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

class MapEnergy {
 public:
  // All references must outlive the energy. source_values: one row per source vertex, same
  // columns as the field. anchor: one position and weight per source vertex; needed (non-null)
  // when weights.anchor > 0, ignored otherwise.
  MapEnergy(const SourceDisk& source, const DescriptorField2D& target_field, const Eigen::MatrixXd& source_values,
            const ScoreSettings& score, const MapEnergyWeights& weights, const MapAnchor* anchor = nullptr);

  int num_variables() const { return 2 * source_->num_vertices; }
  const SourceDisk& source() const { return *source_; }

  MapEnergyTerms evaluate(const Eigen::VectorXd& x) const;

  struct Derivatives {
    MapEnergyTerms terms;
    Eigen::VectorXd gradient;
    std::vector<Matrix6d> triangle_hessians;       // PSD, weighted, in SourceDisk::triangles order
    std::vector<Eigen::Matrix2d> vertex_hessians;  // PSD, weighted descriptor blocks
  };
  // Requires x without inverted triangles.
  void derivatives(const Eigen::VectorXd& x, Derivatives& out) const;

 private:
  // The triangle rows of map_energy_terms(), resolved against the weights once per evaluation.
  struct TriangleTermSet {
    int descriptor = 0;               // index of the descriptor term
    int anchor = -1;                  // index of the anchor term
    std::vector<int> index;           // index of each triangle term in map_energy_terms()
    std::vector<TriangleEnergy> energy;
    std::vector<double> weight;
  };
  TriangleTermSet triangle_terms() const;
  double weighted_total(const std::vector<double>& values) const;
  // Source vertex v's matching score at its position in x, its lookup starting from (and then
  // updating) location_hint_[v]. scratch: 3 * dimension doubles.
  ScoreSample vertex_score(int v, const Eigen::VectorXd& x, bool derivatives, double* scratch) const;
  // The anchor term's value; its weighted gradient and PSD Hessian blocks are added if non-null.
  double anchor_energy(const Eigen::VectorXd& x, std::vector<Vec2>* gradient,
                       std::vector<Eigen::Matrix2d>* hessians) const;

  const SourceDisk* source_;
  const DescriptorField2D* field_;
  std::vector<double> values_;  // source descriptors, row-major n * d for contiguous access
  // Per source vertex, the target triangle where its last evaluation read the field: the start
  // of the next lookup's walk (iterates move little). Only a speed-up: lookups return the same
  // answer with or without it. Written by evaluate/derivatives, one slot per vertex, so one
  // MapEnergy must not be evaluated from two threads at once.
  mutable std::vector<int> location_hint_;
  ScoreSettings score_;
  MapEnergyWeights weights_;
  const MapAnchor* anchor_ = nullptr;  // null when weights_.anchor == 0
};

}  // namespace mcon
