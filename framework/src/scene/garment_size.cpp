#include <drape/vertex_count.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/bodies/given_body.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/geometry/volume.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

namespace drape {
namespace {

constexpr double kBandStep = 0.02;

const ParamSpec* size_spec(const Registry& registry, const Scene& scene) {
  for (const ParamSpec& p : registry.get(scene.garment).params)
    if (p.name == "size" && !p.choices.empty()) return &p;
  return nullptr;
}

// The girths of a mesh at the band's heights of `body` (from its soles), those
// where a loop goes around the vertical axis.
std::vector<geometry::Girth> band_girths(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces,
                                         const Eigen::MatrixX3d& body, const Mesh* material = nullptr) {
  const double y0 = body.col(1).minCoeff(), h = geometry::body_height(body);
  std::vector<geometry::Girth> out;
  for (double f = kGirthBandLow; f <= kGirthBandHigh + 1e-9; f += kBandStep) {
    const geometry::Girth g = geometry::horizontal_girth(vertices, faces, y0 + f * h, {0.0, 0.0},
                                                         material ? &material->uv : nullptr,
                                                         material ? &material->uv_faces : nullptr);
    if (g.found) out.push_back(g);
  }
  return out;
}

}  // namespace

std::string default_garment_size(const Registry& registry, const Scene& scene) {
  const ParamSpec* spec = size_spec(registry, scene);
  if (!spec) throw ConfigError("garment '" + scene.garment + "' has no sizes to choose from (size: auto)");
  return spec->default_value;
}

bool garment_size_is_auto(const Scene& scene) {
  const auto it = scene.garment_params.find("size");
  return it != scene.garment_params.end() && it->second.node.IsScalar() && it->second.node.as<std::string>() == "auto";
}

Scene with_garment_size(const Scene& scene, const std::string& size) {
  Scene out = scene;
  const auto it = scene.garment_params.find("size");
  const SourceLocation where = it != scene.garment_params.end() ? it->second.where : SourceLocation{};
  // Erased and inserted, not assigned: a yaml-cpp node assigned to rebinds
  // the node it shares with `scene` (and every copy of it), so assigning
  // here wrote the last size built into the scene a dataset stores.
  out.garment_params.erase("size");
  out.garment_params.emplace("size", ParamValue{YAML::Node(size), where});
  return out;
}

namespace {

// body_girth's measure, 0 when the body has no torso cross-section to measure.
double largest_tape(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces) {
  double largest = 0.0;
  for (const geometry::Girth& g : band_girths(body, faces, body)) largest = std::max(largest, g.tape);
  return largest;
}

}  // namespace

double body_girth(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces) {
  const double largest = largest_tape(body, faces);
  if (!(largest > 0.0)) throw ConfigError("the body has no torso cross-section around its vertical axis to measure");
  return largest;
}

double garment_girth(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3i& garment_faces,
                     const Eigen::MatrixX3d& mean_body) {
  double narrowest = std::numeric_limits<double>::infinity();
  for (const geometry::Girth& g : band_girths(garment, garment_faces, mean_body)) narrowest = std::min(narrowest, g.length);
  return narrowest;
}

std::string garment_beside_body(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3i& garment_faces,
                                const Eigen::MatrixX3d& mean_body, const Eigen::MatrixX3i& body_faces) {
  const double y0 = mean_body.col(1).minCoeff(), h = geometry::body_height(mean_body);
  double loop = 0.0, around = 0.0;  // the longest torso-sized loop beside the body, and the body's girth there
  for (double f = kGirthBandLow; f <= kGirthBandHigh + 1e-9; f += kBandStep) {
    const geometry::Girth cloth = geometry::horizontal_girth(garment, garment_faces, y0 + f * h, {0.0, 0.0});
    if (cloth.found) return "";
    const geometry::Girth body = geometry::horizontal_girth(mean_body, body_faces, y0 + f * h, {0.0, 0.0});
    if (body.found && cloth.longest_loop >= 0.5 * body.length && cloth.longest_loop > loop)
      loop = cloth.longest_loop, around = body.length;
  }
  if (loop == 0.0) return "";
  // Where the cloth over the band lies: the mean of its vertices there.
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  int count = 0;
  for (Eigen::Index v = 0; v < garment.rows(); ++v) {
    const double f = (garment(v, 1) - y0) / h;
    if (f < kGirthBandLow || f > kGirthBandHigh) continue;
    centre += Eigen::Vector2d(garment(v, 0), garment(v, 2));
    ++count;
  }
  if (count > 0) centre /= count;
  char text[320];
  std::snprintf(text, sizeof text,
                "no loop of it between %.0f and %.0f %% of the body's height encloses the body, while a loop there is "
                "%.0f cm long against the body's %.0f cm around: it lies beside the body, its cloth there centred "
                "%.0f cm %s and %.0f cm %s of the body's axis",
                100 * kGirthBandLow, 100 * kGirthBandHigh, 100 * loop, 100 * around, 100 * std::abs(centre.y()),
                centre.y() >= 0 ? "in front" : "behind", 100 * std::abs(centre.x()), centre.x() >= 0 ? "left" : "right");
  return text;
}

double garment_material_girth(const Mesh& garment, const Eigen::MatrixX3d& mean_body) {
  if (!garment.has_uv()) return std::numeric_limits<double>::quiet_NaN();
  double narrowest = std::numeric_limits<double>::infinity();
  for (const geometry::Girth& g : band_girths(garment.vertices, garment.faces, mean_body, &garment))
    narrowest = std::min(narrowest, g.material_length);
  return std::isfinite(narrowest) ? narrowest : std::numeric_limits<double>::quiet_NaN();
}

double garment_ease(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3i& garment_faces,
                    const Eigen::MatrixX3d& mean_body, const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& body_faces) {
  return garment_ease(garment_girth(garment, garment_faces, mean_body), body, body_faces);
}

double garment_ease(double garment_loop, const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& body_faces) {
  const double around = largest_tape(body, body_faces);
  if (!std::isfinite(garment_loop) || !(around > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return garment_loop / around - 1.0;
}

SizeChart::SizeChart(const Registry& registry, const Scene& scene) {
  const ParamSpec* spec = size_spec(registry, scene);
  if (!spec) throw ConfigError("garment '" + scene.garment + "' has no sizes to choose from (size: auto)");
  design_size_ = spec->default_value;
  double design_girth = 0.0;
  for (const std::string& s : spec->choices) {
    if (s == "auto") continue;
    auto sim = std::make_unique<Simulation>(registry, with_garment_size(scene, s));
    // A size's girth: its fabric's narrowest loop over the band on the mean body.
    const double narrowest = garment_girth(sim->garment().mesh.vertices, sim->garment().mesh.faces, sim->mean_body());
    if (!std::isfinite(narrowest))
      throw ConfigError("size " + s + " of garment '" + scene.garment + "': no loop of it goes around the body to measure");
    if (s == design_size_) design_girth = narrowest;
    sizes_.push_back(s);
    table_.girth.emplace_back(s, narrowest);
    simulations_.push_back(std::move(sim));
  }
  const Simulation& d = design();
  table_.design = design_size_;
  table_.design_ease = design_girth / body_girth(d.mean_body(), d.body_model().faces()) - 1.0;
}

SizeChart::~SizeChart() = default;

const Simulation& SizeChart::simulation(const std::string& size) const {
  for (std::size_t i = 0; i < sizes_.size(); ++i)
    if (sizes_[i] == size) return *simulations_[i];
  throw ConfigError("size '" + size + "' is not one of the garment's sizes");
}

SizeChoice SizeChart::choose(const Eigen::MatrixX3d& body) const {
  const Simulation& d = design();
  require_vertex_count(body.rows(), d.mean_body().rows(), "the body",
                       "the scene's body model '" + d.scene().body_model + "'");
  return table_.choose(body_girth(body, d.body_model().faces()));
}

SceneSimulations::SceneSimulations(const Registry& registry, const Scene& scene) : garment_(scene.garment) {
  if (scene.garment_grade_auto)
    grades_ = std::make_unique<AutoGrade>(registry, scene);
  else if (garment_size_is_auto(scene))
    chart_ = std::make_unique<SizeChart>(registry, scene);
  else
    own_ = std::make_unique<Simulation>(registry, scene);
  given_ = std::make_unique<GivenBodyFrame>(design().body_model());
}

SceneSimulations::~SceneSimulations() = default;

const Simulation& SceneSimulations::design() const {
  return chart_ ? chart_->design() : grades_ ? grades_->design() : *own_;
}

const Simulation& SceneSimulations::for_body(const Eigen::MatrixX3d& body, const std::string& what, SizeChoice* choice,
                                             GradeChoice* grade_choice) const {
  if (grades_) {
    const GradeChoice chosen = grades_->choose(body, what);
    if (grade_choice) *grade_choice = chosen;
    return grades_->simulation(chosen.grade);
  }
  if (!chart_) return *own_;
  const SizeChoice chosen = chart_->choose(body);
  if (chosen.size.empty())
    throw ConfigError(what + ": garment '" + garment_ + "' with size: auto does not fit this body: " + chosen.summary());
  if (choice) *choice = chosen;
  return chart_->simulation(chosen.size);
}

}  // namespace drape
