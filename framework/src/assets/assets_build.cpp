#include "assets_cache.hpp"

#include <drape/fnv1a.hpp>
#include <drape/energy.hpp>
#include <drape/bodies/body.hpp>
#include <drape/assets/assets.hpp>
#include <drape/bodies/fit_body.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/garment_grading.hpp>
#include <drape/geometry/body_correspondence.hpp>
#include <drape/geometry/laplacian.hpp>
#include <drape/registry.hpp>
#include <drape/spectral/spectral.hpp>

#include <algorithm>
#include <chrono>
#include <optional>
#include <cstdlib>
#include <sstream>

namespace fs = std::filesystem;

namespace drape {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

ParamValues values_of(const std::map<std::string, std::string>& given, const std::string& what) {
  ParamValues out;
  for (const auto& [k, v] : given) out[k] = {YAML::Load(v), {what, 0}};
  return out;
}

}  // namespace

std::vector<std::pair<double, Mesh>> garment_materials(const Registry& registry, const AssetsSpec& spec,
                                                       const std::vector<std::pair<std::string, double>>& sizes) {
  const PluginDescriptor& gd = registry.get(spec.garment);
  const auto size_param = std::find_if(gd.params.begin(), gd.params.end(), [](const ParamSpec& p) { return p.name == "size"; });
  const auto build = [&](const std::map<std::string, std::string>& params) {
    return registry.create_garment(spec.garment, Params(gd.params, values_of(params, "garment"), "garment '" + spec.garment + "'"))
        ->build()
        .mesh;
  };
  std::optional<Mesh> design;
  std::vector<std::pair<double, Mesh>> out;
  for (const auto& [name, grade] : sizes) {
    const bool a_size = size_param != gd.params.end() &&
                        std::find(size_param->choices.begin(), size_param->choices.end(), name) != size_param->choices.end();
    if (a_size) {
      std::map<std::string, std::string> params = spec.garment_params;
      params["size"] = name;
      out.emplace_back(grade, build(params));
      continue;
    }
    if (!design) design = build(spec.garment_params);
    Mesh graded = *design;
    grade_material(graded, grade);
    out.emplace_back(grade, std::move(graded));
  }
  return out;
}

std::string AssetsSpec::yaml() const {
  std::ostringstream o;
  o << "body: { model: " << body_model << ", params: {";
  for (const auto& [k, v] : body_params) o << " " << k << ": " << v << ",";
  o << " } }\ngarment: { template: " << garment << ", params: {";
  for (const auto& [k, v] : garment_params) o << " " << k << ": " << v << ",";
  o << " } }\nlevels: " << levels << "\neigen_k: " << eigen_k << "\n";
  // Only when set, so that every spec before it keeps its text and its cache.
  if (!encoder_body.empty()) {
    o << "encoder_body: { model: " << encoder_body << ", params: {";
    for (const auto& [k, v] : encoder_body_params) o << " " << k << ": " << v << ",";
    o << " } }\n";
  }
  return o.str();
}

std::map<std::string, int> Assets::dims() const {
  std::map<std::string, int> d{{"body_vertices", body.num_vertices()},
                               {"garment_vertices", garment ? garment->mesh.num_vertices() : 0},
                               {"eigen_k", static_cast<int>(eigenvalues.size())}};
  for (int l = 1; l < hierarchy.num_levels(); ++l)
    d["level" + std::to_string(l) + "_vertices"] = hierarchy.levels[static_cast<std::size_t>(l)].mesh.num_vertices();
  if (!pose_angles.empty()) {
    d["pose_angles"] = static_cast<int>(pose_angles.size());
    d["joints"] = static_cast<int>(garment_skinning.cols());
  }
  return d;
}

int Assets::correspondence_rows() const {
  return encoder_resampling.size() > 0 ? encoder_resampling.size() : body.num_vertices();
}

fs::path default_cache_dir() {
  if (const char* d = std::getenv("DRAPE_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "drape";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "drape";
  return fs::temp_directory_path() / "drape-cache";
}

std::shared_ptr<const Assets> build_assets(const Registry& registry, const AssetsSpec& spec, const fs::path& cache_dir,
                                           AssetsTimings* timings) {
  AssetsTimings t;
  auto a = std::make_shared<Assets>();
  a->spec_text = spec.yaml();

  // The cheap part, always computed: mean body and the garment dressed on it.
  auto start = Clock::now();
  const PluginDescriptor& bd = registry.get(spec.body_model);
  const auto body_model = registry.create_body(spec.body_model, Params(bd.params, values_of(spec.body_params, "assets body"),
                                                                       "body '" + spec.body_model + "'"));
  a->body.vertices = body_model->vertices(body_model->mean_shape());
  a->body.faces = body_model->faces();
  const PluginDescriptor& gd = registry.get(spec.garment);
  Garment garment = registry
                        .create_garment(spec.garment, Params(gd.params, values_of(spec.garment_params, "assets garment"),
                                                             "garment '" + spec.garment + "'"))
                        ->build();
  // Dressed as a scene dresses it: on the body it is cut for (fit_body.hpp),
  // the mean body a->body for the regular size.
  dress_on_fit_body(*body_model, garment, "the assets' garment '" + spec.garment + "'");
  a->garment = std::make_shared<const Garment>(std::move(garment));
  t.garment = since(start);
  const Mesh& gm = a->garment->mesh;

  // With an encoder body, everything a network's weights are tied to is that
  // body model's own assets': the correspondences (the encoder's points are
  // its vertices, resampled on this body), the hierarchy (its clusters and
  // per-edge weights follow the garment dressed on it) and the eigenbasis
  // (the spectral branch's coefficients are per eigenvector; on the garment
  // dressed on the human rig the vectors past the first few dozen are others,
  // or flipped, and a model started from the mannequin's weights kept a spike
  // at the underarm seam). So they are taken from those assets (built, or
  // read from their own cache), and every weight of a model of that body
  // model means here what it meant there (weight_ties.hpp). Losses,
  // templates and skinning keep the garment on this body (gm).
  std::shared_ptr<const Assets> encoder_assets;
  if (!spec.encoder_body.empty()) {
    AssetsSpec own = spec;
    own.body_model = spec.encoder_body;
    own.body_params = spec.encoder_body_params;
    own.encoder_body.clear();
    own.encoder_body_params.clear();
    AssetsTimings own_timings;
    encoder_assets = build_assets(registry, own, cache_dir, &own_timings);
    const double garment_time = t.garment;
    t = own_timings;  // its cache file, its load or its computation
    t.garment += garment_time;
    a->encoder_resampling = geometry::body_resampling(a->body, encoder_assets->body.vertices);
  }

  Fnv1a h;
  h.bytes(a->spec_text.data(), a->spec_text.size());
  h.matrix(a->body.vertices);
  h.matrix(a->body.faces);
  h.matrix(gm.vertices);
  h.matrix(gm.faces);
  h.matrix(gm.uv);
  h.matrix(gm.uv_faces);
  if (encoder_assets) h.bytes(encoder_assets->hash.data(), encoder_assets->hash.size());
  a->hash = h.hex();

  bool loaded = false;
  if (encoder_assets) {
    a->correspondence = encoder_assets->correspondence;
    a->hierarchy = encoder_assets->hierarchy;
    a->eigenvalues = encoder_assets->eigenvalues;
    a->eigenvectors = encoder_assets->eigenvectors;
    loaded = t.from_cache;
  } else {
    const fs::path cache_file = cache_dir.empty() ? fs::path() : cache_dir / ("assets-" + a->hash + ".h5");
    t.cache_file = cache_file;
    if (!cache_file.empty() && fs::exists(cache_file)) {
      start = Clock::now();
      try {
        assets_cache::load(cache_file, *a);
        loaded = true;
      } catch (const Error&) {
        loaded = false;  // unreadable or stale: rebuild and overwrite below
      }
      t.load = since(start);
    }
    if (!loaded) {
      start = Clock::now();
      a->correspondence = geometry::body_to_garment_correspondence(a->body, gm);
      t.correspondence = since(start);
      start = Clock::now();
      geometry::HierarchyOptions ho;
      ho.levels = spec.levels;
      a->hierarchy = geometry::build_hierarchy(gm, ho);
      t.hierarchy = since(start);
      start = Clock::now();
      const Eigenbasis basis = compute_eigenbasis(gm, std::min(spec.eigen_k, gm.num_vertices()));
      a->eigenvalues = basis.values;
      a->eigenvectors = basis.vectors.cast<float>();
      t.eigenbasis = since(start);
      if (!cache_file.empty()) {
        fs::create_directories(cache_dir);
        assets_cache::save(cache_file, *a);
      }
    }
  }
  t.from_cache = loaded;
  if (body_model->poseable()) {
    try {
      const Eigen::MatrixXd weights = body_model->skinning_weights();
      for (const PoseAngle& angle : body_model->pose_angles()) a->pose_angles.push_back(angle.name);
      a->garment_skinning = garment_skinning_weights(a->body, weights, gm).cast<float>();
    } catch (const ConfigError&) {
      a->pose_angles.clear();  // a model file without its rig (SMPL without pose data): unposed models only
    }
  }
  for (const auto& level : a->hierarchy.levels)
    a->laplacians.push_back(geometry::graph_laplacian(level.mesh.faces, level.mesh.num_vertices()).cast<float>());
  if (timings) *timings = t;
  return a;
}

}  // namespace drape
