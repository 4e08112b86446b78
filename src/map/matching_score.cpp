#include "map/matching_score.h"

#include <algorithm>
#include <cmath>

namespace mcon {

void rim_window(double radius, double band, double& w, double& dw, double& d2w) {
  const double t = (1.0 - radius) / band;
  w = rim_window_value(radius, band);
  if (t >= 1 || t <= 0) {
    dw = d2w = 0;
  } else {
    dw = -(6 * t - 6 * t * t) / band;  // dt/dr = -1 / band
    d2w = (6 - 12 * t) / (band * band);
  }
}

ScoreSample match_score(const DescriptorField2D& field, const double* source_value, const Vec2& x,
                        const ScoreSettings& settings, bool derivatives, double* scratch,
                        const PointLocation* known_location, int location_hint) {
  ScoreSample out;
  const int d = field.dimension();
  double* value = scratch;
  double* gx = scratch + d;
  double* gy = scratch + 2 * d;
  const double r = x.norm();
  double w = 1, dw = 0, d2w = 0;
  // Where the field is read: x itself, or for the rim extension the nearest rim point x / |x|.
  Vec2 p = x;
  const bool beyond = settings.outside == OutsideRule::nearest_rim && r > 1;
  if (settings.outside == OutsideRule::zero) {
    rim_window(r, settings.band, w, dw, d2w);
    if (w <= 0) {
      out.inside = field.locate(x, 0.0, location_hint).triangle >= 0;
      return out;
    }
  } else if (beyond) {
    p = x / r;
  }
  // Points between the boundary polygon and the unit circle read the nearest triangle.
  const PointLocation loc =
      known_location && known_location->triangle >= 0 ? *known_location : field.locate(p, 2.0, location_hint);
  out.location = loc;
  if (loc.triangle < 0) return out;
  field.evaluate_at(loc, value, gx, gy);
  out.inside = !beyond && loc.distance == 0;
  double r2 = 0;
  Vec2 Jr = Vec2::Zero();                        // G^T r
  Eigen::Matrix2d JJ = Eigen::Matrix2d::Zero();  // G^T G
  for (int k = 0; k < d; ++k) {
    const double rk = value[k] - source_value[k];
    r2 += rk * rk;
    if (derivatives) {
      Jr += rk * Vec2(gx[k], gy[k]);
      JJ(0, 0) += gx[k] * gx[k];
      JJ(0, 1) += gx[k] * gy[k];
      JJ(1, 1) += gy[k] * gy[k];
    }
  }
  const double inv_s2 = 1.0 / (settings.sigma * settings.sigma);
  const double g = std::exp(-0.5 * r2 * inv_s2);
  out.score = w * g;
  if (!derivatives) return out;
  JJ(1, 0) = JJ(0, 1);
  if (beyond) {
    // Chain rule through p = x / |x|: dp/dx = (I - p p^T) / |x| (its curvature is left out:
    // a Gauss-Newton model beyond the rim).
    const Eigen::Matrix2d P = (Eigen::Matrix2d::Identity() - p * p.transpose()) / r;
    Jr = P * Jr;
    JJ = P * JJ * P;
  }
  // Gaussian part: dg = g q, d2g = g (q q^T - G^T G / sigma^2), q = -G^T r / sigma^2
  const Vec2 q = -inv_s2 * Jr;
  const Eigen::Matrix2d hg = g * (q * q.transpose() - inv_s2 * JJ);
  const Vec2 dg = g * q;
  // Window part: w(|x|); gradient dw * xhat, Hessian d2w xhat xhat^T + dw / |x| (I - xhat xhat^T)
  Vec2 dW = Vec2::Zero();
  Eigen::Matrix2d hW = Eigen::Matrix2d::Zero();
  if (dw != 0 || d2w != 0) {
    const Vec2 xh = x / r;
    dW = dw * xh;
    hW = d2w * xh * xh.transpose() + (dw / r) * (Eigen::Matrix2d::Identity() - xh * xh.transpose());
  }
  out.gradient = w * dg + g * dW;
  out.hessian = w * hg + dW * dg.transpose() + dg * dW.transpose() + g * hW;
  return out;
}

double descriptor_sigma(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) {
  const double n = static_cast<double>(source.rows() + target.rows());
  if (n == 0 || source.cols() == 0) return 1.0;
  const Eigen::RowVectorXd mean = (source.colwise().sum() + target.colwise().sum()) / n;
  const double ss = (source.rowwise() - mean).squaredNorm() + (target.rowwise() - mean).squaredNorm();
  const double sigma = std::sqrt(ss / n);
  const double scale = std::max(mean.cwiseAbs().maxCoeff(), 1.0);
  return std::max(sigma, 1e-9 * scale);
}

}  // namespace mcon
