// The seed's evaluation metrics (see metrics.hpp for the definitions).
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/laplacian.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/training/metrics.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace drape {

const std::vector<MetricColumn>& metric_columns() {
  static const std::vector<MetricColumn> columns{
      {"ME", "cm", &GarmentMetrics::me_cm},           {"L_l", "cm", &GarmentMetrics::laplacian_cm},
      {"L_e", "%", &GarmentMetrics::edge_percent},    {"L_s", "m", &GarmentMetrics::spectral},
      {"L_d", "", &GarmentMetrics::deformation},      {"p", "%", &GarmentMetrics::penetration_percent},
      {"crossings", "edges", &GarmentMetrics::crossings}, {"crossed_samples", "%", &GarmentMetrics::crossed_percent},
      {"edge_stretch_max", "%", &GarmentMetrics::edge_stretch_max}, {"strain_max", "%", &GarmentMetrics::strain_max}};
  return columns;
}

MetricsContext::MetricsContext(const Assets& assets) {
  if (!assets.garment) throw ConfigError("metrics need a garment template, but the assets have none");
  const Mesh& mesh = assets.garment->mesh;
  if (!mesh.has_uv()) throw ConfigError("metrics need the garment's material space (UVs), but the template has none");
  garment_vertices_ = mesh.num_vertices();
  body_vertices_ = assets.body.num_vertices();
  faces_ = mesh.faces;
  body_faces_ = assets.body.faces;

  material_inverse_.resize(static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Eigen::Matrix2d X;
    X.col(0) = (mesh.uv.row(mesh.uv_faces(f, 1)) - mesh.uv.row(mesh.uv_faces(f, 0))).transpose();
    X.col(1) = (mesh.uv.row(mesh.uv_faces(f, 2)) - mesh.uv.row(mesh.uv_faces(f, 0))).transpose();
    const double det = X.determinant();
    if (!(std::abs(det) > 1e-16))
      throw ConfigError("garment face " + std::to_string(f) + " has a degenerate material-space triangle (area " +
                        std::to_string(det / 2) + " m^2)");
    material_inverse_[static_cast<std::size_t>(f)] = X.inverse();
    for (int j = 0; j < 3; ++j) face_edges_.push_back({mesh.faces(f, j), mesh.faces(f, (j + 1) % 3)});
  }
  rest_lengths_ = face_edge_rest_lengths(mesh);

  edges_ = geometry::edge_list(mesh.faces);

  // Level 0 is the garment itself even when no hierarchy was built.
  const auto& levels = assets.hierarchy.levels;
  if (levels.empty()) {
    levels_.push_back({Eigen::VectorXi::LinSpaced(garment_vertices_, 0, garment_vertices_ - 1),
                       geometry::graph_laplacian(faces_, garment_vertices_)});
  }
  for (const auto& level : levels) {
    if (level.fine_index.size() != level.mesh.num_vertices())
      throw ConfigError("hierarchy level with " + std::to_string(level.mesh.num_vertices()) + " vertices has " +
                        std::to_string(level.fine_index.size()) + " fine indices");
    levels_.push_back({level.fine_index, geometry::graph_laplacian(level.mesh.faces, level.mesh.num_vertices())});
  }
  eigenvectors_ = assets.eigenvectors.cast<double>();
  if (eigenvectors_.size() && eigenvectors_.rows() != garment_vertices_)
    throw ConfigError("the eigenvectors have " + std::to_string(eigenvectors_.rows()) + " rows, the garment " +
                      std::to_string(garment_vertices_) + " vertices");
}

void MetricsContext::check(const Eigen::MatrixX3d& m, int rows, const char* what) const {
  if (m.rows() != rows)
    throw Error(std::string("metrics: ") + what + " has " + std::to_string(m.rows()) + " vertices, expected " +
                std::to_string(rows));
  if (!m.allFinite()) throw Error(std::string("metrics: ") + what + " has a non-finite coordinate");
}

double MetricsContext::mean_error(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) {
  return (x - y).rowwise().norm().mean();
}

double MetricsContext::laplacian_difference(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const {
  const Eigen::MatrixX3d d = x - y;
  double sum = 0.0;
  for (const Level& level : levels_) {
    Eigen::MatrixX3d dk(level.fine_index.size(), 3);
    for (Eigen::Index i = 0; i < level.fine_index.size(); ++i) dk.row(i) = d.row(level.fine_index[i]);
    const Eigen::MatrixX3d ld = level.laplacian * dk;
    sum += ld.cwiseAbs().rowwise().sum().mean();
  }
  return sum;
}

std::vector<double> face_edge_rest_lengths(const Mesh& mesh) {
  if (!mesh.has_uv()) throw ConfigError("the garment's rest lengths need its material space (UVs), but it has none");
  std::vector<double> lengths;
  lengths.reserve(3 * static_cast<std::size_t>(mesh.num_faces()));
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int j = 0; j < 3; ++j)
      lengths.push_back((mesh.uv.row(mesh.uv_faces(f, (j + 1) % 3)) - mesh.uv.row(mesh.uv_faces(f, j))).norm());
  return lengths;
}

double MetricsContext::strain_max(const Eigen::MatrixX3d& x, const std::vector<double>* rest) const {
  const std::vector<double>& lengths = rest ? *rest : rest_lengths_;
  if (lengths.size() != rest_lengths_.size())
    throw Error("strain_max: " + std::to_string(lengths.size()) + " rest lengths for a garment of " +
                std::to_string(rest_lengths_.size()) + " face edges");
  double worst = -1.0;  // an edge can only shrink to zero length
  for (std::size_t e = 0; e < face_edges_.size(); ++e)
    worst = std::max(worst, (x.row(face_edges_[e][0]) - x.row(face_edges_[e][1])).norm() / lengths[e] - 1.0);
  return worst;
}

MetricsContext::EdgeErrors MetricsContext::edge_errors(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const {
  EdgeErrors out;
  if (edges_.empty()) return out;
  for (const auto& [u, v] : edges_) {
    // A ground-truth edge of length zero has no relative error; the loss plugin clamps alike.
    const double lx = (x.row(u) - x.row(v)).norm(), ly = (y.row(u) - y.row(v)).norm(), denominator = std::max(ly, 1e-12);
    out.mean_relative += std::abs(lx - ly) / denominator;
    out.max_stretch = std::max(out.max_stretch, lx / denominator - 1.0);
  }
  out.mean_relative /= double(edges_.size());
  return out;
}

double MetricsContext::edge_error(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const {
  return edge_errors(x, y).mean_relative;
}

double MetricsContext::spectral_difference(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const {
  if (eigenvectors_.cols() == 0) return 0.0;
  const Eigen::MatrixXd c = eigenvectors_.transpose() * (x - y);  // [k, 3]
  return c.cwiseAbs().rowwise().sum().mean();
}

double MetricsContext::deformation_difference(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const {
  if (faces_.rows() == 0) return 0.0;
  // F_x - F_y = [d1-d0, d2-d0] X^-1 with d = x - y: one product per face.
  const Eigen::MatrixX3d d = x - y;
  double sum = 0.0;
  for (int f = 0; f < faces_.rows(); ++f) {
    Eigen::Matrix<double, 3, 2> dx;
    dx.col(0) = (d.row(faces_(f, 1)) - d.row(faces_(f, 0))).transpose();
    dx.col(1) = (d.row(faces_(f, 2)) - d.row(faces_(f, 0))).transpose();
    sum += (dx * material_inverse_[static_cast<std::size_t>(f)]).cwiseAbs().sum();
  }
  return sum / double(faces_.rows());
}

double MetricsContext::penetration(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body) const {
  const geometry::BodySurface surface(body, body_faces_);
  return geometry::penetration_ratio(surface, x);
}

int MetricsContext::crossings(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body) const {
  return geometry::surface_crossings(x, faces_, body, body_faces_).total();
}

GarmentMetrics MetricsContext::evaluate(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y,
                                        const Eigen::MatrixX3d& body, const std::vector<double>* rest) const {
  check(x, garment_vertices_, "the prediction");
  check(y, garment_vertices_, "the ground truth");
  check(body, body_vertices_, "the body");
  GarmentMetrics m;
  m.me_cm = 100.0 * mean_error(x, y);
  m.laplacian_cm = 100.0 * laplacian_difference(x, y);
  const EdgeErrors edges = edge_errors(x, y);
  m.edge_percent = 100.0 * edges.mean_relative;
  m.spectral = spectral_difference(x, y);
  m.deformation = deformation_difference(x, y);
  m.penetration_percent = 100.0 * penetration(x, body);
  m.crossings = crossings(x, body);
  m.crossed_percent = m.crossings > 0 ? 100.0 : 0.0;
  m.edge_stretch_max = 100.0 * edges.max_stretch;
  m.strain_max = 100.0 * strain_max(x, rest);
  return m;
}

MetricsSummary summarize(const std::vector<GarmentMetrics>& samples) {
  MetricsSummary s;
  s.samples = samples.size();
  if (samples.empty()) return s;
  for (const auto& column : metric_columns()) {
    double sum = 0.0, largest = samples.front().*column.field;
    for (const auto& m : samples) {
      sum += m.*column.field;
      largest = std::max(largest, m.*column.field);
    }
    const double mean = sum / double(samples.size());
    double var = 0.0;
    for (const auto& m : samples) var += (m.*column.field - mean) * (m.*column.field - mean);
    s.mean.*column.field = mean;
    s.max.*column.field = largest;
    s.stddev.*column.field = samples.size() > 1 ? std::sqrt(var / double(samples.size() - 1)) : 0.0;
  }
  return s;
}

}  // namespace drape
