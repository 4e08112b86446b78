#include "common/svg_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "base/error.h"

namespace mcon::tools {
namespace {

// Colours that stay apart for up to 10 classes (Tableau 10).
const char* const kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  require(static_cast<bool>(f), MCON_ERROR_IO, "cannot write '" + path + "'");
  f << text;
  f.close();
  require(static_cast<bool>(f), MCON_ERROR_IO, "cannot write '" + path + "'");
}

std::string svg_header(int width, int height) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
         std::to_string(height) + "\" viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
         "\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
}

std::string text(double x, double y, const std::string& s, int size, const char* anchor = "start",
                 const char* extra = "") {
  return "<text x=\"" + fmt(x) + "\" y=\"" + fmt(y) + "\" font-size=\"" + std::to_string(size) +
         "\" text-anchor=\"" + anchor + "\" " + extra + ">" + escape(s) + "</text>\n";
}

Eigen::MatrixXd centered_gram(const std::vector<double>& distances, std::size_t n) {
  require(n >= 1 && distances.size() == n * n, MCON_ERROR_INVALID_ARGUMENT, "MDS: need an n x n distance matrix");
  for (const double d : distances) require(std::isfinite(d), MCON_ERROR_NON_FINITE, "MDS: a distance is not finite");
  const Eigen::Index m = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd d2(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) {
      const double d = 0.5 * (distances[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)] +
                              distances[static_cast<std::size_t>(j) * n + static_cast<std::size_t>(i)]);
      d2(i, j) = d * d;
    }
  const Eigen::VectorXd row_mean = d2.rowwise().mean();
  const double all_mean = row_mean.mean();
  Eigen::MatrixXd b(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) b(i, j) = -0.5 * (d2(i, j) - row_mean(i) - row_mean(j) + all_mean);
  return b;
}

}  // namespace

std::vector<double> classical_mds_2d(const std::vector<double>& distances, std::size_t n) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(centered_gram(distances, n));
  require(es.info() == Eigen::Success, MCON_ERROR_NUMERICAL, "MDS: eigen decomposition failed");
  const Eigen::Index m = static_cast<Eigen::Index>(n);
  std::vector<double> xy(2 * n, 0.0);
  for (int axis = 0; axis < 2 && axis < m; ++axis) {
    const Eigen::Index c = m - 1 - axis;  // eigenvalues ascend
    const double lambda = es.eigenvalues()(c);
    if (!(lambda > 0)) continue;
    Eigen::VectorXd v = es.eigenvectors().col(c);
    // Fix the sign (an eigenvector's sign is arbitrary): largest-magnitude entry positive.
    Eigen::Index big = 0;
    v.cwiseAbs().maxCoeff(&big);
    if (v(big) < 0) v = -v;
    for (Eigen::Index i = 0; i < m; ++i) xy[2 * static_cast<std::size_t>(i) + static_cast<std::size_t>(axis)] = v(i) * std::sqrt(lambda);
  }
  return xy;
}

double classical_mds_2d_explained(const std::vector<double>& distances, std::size_t n) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(centered_gram(distances, n), Eigen::EigenvaluesOnly);
  double positive = 0, top = 0;
  const Eigen::Index m = es.eigenvalues().size();
  for (Eigen::Index i = 0; i < m; ++i) positive += std::max(0.0, es.eigenvalues()(i));
  for (Eigen::Index i = std::max<Eigen::Index>(0, m - 2); i < m; ++i) top += std::max(0.0, es.eigenvalues()(i));
  return positive > 0 ? top / positive : 0.0;
}

void write_precision_recall_svg(const std::string& path, const PrecisionRecallPlot& plot) {
  require(!plot.precision.empty() && plot.precision.size() == plot.recall.size(), MCON_ERROR_INVALID_ARGUMENT,
          "precision/recall plot: need as many recall as precision values");
  const int W = 640, H = 440, left = 70, right = 30, top = 50, bottom = 60;
  const double pw = W - left - right, ph = H - top - bottom;
  const std::size_t count = plot.precision.size();
  const auto X = [&](double n) { return left + (count > 1 ? (n - 1) / static_cast<double>(count - 1) : 0.5) * pw; };
  const auto Y = [&](double v) { return top + (1.0 - std::clamp(v, 0.0, 1.0)) * ph; };
  std::ostringstream s;
  s << svg_header(W, H);
  s << text(W / 2.0, 28, plot.title, 16, "middle", "font-weight=\"bold\"");
  // Grid and axes.
  for (int i = 0; i <= 10; ++i) {
    const double v = i / 10.0;
    s << "<line x1=\"" << left << "\" y1=\"" << fmt(Y(v)) << "\" x2=\"" << W - right << "\" y2=\"" << fmt(Y(v))
      << "\" stroke=\"#e0e0e0\"/>\n";
    s << text(left - 8, Y(v) + 4, fmt(v).substr(0, 3), 12, "end");
  }
  for (std::size_t n = 1; n <= count; ++n) {
    s << "<line x1=\"" << fmt(X(static_cast<double>(n))) << "\" y1=\"" << top + ph << "\" x2=\""
      << fmt(X(static_cast<double>(n))) << "\" y2=\"" << top + ph + 5 << "\" stroke=\"black\"/>\n";
    s << text(X(static_cast<double>(n)), top + ph + 20, std::to_string(n), 12, "middle");
  }
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"black\"/>\n";
  s << text(left + pw / 2, H - 15, "number of retrieved patches n", 13, "middle");
  s << text(18, top + ph / 2, "ratio", 13, "middle",
            ("transform=\"rotate(-90 18 " + fmt(top + ph / 2) + ")\"").c_str());
  const auto curve = [&](const std::vector<double>& v, const char* colour) {
    s << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2.5\" points=\"";
    for (std::size_t i = 0; i < v.size(); ++i) s << fmt(X(static_cast<double>(i + 1))) << "," << fmt(Y(v[i])) << " ";
    s << "\"/>\n";
    for (std::size_t i = 0; i < v.size(); ++i)
      s << "<circle cx=\"" << fmt(X(static_cast<double>(i + 1))) << "\" cy=\"" << fmt(Y(v[i])) << "\" r=\"4\" fill=\""
        << colour << "\"/>\n";
  };
  // Legend at the right end, in a band that neither curve crosses over the last few n (the curves
  // are drawn first, the legend box on top of them).
  const double candidates[][2] = {{0.62, 0.47}, {0.22, 0.07}, {0.88, 0.73}, {0.45, 0.30}};
  double band_top = candidates[0][0];
  for (const auto& c : candidates) {
    bool free = true;
    for (std::size_t i = count * 6 / 10; i < count; ++i)
      for (const double v : {plot.precision[i], plot.recall[i]}) free = free && (v > c[0] + 0.02 || v < c[1] - 0.02);
    if (free) {
      band_top = c[0];
      break;
    }
  }
  curve(plot.precision, "#4e79a7");
  curve(plot.recall, "#e15759");
  const double lx = left + pw - 160, ly = Y(band_top);
  s << "<rect x=\"" << fmt(lx) << "\" y=\"" << fmt(ly) << "\" width=\"150\" height=\"52\" "
    << "fill=\"white\" stroke=\"#999\"/>\n";
  const auto legend = [&](const char* colour, const char* name, double y) {
    s << "<line x1=\"" << fmt(lx + 10) << "\" y1=\"" << fmt(y) << "\" x2=\"" << fmt(lx + 38) << "\" y2=\"" << fmt(y)
      << "\" stroke=\"" << colour << "\" stroke-width=\"2.5\"/>\n";
    s << text(lx + 46, y + 4, name, 13);
  };
  legend("#4e79a7", "precision", ly + 16);
  legend("#e15759", "recall", ly + 38);
  s << "</svg>\n";
  write_text_file(path, s.str());
}

void write_scatter_svg(const std::string& path, const ScatterPlot& plot) {
  const std::size_t n = plot.xy.size() / 2;
  require(plot.xy.size() == 2 * n && plot.group.size() == n && (plot.marker.empty() || plot.marker.size() == n),
          MCON_ERROR_INVALID_ARGUMENT, "scatter plot: one group (and marker) per point");
  for (const int g : plot.group)
    require(g >= 0 && g < static_cast<int>(plot.groups.size()), MCON_ERROR_INVALID_ARGUMENT,
            "scatter plot: group index out of range");
  const int W = 760, H = 600, left = 30, top = 50, bottom = 40, legend_w = 170;
  const double pw = W - left - legend_w - 20, ph = H - top - bottom;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (n > 0) {
    x0 = x1 = plot.xy[0];
    y0 = y1 = plot.xy[1];
    for (std::size_t i = 0; i < n; ++i) {
      x0 = std::min(x0, plot.xy[2 * i]);
      x1 = std::max(x1, plot.xy[2 * i]);
      y0 = std::min(y0, plot.xy[2 * i + 1]);
      y1 = std::max(y1, plot.xy[2 * i + 1]);
    }
  }
  // One scale for both axes (MDS distances mean the same in x and y), centered, 5% margin.
  const double span = std::max({x1 - x0, y1 - y0, 1e-12}) * 1.1;
  const double scale = std::min(pw, ph) / span;
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const auto X = [&](double x) { return left + pw / 2 + (x - cx) * scale; };
  const auto Y = [&](double y) { return top + ph / 2 - (y - cy) * scale; };
  std::ostringstream s;
  s << svg_header(W, H);
  s << text(W / 2.0, 28, plot.title, 15, "middle", "font-weight=\"bold\"");
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"#999\"/>\n";
  const auto mark = [&](double x, double y, int g, int m) {
    const char* colour = kPalette[static_cast<std::size_t>(g) % 10];
    if (m == 1)
      s << "<rect x=\"" << fmt(x - 4.5) << "\" y=\"" << fmt(y - 4.5) << "\" width=\"9\" height=\"9\" fill=\"" << colour
        << "\" fill-opacity=\"0.85\" stroke=\"black\" stroke-width=\"0.6\"/>\n";
    else
      s << "<circle cx=\"" << fmt(x) << "\" cy=\"" << fmt(y) << "\" r=\"5\" fill=\"" << colour
        << "\" fill-opacity=\"0.85\" stroke=\"black\" stroke-width=\"0.6\"/>\n";
  };
  for (std::size_t i = 0; i < n; ++i)
    mark(X(plot.xy[2 * i]), Y(plot.xy[2 * i + 1]), plot.group[i], plot.marker.empty() ? 0 : plot.marker[i]);
  // Legend: classes (colours), then markers (shapes).
  const double lx = W - legend_w;
  double ly = top + 10;
  s << text(lx, ly, "class", 13, "start", "font-weight=\"bold\"");
  for (std::size_t g = 0; g < plot.groups.size(); ++g) {
    ly += 22;
    mark(lx + 8, ly - 4, static_cast<int>(g), 0);
    s << text(lx + 22, ly, plot.groups[g], 13);
  }
  if (!plot.markers.empty()) {
    ly += 34;
    s << text(lx, ly, "model", 13, "start", "font-weight=\"bold\"");
    for (std::size_t m = 0; m < plot.markers.size(); ++m) {
      ly += 22;
      s << (m == 1 ? "<rect x=\"" + fmt(lx + 3.5) + "\" y=\"" + fmt(ly - 8.5) +
                         "\" width=\"9\" height=\"9\" fill=\"#ccc\" stroke=\"black\" stroke-width=\"0.6\"/>\n"
                   : "<circle cx=\"" + fmt(lx + 8) + "\" cy=\"" + fmt(ly - 4) +
                         "\" r=\"5\" fill=\"#ccc\" stroke=\"black\" stroke-width=\"0.6\"/>\n");
      s << text(lx + 22, ly, plot.markers[m], 13);
    }
  }
  s << "</svg>\n";
  write_text_file(path, s.str());
}

}  // namespace mcon::tools
