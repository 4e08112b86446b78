// Plain-SVG figures for the evaluation commands (no plotting dependency: the SVG is written as
// text): a precision/recall curve over the result-set size n (thesis figure 3.6) and a 2D classical
// multidimensional-scaling picture of a distance matrix coloured by class (figures 3.4/3.5).
#pragma once

#include <string>
#include <vector>

namespace mcon::tools {

// Classical (Torgerson) MDS: B = -1/2 J D^2 J with J the centering matrix; the coordinates are the
// two leading eigenvectors scaled by sqrt(eigenvalue) (0 for a non-positive eigenvalue).
// `distances` is n x n row-major and should be symmetric. Returns n (x, y) pairs, x0 y0 x1 y1 ...
// Throws mcon::Error(INVALID_ARGUMENT) for a wrong size, NON_FINITE for non-finite distances.
std::vector<double> classical_mds_2d(const std::vector<double>& distances, std::size_t n);

// The share of the squared-distance "energy" the two MDS axes keep: (l1 + l2) / sum of positive
// eigenvalues (1 = the 2D picture is exact).
double classical_mds_2d_explained(const std::vector<double>& distances, std::size_t n);

struct PrecisionRecallPlot {
  std::string title;
  std::vector<double> precision;  // at n = 1..N
  std::vector<double> recall;
};

// Writes the SVG; throws mcon::Error(IO) if the file cannot be written.
void write_precision_recall_svg(const std::string& path, const PrecisionRecallPlot& plot);

struct ScatterPlot {
  std::string title;
  std::vector<double> xy;            // n points, x0 y0 x1 y1 ...
  std::vector<int> group;            // per point: index into groups (its colour)
  std::vector<std::string> groups;   // legend names
  std::vector<int> marker;           // per point: 0 circle, 1 square (empty: circles)
  std::vector<std::string> markers;  // legend names of the markers (empty: no marker legend)
};

void write_scatter_svg(const std::string& path, const ScatterPlot& plot);

}  // namespace mcon::tools
