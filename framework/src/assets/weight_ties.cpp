#include <drape/assets/weight_ties.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape {
namespace {

std::string correspondences_differ(const Assets& from, const Assets& to) {
  std::ostringstream o;
  if (from.correspondence_rows() != to.correspondence_rows()) {
    o << "the correspondences index " << from.correspondence_rows() << " body points there and "
      << to.correspondence_rows() << " here";
    return o.str();
  }
  if (from.correspondence.size() != to.correspondence.size()) return "";  // another garment: the shapes say so
  std::size_t changed = 0;
  for (std::size_t g = 0; g < from.correspondence.size(); ++g) changed += from.correspondence[g] != to.correspondence[g];
  if (changed == 0) return "";
  o << changed << " of " << from.correspondence.size() << " garment vertices read another body point";
  return o.str();
}

std::string hierarchy_differs(const Assets& from, const Assets& to) {
  const auto& a = from.hierarchy.levels;
  const auto& b = to.hierarchy.levels;
  if (a.size() != b.size()) {
    std::ostringstream o;
    o << "the hierarchy has " << a.size() << " levels there and " << b.size() << " here";
    return o.str();
  }
  std::vector<std::string> levels;
  for (std::size_t l = 1; l < a.size(); ++l)
    if (a[l].mesh.num_vertices() != b[l].mesh.num_vertices() || a[l].mesh.faces != b[l].mesh.faces)
      levels.push_back(std::to_string(l));
  if (levels.empty()) return "";
  std::string out = "the hierarchy's level";
  out += levels.size() > 1 ? "s " : " ";
  for (std::size_t i = 0; i < levels.size(); ++i) out += (i ? ", " : "") + levels[i];
  return out + (levels.size() > 1 ? " cluster" : " clusters") + " the garment otherwise";
}

std::string eigenvectors_differ(const Assets& from, const Assets& to) {
  const MatrixRM& a = from.eigenvectors;
  const MatrixRM& b = to.eigenvectors;
  if (a.rows() != b.rows() || a.rows() == 0) return "";
  const Eigen::Index k = std::min(a.cols(), b.cols());
  int changed = 0;
  Eigen::Index first = -1;
  // |cos| of each pair of columns, in double: three column sums.
  const Eigen::MatrixXd da = a.leftCols(k).cast<double>(), db = b.leftCols(k).cast<double>();
  const Eigen::ArrayXd dots = (da.array() * db.array()).colwise().sum().transpose();
  const Eigen::ArrayXd norms = (da.colwise().norm().array() * db.colwise().norm().array()).transpose();
  for (Eigen::Index i = 0; i < k; ++i) {
    const double c = norms[i] > 0 ? std::abs(dots[i]) / norms[i] : 0.0;
    if (!(c >= kSameEigenvector)) {
      ++changed;
      if (first < 0) first = i;
    }
  }
  if (changed == 0) return "";
  std::ostringstream o;
  o << changed << " of " << k << " eigenvectors are others (|cos| below " << kSameEigenvector << ", the first at "
    << first << "): the spectral branch's coefficients there mean other shapes here";
  return o.str();
}

}  // namespace

std::vector<std::string> weight_ties_differ(const Assets& from, const Assets& to) {
  std::vector<std::string> out;
  for (std::string s : {correspondences_differ(from, to), hierarchy_differs(from, to), eigenvectors_differ(from, to)})
    if (!s.empty()) out.push_back(std::move(s));
  return out;
}

}  // namespace drape
