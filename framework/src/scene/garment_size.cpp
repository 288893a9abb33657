#include <drape/garment_size.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/simulation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace drape {
namespace {

constexpr double kBandStep = 0.02;

const ParamSpec* size_spec(const Registry& registry, const Scene& scene) {
  for (const ParamSpec& p : registry.get(scene.garment).params)
    if (p.name == "size" && !p.choices.empty()) return &p;
  return nullptr;
}

// The garment's narrowest loop around the body's axis over the band, on the mean body.
double garment_girth_on(const Mesh& garment, const Eigen::MatrixX3d& mean_body) {
  const double y0 = mean_body.col(1).minCoeff(), h = geometry::body_height(mean_body);
  double narrowest = std::numeric_limits<double>::infinity();
  for (double f = kGirthBandLow; f <= kGirthBandHigh + 1e-9; f += kBandStep) {
    const geometry::Girth g = geometry::horizontal_girth(garment.vertices, garment.faces, y0 + f * h, {0.0, 0.0});
    if (g.found) narrowest = std::min(narrowest, g.length);
  }
  return narrowest;
}

}  // namespace

double SizeChoice::garment_girth(const std::string& s) const {
  for (const auto& [name, g] : girth)
    if (name == s) return g;
  return 0.0;
}

std::string SizeChoice::summary() const {
  char head[160];
  std::snprintf(head, sizeof head, "body girth %.3f m (chest or belly); design ease %.1f %%; ease by size:", body_girth,
                100.0 * design_ease);
  std::string out = head;
  for (const auto& [name, e] : ease) {
    char item[64];
    std::snprintf(item, sizeof item, " %s %+.1f %%", name.c_str(), 100.0 * e);
    out += item;
  }
  if (size.empty()) return out + ": no size is as large as the body, the garment does not fit it";
  return out + ": size " + size;
}

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
  out.garment_params["size"] = ParamValue{YAML::Node(size), it != scene.garment_params.end() ? it->second.where : SourceLocation{}};
  return out;
}

double body_girth(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces) {
  const double y0 = body.col(1).minCoeff(), h = geometry::body_height(body);
  double largest = 0.0;
  for (double f = kGirthBandLow; f <= kGirthBandHigh + 1e-9; f += kBandStep) {
    const geometry::Girth g = geometry::horizontal_girth(body, faces, y0 + f * h, {0.0, 0.0});
    if (g.found) largest = std::max(largest, g.tape);
  }
  if (!(largest > 0.0)) throw ConfigError("the body has no torso cross-section around its vertical axis to measure");
  return largest;
}

SizeChart::SizeChart(const Registry& registry, const Scene& scene) {
  const ParamSpec* spec = size_spec(registry, scene);
  if (!spec) throw ConfigError("garment '" + scene.garment + "' has no sizes to choose from (size: auto)");
  double design_girth = 0.0;
  Eigen::MatrixX3d mean_body;
  for (const std::string& s : spec->choices) {
    if (s == "auto") continue;
    const Simulation sim(registry, with_garment_size(scene, s));
    const double g = garment_girth_on(sim.garment().mesh, sim.mean_body());
    if (!std::isfinite(g)) throw ConfigError("size " + s + " of garment '" + scene.garment + "': no loop of it goes around the body to measure");
    sizes_.push_back(s);
    girth_.emplace_back(s, g);
    if (s == spec->default_value) design_girth = g;
    mean_body = sim.mean_body();
    faces_ = sim.body_model().faces();
  }
  body_vertices_ = mean_body.rows();
  design_ease_ = design_girth / body_girth(mean_body, faces_) - 1.0;
}

SizeChoice SizeChart::choose(const Eigen::MatrixX3d& body) const {
  if (body.rows() != body_vertices_)
    throw ConfigError("the body has " + std::to_string(body.rows()) + " vertices; the scene's body model has " +
                      std::to_string(body_vertices_));
  SizeChoice choice;
  choice.girth = girth_;
  choice.design_ease = design_ease_;
  choice.body_girth = body_girth(body, faces_);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [s, g] : girth_) {
    const double ease = g / choice.body_girth - 1.0;
    choice.ease.emplace_back(s, ease);
    if (ease >= kMinimumEase && std::abs(ease - design_ease_) < best) {
      best = std::abs(ease - design_ease_);
      choice.size = s;
    }
  }
  return choice;
}

SizeChoice choose_garment_size(const Registry& registry, const Scene& scene, const Eigen::MatrixX3d& body) {
  return SizeChart(registry, scene).choose(body);
}

}  // namespace drape
