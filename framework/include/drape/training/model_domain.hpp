#pragma once
// The domain a model was trained on: which body model, the range of every
// shape parameter and of the body's measured height and BMI over its training
// bodies, and a coarse descriptor of each training body, so that a body a
// user brings can be told to lie outside it (a network answers anything, and
// far from its data it answers wrongly without a sign: issue 21 measured
// p = 29 % on a female body given to a model trained on male ones).
//
// Stored in the model file under /domain (docs/formats.md):
//   attributes  body_model, source (the dataset), param_names (comma-joined),
//               measure_names ("height,bmi"), samples, neighbour_limit (m)
//   /domain/param_range     f64 [P, 2]   min, max of each shape parameter
//   /domain/measure_range   f64 [2, 2]   min, max of height (m) and BMI
//   /domain/descriptors     f32 [n, 3K]  K body vertices of each distinct training body
//   /domain/descriptor_vertices i32 [K]  which vertices
//   /domain/placement       f64 [2, 3]   where the training bodies stood (optional)
//   /domain/pose_range      f64 [A, 2]   min, max of each joint angle, degrees, over a
//                                        posed dataset's training bodies; attribute
//                                        pose_names (comma-joined). Absent: A-pose bodies
#include <drape/bodies/pose.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/io/dataset.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace drape {

struct BodyAnchor;  // bodies/body_anchor.hpp

struct ValueRange {
  double min = 0, max = 0;
};

struct ModelDomain {
  std::string body_model;
  std::string source;
  std::vector<std::string> param_names;
  std::vector<ValueRange> params;
  ValueRange height, bmi;
  std::vector<int> descriptor_vertices;
  Eigen::MatrixXf descriptors;  // [n, 3K], centred on each body's centroid; a body trained on twice once
  // A body farther (RMS over the descriptor vertices) from every training body
  // than this is outside: the largest distance of a training body to its
  // nearest other training body, times a margin (model_domain.cpp).
  double neighbour_limit = 0;
  std::size_t samples = 0;
  // Where the training bodies stood (body_placement): the mean over them, and
  // the largest distance of one of them from it on each axis. NaN in files
  // written before 2026-11-27, which do not record it.
  Eigen::Vector3d placement = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d placement_spread = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // The joint angles of a posed dataset's training bodies (degrees), by
  // name; empty for A-pose bodies. Height, BMI, descriptors and placement
  // are then measured on the bodies at rest (a raised arm is no height).
  std::vector<std::string> pose_names;
  std::vector<ValueRange> pose;
};

// How many bodies the model learnt from, as `drape train` and `model info`
// say it: "8 training bodies", or "16 training samples (8 distinct bodies)"
// when a body was trained on twice (a drape and its mirror image), which the
// descriptors hold once.
std::string training_count(const ModelDomain& domain);

// One line per joint angle of `pose` (degrees, full names) outside the
// domain's trained range ("joint angle left_shoulder_abduction 120 degrees is
// outside the trained range 25..100 degrees"); empty when inside or the
// domain records no poses.
std::vector<std::string> pose_violations(const ModelDomain& domain, const Pose& pose);

// Where a body stands: the mean x and z of its vertices and its lowest y (m).
// A network sees absolute coordinates, so a body lifted or moved aside from
// where its training bodies stood is a body it has never seen, although its
// shape (the descriptor, centred) is inside the domain.
Eigen::Vector3d body_placement(const Eigen::MatrixX3d& body);

// How far (m, per axis) a body stands from where the training bodies stood,
// on the axes where it is outside their spread by more than kPlacementSlack
// (0 on the others); nullopt when inside it on every axis, or when the
// domain records no placement.
constexpr double kPlacementSlack = 0.005;
std::optional<Eigen::Vector3d> placement_offset(const ModelDomain& domain, const Eigen::MatrixX3d& body);
// The same against any reference placement and spread (drape simulate --body
// against the body model's mean body).
std::optional<Eigen::Vector3d> placement_offset(const Eigen::Vector3d& reference, const Eigen::Vector3d& spread,
                                                const Eigen::MatrixX3d& body);

// Moves `body` by -placement_offset, so that it stands where the reference
// bodies stood; returns the offset (what to add to a drape made there to move
// it back with the body), nullopt when it was not moved. What predict,
// optimize and simulate --body (C++ and Python) do with a body given elsewhere.
std::optional<Eigen::Vector3d> move_to_placement(const Eigen::Vector3d& reference, const Eigen::Vector3d& spread,
                                                 Eigen::MatrixX3d& body);
std::optional<Eigen::Vector3d> move_to_placement(const ModelDomain& domain, Eigen::MatrixX3d& body);
// With the body model's anchor (bodies/body_anchor.hpp): on the axes it
// anchors, the body is placed by its anchor vertices, exactly where its model
// makes bodies (moved when off by more than the anchor's spread and
// kAnchorSlack); on the others as above. A null anchor: as above.
std::optional<Eigen::Vector3d> move_to_placement(const Eigen::Vector3d& reference, const Eigen::Vector3d& spread,
                                                 const BodyAnchor* anchor, Eigen::MatrixX3d& body);
// "stands (+0.000, +5.000, +0.000) m from where <where>; it is draped there and
// moved back with it": the one wording of that move for notes and warnings.
std::string placement_note(const Eigen::Vector3d& offset, const std::string& where);

// The domain of a dataset's training split (its done samples with split
// train), or of the part of it drape train --fraction trains on (the first
// ceil(fraction n) of them, as the trainer takes them). ConfigError when it has none.
ModelDomain domain_of_dataset(const DatasetReader& data, const std::string& body_model,
                              const std::vector<std::string>& param_names, const Eigen::MatrixX3i& body_faces,
                              double train_fraction = 1.0);

// The RMS distance (m) of a body to its nearest training body over the
// descriptor vertices.
double distance_to_training(const ModelDomain& domain, const Eigen::MatrixX3d& body);

// One line per way a body lies outside the domain, naming the measure, its
// value and the trained range; empty when inside. `params` are the body's
// shape parameters when known (a body made by the model's own plugin).
std::vector<std::string> domain_violations(const ModelDomain& domain, const Eigen::MatrixX3d& body,
                                           const Eigen::MatrixX3i& faces, const Eigen::VectorXd* params);

// Records the domain of `data`'s training split in the model file `model`,
// written to `out` (may be `model`) atomically and in the current, sealed
// format: drape train does it when it ends, drape model domain for older
// models. Returns what it recorded.
class Registry;
ModelDomain record_model_domain(const Registry& registry, const std::filesystem::path& model,
                                const std::filesystem::path& data, const std::filesystem::path& out,
                                double train_fraction = 1.0);

// Written into an open model file / read from one (nullopt: the file records
// no domain, as models written before 2026-11-25).
namespace h5 {
class File;
}
void write_domain(h5::File& file, const ModelDomain& domain);
std::optional<ModelDomain> read_domain(const h5::File& file);
std::optional<ModelDomain> read_domain(const std::filesystem::path& model_file);
// A model file written atomically: save_checkpoint, and the domain when there
// is one (drape model set, Python's Model.save: a rewritten model keeps the
// domain of the file it came from).
void save_model_file(const std::filesystem::path& path, const NamedWeights& weights, const Checkpoint& checkpoint,
                     const std::optional<ModelDomain>& domain);

}  // namespace drape
