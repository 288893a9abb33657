#pragma once
// Tiny learnable datasets for the training tests, written with DatasetWriter:
// a ~300-vertex T-shirt on the parametric body. Sample i has a size a_i; its
// body is the mean body grown by a_i about its centroid and its garment the
// template grown by 1.2 a_i about the same point plus a sideways sway of
// 0.5 a_i^2 -- a smooth function of the body that a network can learn.
#include <drape/assets/assets.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/h5.hpp>
#include <drape/training/model.hpp>
#include <drape/training/rng.hpp>
#include <drape/training/trainer.hpp>

#include <fstream>
#include <map>
#include <vector>
#include <string>

#include "test_support.hpp"

namespace drape::test {

inline const char* tiny_scene() {
  return "description: tiny training scene\n"
         "body: {model: parametric}\n"
         "garment: {template: tshirt, params: {resolution: 300}}\n"
         "effects: [gravity, stretching, bending]\n";
}

// One assets cache for the whole test program (the 300-vertex template builds in well under a second).
inline const std::filesystem::path& assets_cache() {
  static TempDir dir;
  return dir.path();
}

inline constexpr int kTinyK = 16;

inline std::shared_ptr<const Assets> tiny_assets() {
  static const auto assets = build_assets(plugins(), assets_spec_for(parse_scene(tiny_scene()), kTinyK), assets_cache());
  return assets;
}

// n samples: the first n_train train, the next n_val validation, the rest test.
inline void write_tiny_dataset(const std::filesystem::path& file, int n, int n_train, int n_val, std::uint64_t seed = 3) {
  const auto assets = tiny_assets();
  const Eigen::MatrixX3d& body = assets->body.vertices;
  const Eigen::MatrixX3d& garment = assets->garment->mesh.vertices;
  const Eigen::RowVector3d centre = body.colwise().mean();
  DatasetLayout layout;
  layout.samples = static_cast<std::size_t>(n);
  const Eigen::VectorXd mean_shape = make_body_model(plugins(), assets_spec_for(parse_scene(tiny_scene()), kTinyK))->mean_shape();
  layout.body_params = static_cast<int>(mean_shape.size());
  layout.body_vertices = assets->body.num_vertices();
  layout.garment_vertices = assets->garment->mesh.num_vertices();
  layout.scene = parse_scene(tiny_scene()).yaml();
  layout.template_hash = template_hash(assets->garment->mesh, assets->body.faces);
  layout.stats = {"bmi"};  // a stand-in that grows with the body, for eval's --by and --svg
  DatasetWriter writer(file, layout);
  Rng rng(seed);
  for (int i = 0; i < n; ++i) {
    const double a = rng.uniform(0.0, 0.2);
    DatasetSample s;
    s.body_params = mean_shape.cast<float>();
    s.body_params[0] += float(a);
    s.body_vertices = (centre.replicate(body.rows(), 1) + (1.0 + a) * (body.rowwise() - centre)).cast<float>();
    Eigen::MatrixX3d g = centre.replicate(garment.rows(), 1) + (1.0 + 1.2 * a) * (garment.rowwise() - centre);
    g.col(0).array() += 0.5 * a * a;
    s.garment_vertices = g.cast<float>();
    s.split = i < n_train ? Split::Train : i < n_train + n_val ? Split::Val : Split::Test;
    s.stats["bmi"] = 20.0 + 100.0 * a;
    writer.write(static_cast<std::size_t>(i), s);
  }
  writer.finish();
}

// Drapes as drape optimize --data writes them, made from the samples `sources`
// of `truth`: each garment the source's moved by shift[i] along x (so its ME is
// 100 shift[i] cm), its body the source's (the next sample's for row
// `other_body`), statistics source_index and separated (1 unless given).
inline void write_shifted_drapes(const std::filesystem::path& file, const DatasetReader& truth,
                                 const std::vector<std::size_t>& sources, const std::vector<double>& shift,
                                 int other_body = -1, const std::vector<double>& separated = {}) {
  DatasetLayout layout = truth.layout();
  layout.samples = sources.size();
  layout.created.clear();
  layout.stats = {"source_index", "separated"};
  DatasetWriter writer(file, layout);
  for (std::size_t i = 0; i < sources.size(); ++i) {
    DatasetSample s = truth.sample(sources[i]);
    s.garment_vertices.col(0).array() += float(shift[i]);
    if (int(i) == other_body) s.body_vertices = truth.sample(sources[i] + 1).body_vertices;
    s.stats = {{"source_index", double(sources[i])}, {"separated", separated.empty() ? 1.0 : separated[i]}};
    writer.write(i, s);
  }
  writer.finish();
}

inline std::filesystem::path baseline_graph() { return source_dir() / "graphs/examples/mlp_baseline.yaml"; }

inline TrainOptions tiny_training(const std::filesystem::path& data, const std::filesystem::path& out) {
  TrainOptions o;
  o.graph = baseline_graph();
  o.data = data;
  o.out = out;
  o.epochs = 6;
  o.batch = 4;
  o.lr = 3e-3;
  o.seed = 5;
  o.threads = 2;
  o.eigen_k = kTinyK;
  o.cache_dir = assets_cache();
  o.assets = tiny_assets();
  return o;
}

// Every /weights array of a checkpoint, by name.
inline std::map<std::string, std::vector<float>> weights_of(const std::filesystem::path& file) {
  const h5::File f = h5::File::open(file);
  std::map<std::string, std::vector<float>> out;
  for (const auto& name : f.datasets_below("/weights")) out[name] = f.read<float>("/weights/" + name);
  return out;
}

// The drape program with the test's assets cache.
inline std::string drape_command(const std::string& args) {
  return "env DRAPE_CACHE_DIR=" + assets_cache().string() + " " + drape_program().string() + " " + args;
}

}  // namespace drape::test
