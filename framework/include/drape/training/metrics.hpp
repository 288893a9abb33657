#pragma once
// The seed's evaluation metrics (Sec. 6.5.2, the columns of Tables 6.1-6.3) for
// one predicted garment x against the ground truth y on the same body:
//
//   ME   (cm)  mean over vertices of |x_i - y_i|                      (replaces L_V2V)
//   L_l  (cm)  eq. 6.12: sum over the 4 hierarchy levels k of the mean over
//              level-k vertices of |(L_k (x - y))_i|_1, L_k the random-walk
//              graph Laplacian of level k (x, y restricted to its vertices)
//   L_e  (%)   eq. 6.9: mean over edges of | |u_x - v_x| - |u_y - v_y| | / |u_y - v_y|
//   L_s  (m)   eq. 6.13: mean over the k coefficients j of |(V^T (x - y))_j|_1,
//              V the assets' k eigenvectors (so the value is comparable across k)
//   L_d        eq. 6.10-6.11: mean over faces of sum |F_x - F_y| (the six
//              entries), F = [x1-x0, x2-x0] [X1-X0, X2-X0]^-1 with X the
//              material-space (UV, metres) corners of the face
//   p    (%)   share of garment vertices strictly inside the body
//              (geometry::penetration_ratio, tolerance 0)
//
// The seed writes the sums of eqs. 6.10, 6.12 and 6.13 without saying how they
// are normalised; means per element make the values independent of the mesh
// resolution. They are the values of the loss plugins edge, laplacian,
// spectral_loss and deformation with their default `reduction: mean`
// (docs/losses.md). Everything is computed in double.
#include <drape/assets/assets.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace drape {

struct GarmentMetrics {
  double me_cm = 0;         // ME
  double laplacian_cm = 0;  // L_l
  double edge_percent = 0;  // L_e
  double spectral = 0;      // L_s (m)
  double deformation = 0;   // L_d
  double penetration_percent = 0;  // p
  // Not the seed's: garment edges through body triangles plus body edges
  // through garment triangles (geometry::surface_crossings), which p misses
  // where no vertex is inside; and 100 when there is any, else 0 (its mean over
  // samples is the share of samples with a crossing).
  double crossings = 0;
  double crossed_percent = 0;
  // Not the seed's: the most stretched edge against the ground truth,
  // 100 (l_pred / l_true - 1), so that a torn prediction (an edge pulled
  // across the body) shows even where the mean edge error L_e is small.
  double edge_stretch_max = 0;
  // Not the seed's: the most strained edge against the material space (the
  // garment's UVs), 100 (l / l_rest - 1): a torn mesh in the cloth's own
  // terms. drape eval measures it against the garment each body wore (a
  // size: auto dataset's sizes, services/worn_garments.hpp), not the
  // template's design size, whose edges a 5xlarge shirt's exceed by 80-130 %. edge_stretch_max above is relative to the simulated edge, which
  // a fold may have compressed to a millimetre, so it can be large where the
  // cloth is not strained at all; the simulated drape itself has this one too.
  double strain_max = 0;
};

// Names, units and values in table order: {"ME", "cm"}, {"L_l", "cm"}, {"L_e", "%"},
// {"L_s", "m"}, {"L_d", ""}, {"p", "%"}, then {"crossings", "edges"}, {"crossed_samples", "%"},
// {"edge_stretch_max", "%"}, {"strain_max", "%"}.
struct MetricColumn {
  std::string name, unit;
  double GarmentMetrics::*field;
};
const std::vector<MetricColumn>& metric_columns();

// The material-space length of each face's three edges of `mesh` (from its
// UVs; an edge on a UV seam once per side), face by face: the rest lengths
// strain_max measures against. For a garment of the template's topology
// graded to another size (its pattern, or its material space, graded: the
// garment a body of a size: auto dataset wore). ConfigError without UVs.
std::vector<double> face_edge_rest_lengths(const Mesh& mesh);

// What the metrics need of a garment template, precomputed once.
class MetricsContext {
 public:
  // The garment (level 0 of the hierarchy, material space from its UVs), the
  // hierarchy levels, the eigenvectors and the body faces, all from `assets`.
  // Throws ConfigError when the garment has no UVs or a face has a degenerate
  // material-space triangle.
  explicit MetricsContext(const Assets& assets);

  int garment_vertices() const { return garment_vertices_; }
  int body_vertices() const { return body_vertices_; }

  // Every metric of one sample. x, y: [garment vertices, 3]; body: [body
  // vertices, 3] in the assets' body topology. Throws Error on a size mismatch
  // or a non-finite input. rest (optional): the rest lengths of the garment
  // the body wore (face_edge_rest_lengths of the template graded to its
  // size), which strain_max measures against; the template's when null.
  GarmentMetrics evaluate(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y, const Eigen::MatrixX3d& body,
                          const std::vector<double>* rest = nullptr) const;

  // The parts, for tests and for callers that need only some.
  // ME needs no assets: the loss vertex_distance calls it too, so the two agree by construction.
  static double mean_error(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y);        // m
  double laplacian_difference(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const;  // m
  double edge_error(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const;          // fraction
  // L_e and the most stretched edge (both fractions) in one pass over the edges.
  struct EdgeErrors {
    double mean_relative = 0, max_stretch = 0;
  };
  EdgeErrors edge_errors(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const;
  double spectral_difference(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const;   // m
  double deformation_difference(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y) const;
  double penetration(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body) const;      // fraction
  int crossings(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body) const;           // edges
  // Fraction, against the material space: the template's, or `rest` (as evaluate's).
  double strain_max(const Eigen::MatrixX3d& x, const std::vector<double>* rest = nullptr) const;

 private:
  void check(const Eigen::MatrixX3d& m, int rows, const char* what) const;

  int garment_vertices_ = 0, body_vertices_ = 0;
  Eigen::MatrixX3i faces_;
  std::vector<Eigen::Matrix2d> material_inverse_;  // per face: [X1-X0, X2-X0]^-1
  std::vector<std::array<int, 2>> edges_;
  // Every face's three edges and their material-space lengths (an edge on a
  // UV seam appears once per side, each with its own rest length).
  std::vector<std::array<int, 2>> face_edges_;
  std::vector<double> rest_lengths_;
  struct Level {
    Eigen::VectorXi fine_index;  // level vertex -> garment vertex
    Eigen::SparseMatrix<double, Eigen::RowMajor> laplacian;
  };
  std::vector<Level> levels_;
  Eigen::MatrixXd eigenvectors_;  // [garment vertices, k]
  Eigen::MatrixX3i body_faces_;
};

// Mean, standard deviation and largest value of each metric over samples
// (the largest: the worst body, e.g. the highest p).
struct MetricsSummary {
  std::size_t samples = 0;
  GarmentMetrics mean, stddev, max;
};
MetricsSummary summarize(const std::vector<GarmentMetrics>& samples);

}  // namespace drape
