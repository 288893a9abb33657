// A model's training domain: ranges, body descriptors and the check of a
// body against them (model_domain.hpp).
#include <drape/geometry/body_units.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/io/h5.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/bodies/body_anchor.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string_view>
#include <unordered_set>

namespace drape {

using geometry::body_bmi;
using geometry::body_height;

namespace {

// About this many body vertices describe a body's shape: enough to tell a
// female body from a male one of the same BMI, few enough to keep thousands
// of training bodies in the model file (200 * 3 floats each).
constexpr int kDescriptorVertices = 200;
// A body up to this many times the largest nearest-neighbour gap between the
// training bodies from its nearest training body is still inside.
constexpr double kNeighbourMargin = 1.5;

std::vector<int> descriptor_vertices(int body_vertices) {
  const int stride = std::max(1, body_vertices / kDescriptorVertices);
  std::vector<int> v;
  for (int i = 0; i < body_vertices; i += stride) v.push_back(i);
  return v;
}

Eigen::VectorXf descriptor(const Eigen::MatrixX3d& body, const std::vector<int>& vertices) {
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t k = 0; k < vertices.size(); ++k) points.row(static_cast<Eigen::Index>(k)) = body.row(vertices[k]);
  points.rowwise() -= points.colwise().mean();
  Eigen::VectorXf d(points.size());
  Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>>(d.data(), points.rows(), 3) = points.cast<float>();
  return d;
}

// RMS over the descriptor's vertices of the distance between two descriptors.
double rms_distance(const Eigen::Ref<const Eigen::VectorXf>& a, const Eigen::Ref<const Eigen::VectorXf>& b) {
  return std::sqrt((a - b).cast<double>().squaredNorm() / (static_cast<double>(a.size()) / 3.0));
}

void widen(ValueRange& r, double v, bool first) {
  if (first) r = {v, v};
  r.min = std::min(r.min, v);
  r.max = std::max(r.max, v);
}

std::string fmt(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.4g", v);  // 1.502..1.999 m, not 1.5..2
  return s;
}

std::string outside(const std::string& what, double value, const ValueRange& r, const std::string& unit) {
  return what + " " + fmt(value) + unit + " is outside the trained range " + fmt(r.min) + ".." + fmt(r.max) + unit;
}

std::vector<std::string> split_names(const std::string& joined) {
  std::vector<std::string> names;
  std::stringstream in(joined);
  for (std::string n; std::getline(in, n, ',');) names.push_back(n);
  return names;
}

}  // namespace

ModelDomain domain_of_dataset(const DatasetReader& data, const std::string& body_model,
                              const std::vector<std::string>& param_names, const Eigen::MatrixX3i& body_faces,
                              double train_fraction) {
  const std::vector<std::size_t> train = data.training_indices(train_fraction);
  if (train.empty()) throw ConfigError("the dataset has no training samples to take a model's domain from");
  ModelDomain d;
  d.body_model = body_model;
  d.param_names = param_names;
  d.samples = train.size();
  const Tensor params = data.body_params(train);
  const int P = params.cols();
  if (static_cast<std::size_t>(P) != param_names.size())
    throw ConfigError("the dataset stores " + std::to_string(P) + " body parameters; the body model '" + body_model +
                      "' has " + std::to_string(param_names.size()));
  d.params.assign(static_cast<std::size_t>(P), {});
  const bool posed = !data.layout().pose_angles.empty();
  if (posed) {
    d.pose_names = data.layout().pose_angles;
    d.pose.assign(d.pose_names.size(), {});
    const Tensor angles = data.poses(train);
    for (int s = 0; s < angles.batch(); ++s)
      for (std::size_t a = 0; a < d.pose.size(); ++a) widen(d.pose[a], angles(s, 0, static_cast<int>(a)), s == 0);
  }
  std::vector<Eigen::Vector3d> placements;
  placements.reserve(train.size());
  const int nb = data.layout().body_vertices;
  d.descriptor_vertices = descriptor_vertices(nb);
  d.descriptors.resize(static_cast<Eigen::Index>(train.size()), static_cast<Eigen::Index>(3 * d.descriptor_vertices.size()));
  // In slices: a default-resolution dataset's bodies do not all fit in memory at once.
  constexpr std::size_t kSlice = 256;
  for (std::size_t first = 0; first < train.size(); first += kSlice) {
    const std::vector<std::size_t> slice(train.begin() + static_cast<std::ptrdiff_t>(first),
                                         train.begin() + static_cast<std::ptrdiff_t>(std::min(train.size(), first + kSlice)));
    // A posed dataset's bodies measured at rest (what predict measures: BodyPreparation runs before posing).
    const Tensor bodies = posed ? data.posing(slice).unposed : data.body_vertices(slice);
    for (int i = 0; i < bodies.batch(); ++i) {
      const std::size_t s = first + static_cast<std::size_t>(i);
      const Eigen::MatrixX3d v = bodies.mat(i).cast<double>();
      widen(d.height, body_height(v), s == 0);
      widen(d.bmi, body_bmi(v, body_faces), s == 0);
      for (int p = 0; p < P; ++p) widen(d.params[static_cast<std::size_t>(p)], params(static_cast<int>(s), 0, p), s == 0);
      d.descriptors.row(static_cast<Eigen::Index>(s)) = descriptor(v, d.descriptor_vertices).transpose();
      placements.push_back(body_placement(v));
    }
  }
  d.placement.setZero();
  for (const Eigen::Vector3d& p : placements) d.placement += p / static_cast<double>(placements.size());
  d.placement_spread.setZero();
  for (const Eigen::Vector3d& p : placements) d.placement_spread = d.placement_spread.cwiseMax((p - d.placement).cwiseAbs());
  // A body trained on twice (a posed drape and its mirror image share the
  // body at rest: scripts/mirror_dataset.py) is stored once: its copy would
  // double the model file's descriptors and every check's scan, and as its own
  // neighbour at distance 0 make the widest gap 0 and the limit the 1 cm floor.
  // On the descriptors as contiguous columns: the model's rows are strided.
  const Eigen::MatrixXf all = d.descriptors.transpose();
  std::vector<Eigen::Index> distinct;
  std::unordered_set<std::string_view> seen;
  const auto bytes = [&all](Eigen::Index c) {
    return std::string_view(reinterpret_cast<const char*>(all.col(c).data()), sizeof(float) * static_cast<std::size_t>(all.rows()));
  };
  for (Eigen::Index c = 0; c < all.cols(); ++c)
    if (seen.insert(bytes(c)).second) distinct.push_back(c);
  const Eigen::MatrixXf columns = all(Eigen::all, distinct);
  d.descriptors = columns.transpose();
  // The largest gap from a training body to its nearest other one, each pair
  // once (3,300 bodies' 5.4 million pairs read row by row took minutes of
  // `drape train`).
  const Eigen::Index n = columns.cols();
  std::vector<double> nearest(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const double r = rms_distance(columns.col(i), columns.col(j));
      nearest[static_cast<std::size_t>(i)] = std::min(nearest[static_cast<std::size_t>(i)], r);
      nearest[static_cast<std::size_t>(j)] = std::min(nearest[static_cast<std::size_t>(j)], r);
    }
  double widest = 0;
  for (const double r : nearest)
    if (std::isfinite(r)) widest = std::max(widest, r);
  // One training body: allow what a fitted shape differs by (1 cm).
  d.neighbour_limit = std::max(kNeighbourMargin * widest, 0.01);
  return d;
}

Eigen::Vector3d body_placement(const Eigen::MatrixX3d& body) {
  const Eigen::RowVector3d mean = body.colwise().mean();
  return {mean[0], body.col(1).minCoeff(), mean[2]};
}

std::optional<Eigen::Vector3d> placement_offset(const Eigen::Vector3d& reference, const Eigen::Vector3d& spread,
                                                const Eigen::MatrixX3d& body) {
  if (!reference.allFinite() || !spread.allFinite() || body.rows() == 0) return std::nullopt;
  Eigen::Vector3d offset = body_placement(body) - reference;
  // Only the axes on which the body stands outside the spread: a body only
  // lifted keeps its own x and z.
  for (int a = 0; a < 3; ++a)
    if (std::abs(offset[a]) <= spread[a] + kPlacementSlack) offset[a] = 0;
  if (offset.isZero()) return std::nullopt;
  return offset;
}

std::optional<Eigen::Vector3d> placement_offset(const ModelDomain& domain, const Eigen::MatrixX3d& body) {
  return placement_offset(domain.placement, domain.placement_spread, body);
}

std::optional<Eigen::Vector3d> move_to_placement(const Eigen::Vector3d& reference, const Eigen::Vector3d& spread,
                                                 Eigen::MatrixX3d& body) {
  const std::optional<Eigen::Vector3d> offset = placement_offset(reference, spread, body);
  if (offset) body.rowwise() -= offset->transpose();
  return offset;
}

std::optional<Eigen::Vector3d> move_to_placement(const ModelDomain& domain, Eigen::MatrixX3d& body) {
  return move_to_placement(domain.placement, domain.placement_spread, body);
}

std::optional<Eigen::Vector3d> move_to_placement(const Eigen::Vector3d& reference, const Eigen::Vector3d& spread,
                                                 const BodyAnchor* anchor, Eigen::MatrixX3d& body) {
  if (!anchor) return move_to_placement(reference, spread, body);
  Eigen::Vector3d offset = placement_offset(reference, spread, body).value_or(Eigen::Vector3d::Zero());
  const Eigen::Vector3d anchored = anchor->offset(body);
  for (int a = 0; a < 3; ++a) {
    // Bodies recorded standing elsewhere than the body model stands them keep that record.
    const bool recorded = std::isfinite(reference[a]) && std::isfinite(spread[a]);
    if (!anchor->anchors(a) || (recorded && !anchor->agrees(a, reference[a], spread[a]))) continue;
    offset[a] = std::abs(anchored[a]) <= anchor->spread[a] + kAnchorSlack ? 0.0 : anchored[a];
  }
  if (offset.isZero(0.0)) return std::nullopt;
  body.rowwise() -= offset.transpose();
  return offset;
}

std::string placement_note(const Eigen::Vector3d& offset, const std::string& where) {
  char moved[96];
  // A move under a centimetre in millimetres: "(+0.000, +0.000, +0.000) m" said a move that changed the drape.
  if (offset.cwiseAbs().maxCoeff() < 0.01)
    std::snprintf(moved, sizeof moved, "stands (%+.2f, %+.2f, %+.2f) mm from where ", 1e3 * offset[0], 1e3 * offset[1], 1e3 * offset[2]);
  else
    std::snprintf(moved, sizeof moved, "stands (%+.3f, %+.3f, %+.3f) m from where ", offset[0], offset[1], offset[2]);
  return moved + where + "; it is draped there and moved back with it";
}

double distance_to_training(const ModelDomain& domain, const Eigen::MatrixX3d& body) {
  const Eigen::VectorXf d = descriptor(body, domain.descriptor_vertices);
  // Coordinate by coordinate down the stored columns (contiguous), every
  // training body at once: a row per body would be a strided read.
  const Eigen::MatrixXf& stored = domain.descriptors;
  Eigen::ArrayXd squared = Eigen::ArrayXd::Zero(stored.rows());
  for (Eigen::Index k = 0; k < stored.cols(); ++k)
    squared += (stored.col(k).array() - d[k]).cast<double>().square();
  double nearest = std::numeric_limits<double>::infinity();
  if (squared.size() > 0) nearest = std::sqrt(squared.minCoeff() / (static_cast<double>(stored.cols()) / 3.0));
  return nearest;
}

std::string training_count(const ModelDomain& domain) {
  const auto distinct = static_cast<std::size_t>(domain.descriptors.rows());
  if (distinct > 0 && distinct < domain.samples)
    return std::to_string(domain.samples) + " training samples (" + std::to_string(distinct) + " distinct bodies)";
  return std::to_string(domain.samples) + " training bodies";
}

std::vector<std::string> domain_violations(const ModelDomain& domain, const Eigen::MatrixX3d& body,
                                           const Eigen::MatrixX3i& faces, const Eigen::VectorXd* params) {
  std::vector<std::string> out;
  // Each range with a little slack: the same body measured again (another
  // mesh writer's rounding) must not fall out.
  auto within = [](double v, const ValueRange& r, double slack) { return v >= r.min - slack && v <= r.max + slack; };
  const double h = body_height(body), bmi = body_bmi(body, faces);
  const bool height_out = !within(h, domain.height, 0.005);
  if (height_out) out.push_back(outside("height", h, domain.height, " m"));
  // The usual reasons a mesh of the right topology is far off: other units,
  // lying down (Z up, or on its side), an absurd coordinate (body_units.hpp).
  if (std::string why = body_units_problem(body, "the body"); !why.empty()) out.push_back(std::move(why));
  if (!within(bmi, domain.bmi, 0.1)) out.push_back(outside("BMI", bmi, domain.bmi, ""));
  if (params && static_cast<std::size_t>(params->size()) == domain.params.size())
    for (std::size_t p = 0; p < domain.params.size(); ++p) {
      const double v = (*params)(static_cast<Eigen::Index>(p));
      const ValueRange& r = domain.params[p];
      // n bodies drawn uniformly over [a, b] fall short of each end by
      // g = (b - a) / (n + 1) on average, and by more than k g with
      // probability about exp(-k): a parameter within 5 g of the sampled
      // range is inside the range the data were drawn from (the heights 1.50
      // and 2.00 m of a model sampled over 1.50-2.00 m), missed at an end
      // with probability 0.7 %. (With 2 g, 13.5 %: the A-pose model of 2,289
      // bodies, whose tallest is 1.99956 m, 2.03 g short, called 2.00 m
      // outside.)
      const double gap = (r.max - r.min) / static_cast<double>(domain.samples + 1);
      // (A shape parameter that is the height itself says what the measured height said.)
      if (height_out && domain.param_names[p] == "height") continue;
      if (!within(v, r, std::max(5.0 * gap, 1e-6 * std::max(1.0, r.max - r.min))))
        out.push_back(outside("shape parameter '" + domain.param_names[p] + "'", v, r, ""));
    }
  if (!domain.descriptor_vertices.empty() && domain.descriptors.rows() > 0 &&
      domain.descriptor_vertices.back() < body.rows()) {
    const double d = distance_to_training(domain, body);
    if (d > domain.neighbour_limit)
      out.push_back("the body is " + fmt(100 * d) + " cm (RMS) from the nearest of the " + std::to_string(domain.descriptors.rows()) +
                    " training bodies (limit " + fmt(100 * domain.neighbour_limit) + " cm)");
  }
  return out;
}

void write_domain(h5::File& file, const ModelDomain& d) {
  file.create_group("/domain");
  file.set_attribute("/domain", "body_model", d.body_model);
  file.set_attribute("/domain", "source", d.source);
  std::string names;
  for (std::size_t i = 0; i < d.param_names.size(); ++i) names += (i ? "," : "") + d.param_names[i];
  file.set_attribute("/domain", "param_names", names);
  file.set_attribute("/domain", "measure_names", "height,bmi");
  file.set_attribute("/domain", "samples", static_cast<double>(d.samples));
  file.set_attribute("/domain", "neighbour_limit", d.neighbour_limit);
  std::vector<double> ranges;
  for (const ValueRange& r : d.params) ranges.insert(ranges.end(), {r.min, r.max});
  file.write("/domain/param_range", {d.params.size(), 2}, ranges.data());
  const std::vector<double> measures{d.height.min, d.height.max, d.bmi.min, d.bmi.max};
  file.write("/domain/measure_range", {2, 2}, measures.data());
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = d.descriptors;
  file.write("/domain/descriptors", {static_cast<std::size_t>(rows.rows()), static_cast<std::size_t>(rows.cols())}, rows.data());
  const std::vector<std::int32_t> vertices(d.descriptor_vertices.begin(), d.descriptor_vertices.end());
  file.write("/domain/descriptor_vertices", vertices);
  if (d.placement.allFinite() && d.placement_spread.allFinite()) {
    const std::vector<double> placement{d.placement[0],        d.placement[1],        d.placement[2],
                                        d.placement_spread[0], d.placement_spread[1], d.placement_spread[2]};
    file.write("/domain/placement", {2, 3}, placement.data());
  }
  if (!d.pose_names.empty()) {
    std::string pose_names;
    for (std::size_t i = 0; i < d.pose_names.size(); ++i) pose_names += (i ? "," : "") + d.pose_names[i];
    std::vector<double> pose;
    for (const ValueRange& r : d.pose) pose.insert(pose.end(), {r.min, r.max});
    file.write("/domain/pose_range", {d.pose.size(), 2}, pose.data());
    file.set_attribute("/domain", "pose_names", pose_names);
  }
}

std::optional<ModelDomain> read_domain(const h5::File& file) {
  if (!file.is_group("/domain")) return std::nullopt;
  ModelDomain d;
  d.body_model = file.require_string_attribute("/domain", "body_model");
  d.source = file.string_attribute("/domain", "source").value_or("");
  d.param_names = split_names(file.require_string_attribute("/domain", "param_names"));
  d.samples = static_cast<std::size_t>(file.number_attribute("/domain", "samples").value_or(0));
  d.neighbour_limit = file.number_attribute("/domain", "neighbour_limit").value_or(0);
  h5::Dims shape;
  const std::vector<double> ranges = file.read<double>("/domain/param_range", &shape);
  if (shape.size() != 2 || shape[1] != 2 || shape[0] != d.param_names.size())
    throw ConfigError(file.path().string() + ": /domain/param_range has shape " + h5::to_string(shape) + ", expected [" +
                      std::to_string(d.param_names.size()) + ", 2]");
  // A range a model records is finite and not upside down: a warning that
  // says "trained on nan..nan" or "2..1.5" helps nobody (and --strict would
  // refuse every body by it).
  const auto check_range = [&](const std::string& what, double lo, double hi) {
    if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi))
      throw ConfigError(file.path().string() + ": /domain/" + what + " is [" + fmt(lo) + ", " + fmt(hi) +
                        "], not a range (finite, min <= max): the model file is damaged");
  };
  for (std::size_t p = 0; p < shape[0]; ++p) {
    check_range("param_range of '" + d.param_names[p] + "'", ranges[2 * p], ranges[2 * p + 1]);
    d.params.push_back({ranges[2 * p], ranges[2 * p + 1]});
  }
  const std::vector<double> measures = file.read<double>("/domain/measure_range", &shape);
  if (measures.size() != 4) throw ConfigError(file.path().string() + ": /domain/measure_range is not [2, 2]");
  check_range("measure_range (height)", measures[0], measures[1]);
  check_range("measure_range (BMI)", measures[2], measures[3]);
  d.height = {measures[0], measures[1]};
  d.bmi = {measures[2], measures[3]};
  if (!(std::isfinite(d.neighbour_limit) && d.neighbour_limit >= 0))
    throw ConfigError(file.path().string() + ": /domain's neighbour_limit is " + fmt(d.neighbour_limit) +
                      ", not a distance: the model file is damaged");
  const std::vector<std::int32_t> vertices = file.read<std::int32_t>("/domain/descriptor_vertices");
  // Body vertex indices, rising (the test of a body against the training
  // bodies reads them from it, and checks the body only against the last).
  for (std::size_t k = 0; k < vertices.size(); ++k)
    if (vertices[k] < 0 || (k > 0 && vertices[k] <= vertices[k - 1]))
      throw ConfigError(file.path().string() + ": /domain/descriptor_vertices[" + std::to_string(k) + "] = " +
                        std::to_string(vertices[k]) + " is not a body vertex index above the one before: the model file is damaged");
  d.descriptor_vertices.assign(vertices.begin(), vertices.end());
  const std::vector<float> rows = file.read<float>("/domain/descriptors", &shape);
  if (shape.size() != 2 || shape[1] != 3 * vertices.size())
    throw ConfigError(file.path().string() + ": /domain/descriptors has shape " + h5::to_string(shape) + ", expected [n, " +
                      std::to_string(3 * vertices.size()) + "]");
  d.descriptors = Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      rows.data(), static_cast<Eigen::Index>(shape[0]), static_cast<Eigen::Index>(shape[1]));
  if (!d.descriptors.allFinite())
    throw ConfigError(file.path().string() + ": /domain/descriptors holds a non-finite value: the model file is damaged");
  if (file.exists("/domain/placement")) {
    const std::vector<double> placement = file.read<double>("/domain/placement", &shape);
    if (shape.size() != 2 || shape[0] != 2 || shape[1] != 3 ||
        !std::all_of(placement.begin(), placement.end(), [](double v) { return std::isfinite(v); }))
      throw ConfigError(file.path().string() + ": /domain/placement has shape " + h5::to_string(shape) +
                        " or non-finite values, expected [2, 3] finite numbers");
    d.placement = Eigen::Vector3d(placement[0], placement[1], placement[2]);
    d.placement_spread = Eigen::Vector3d(placement[3], placement[4], placement[5]);
  }
  if (file.exists("/domain/pose_range")) {
    d.pose_names = split_names(file.require_string_attribute("/domain", "pose_names"));
    const std::vector<double> pose = file.read<double>("/domain/pose_range", &shape);
    if (shape.size() != 2 || shape[1] != 2 || shape[0] != d.pose_names.size())
      throw ConfigError(file.path().string() + ": /domain/pose_range has shape " + h5::to_string(shape) + ", expected [" +
                        std::to_string(d.pose_names.size()) + ", 2]");
    for (std::size_t a = 0; a < shape[0]; ++a) {
      check_range("pose_range of '" + d.pose_names[a] + "'", pose[2 * a], pose[2 * a + 1]);
      d.pose.push_back({pose[2 * a], pose[2 * a + 1]});
    }
  }
  return d;
}

std::vector<std::string> pose_violations(const ModelDomain& domain, const Pose& pose) {
  std::vector<std::string> out;
  for (std::size_t a = 0; a < domain.pose_names.size(); ++a) {
    const auto it = pose.angles.find(domain.pose_names[a]);
    if (it == pose.angles.end()) continue;
    const ValueRange& r = domain.pose[a];
    // As for the shape parameters: n angles drawn uniformly fall short of each
    // end of the drawn range by (max - min) / (n + 1) on average, so an angle
    // within twice that (and half a degree: a pose written with fewer digits)
    // lies in what the training poses were drawn from.
    const double slack = std::max(0.5, 2.0 * (r.max - r.min) / static_cast<double>(domain.samples + 1));
    if (it->second >= r.min - slack && it->second <= r.max + slack) continue;
    out.push_back(outside("joint angle " + domain.pose_names[a], it->second, r, " degrees"));
  }
  return out;
}

std::optional<ModelDomain> read_domain(const std::filesystem::path& model_file) {
  return read_domain(h5::File::open(model_file));
}

}  // namespace drape
