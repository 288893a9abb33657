#pragma once
// Precomputed data of one garment template that nodes ask for: the garment
// dressed on the mean body (rest and start state, material space, materials),
// the mean body, the fixed body->garment correspondences, the 4-level hierarchy
// with its UV-space up-sampling and graph Laplacians, and the spectral basis.
// build_assets() computes all of it once and caches it in HDF5, keyed by a hash
// of the template and the settings (docs/formats.md, "Assets cache").
#include <drape/energy.hpp>
#include <drape/geometry/body_resampling.hpp>
#include <drape/geometry/hierarchy.hpp>
#include <drape/tensor.hpp>

#include <Eigen/SparseCore>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drape {

class Registry;

class Assets {
 public:
  std::shared_ptr<const Garment> garment;  // dressed on the mean body
  Mesh body;                               // the mean body (topology of every input body)
  std::vector<int> correspondence;         // [garment vertices] -> body vertex
  geometry::Hierarchy hierarchy;           // levels[0] is the garment
  // Random-walk graph Laplacian I - D^-1 A of each hierarchy level (eq. 6.12), float for the losses.
  std::vector<Eigen::SparseMatrix<float, Eigen::RowMajor>> laplacians;
  Eigen::VectorXd eigenvalues;             // [k] ascending
  MatrixRM eigenvectors;                   // [garment vertices, k] orthonormal columns
  // Posing (docs/poses.md), when the body model has a skeleton: its pose
  // angles in the order of the graph input `pose`, and the garment's
  // skinning weights [garment vertices, joints] from the mean body's
  // (garment_skinning.hpp), for the skin node. Empty otherwise. Recomputed
  // at every build (tens of milliseconds), not cached.
  std::vector<std::string> pose_angles;
  Eigen::MatrixXf garment_skinning;
  // The encoder's body (AssetsSpec::encoder_body; docs/bodies.md, "One
  // encoder for both rigs"), when the spec names one: each vertex of that body
  // model's mean body attached to its closest point on `body` (a face of
  // `body` and barycentric weights; its resampled_template is `body` read at
  // those points [Ne, 3]).
  // The `resample_body` node carries every input body onto these points, and
  // `correspondence` then indexes them. The correspondences, the hierarchy
  // and the eigenbasis are the encoder body model's own assets' (built or
  // read from their own cache), so that every weight of a model of that body
  // model means what it meant there (weight_ties.hpp). Empty otherwise;
  // recomputed at every build (milliseconds).
  geometry::BodyResampling encoder_resampling;
  std::string hash;                        // of the template and settings
  std::string spec_text;                   // the settings as YAML

  // The rows `correspondence` indexes: the encoder body's points when there
  // is one, else the body's vertices.
  int correspondence_rows() const;

  // Sizes graphs use in `inputs:`: body_vertices, garment_vertices,
  // level1_vertices .. level3_vertices, eigen_k, and for a poseable body
  // model pose_angles and joints.
  std::map<std::string, int> dims() const;
};

// What to build. Plugin parameters are YAML scalars/lists by name.
struct AssetsSpec {
  std::string body_model = "parametric";
  std::map<std::string, std::string> body_params;
  std::string garment = "tshirt";
  std::map<std::string, std::string> garment_params;  // e.g. size: small, resolution: coarse
  int levels = 4;
  int eigen_k = 1000;  // clamped to the garment's vertex count
  // A body model whose vertices the encoder reads instead of body_model's
  // (its mean body resampled on this one's surface: Assets::
  // encoder_resampling), so that a model trained on one body model's
  // topology (the mannequin's) starts a model of another (the human rig).
  // Empty: the encoder reads body_model's own vertices.
  std::string encoder_body;
  std::map<std::string, std::string> encoder_body_params;
  std::string yaml() const;  // canonical text: the cache key's source
};

struct AssetsTimings {
  double garment = 0, correspondence = 0, hierarchy = 0, eigenbasis = 0, load = 0;
  bool from_cache = false;
  std::filesystem::path cache_file;
};

// $DRAPE_CACHE_DIR, else $XDG_CACHE_HOME/drape, else ~/.cache/drape.
std::filesystem::path default_cache_dir();

// Builds the garment and mean body (cheap), hashes them with the spec, and loads
// the rest from <cache_dir>/assets-<hash>.h5 when present, else computes it and
// writes that file atomically. An empty cache_dir disables caching.
std::shared_ptr<const Assets> build_assets(const Registry& registry, const AssetsSpec& spec,
                                           const std::filesystem::path& cache_dir = default_cache_dir(),
                                           AssetsTimings* timings = nullptr);

// The material space (the mesh with its UVs, as its template builds it, not
// dressed) of the spec's garment in each size of `sizes` (names of its
// template's `size` parameter), with each size's grade: what a garment of
// that size rests at. A name the template has no size of (grade: auto's
// steps, g1.05) is the spec's garment's material graded by its grade
// (grade_material). `sizes` pairs a name with its grade.
std::vector<std::pair<double, Mesh>> garment_materials(const Registry& registry, const AssetsSpec& spec,
                                                       const std::vector<std::pair<std::string, double>>& sizes);

}  // namespace drape
