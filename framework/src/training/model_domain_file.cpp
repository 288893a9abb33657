// Recording a model's domain in its file (model_domain.hpp).
#include <drape/bodies/body.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/errors.hpp>
#include <drape/io/h5.hpp>
#include <drape/training/model.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/training/optimizer.hpp>

namespace fs = std::filesystem;

namespace drape {

namespace {

// The checkpoint `from` (its non-weight part `c` already read) written anew
// to `to` in the current format (sealed, fixed-length strings), whatever
// format it was written in.
void rewrite_checkpoint(const fs::path& from, const Checkpoint& c, const fs::path& to) {
  const h5::File source = h5::File::open(from);
  const std::vector<std::string> names = source.datasets_below("/weights");
  std::vector<Weight> weights(names.size());
  NamedWeights named;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const h5::Dims shape = source.shape("/weights/" + names[i]);
    if (shape.size() != 2) throw ConfigError(from.string() + ": weight " + names[i] + " is not a matrix");
    weights[i].value = Tensor(1, static_cast<int>(shape[0]), static_cast<int>(shape[1]));
    source.read("/weights/" + names[i], shape, weights[i].value.data());
    named.emplace_back(names[i], &weights[i]);
  }
  save_checkpoint(to, named, c);
}

}  // namespace

ModelDomain record_model_domain(const Registry& registry, const fs::path& model_file, const fs::path& data_file,
                                const fs::path& out, double train_fraction) {
  // Only the body model is needed, not the garment's assets or the graph.
  const Checkpoint checkpoint = read_checkpoint(model_file);
  const auto assets = checkpoint.meta.find("assets");
  if (assets == checkpoint.meta.end())
    throw ConfigError(model_file.string() + ": not a drape model (no meta 'assets' naming its body model)");
  const AssetsSpec spec = parse_assets_spec(assets->second, model_file.string() + " meta 'assets'");
  const std::unique_ptr<BodyModel> body = make_body_model(registry, spec);
  const DatasetReader data(data_file);
  if (data.layout().body_vertices != body->num_vertices())
    throw ConfigError(data_file.string() + ": its bodies have " + std::to_string(data.layout().body_vertices) +
                      " vertices; the model's body model has " + std::to_string(body->num_vertices()));
  ModelDomain d = domain_of_dataset(data, spec.body_model, body->shape_names(), body->faces(), train_fraction);
  d.source = dataset_name(data_file);
  write_atomically(out, [&](const fs::path& tmp) {
    rewrite_checkpoint(model_file, checkpoint, tmp);
    h5::File f = h5::File::open(tmp, h5::Access::ReadWrite);
    write_domain(f, d);
    f.close();
  });
  return d;
}

void save_model_file(const fs::path& path, const NamedWeights& weights, const Checkpoint& checkpoint,
                     const std::optional<ModelDomain>& domain) {
  write_atomically(path, [&](const fs::path& tmp) {
    save_checkpoint(tmp, weights, checkpoint);
    if (!domain) return;
    h5::File f = h5::File::open(tmp, h5::Access::ReadWrite);
    write_domain(f, *domain);
    f.close();
  });
}

}  // namespace drape
