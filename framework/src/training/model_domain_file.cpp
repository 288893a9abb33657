// Recording a model's domain in its file (model_domain.hpp).
#include <drape/atomic_file.hpp>
#include <drape/checkpoint.hpp>
#include <drape/errors.hpp>
#include <drape/h5.hpp>
#include <drape/model.hpp>
#include <drape/model_domain.hpp>
#include <drape/optimizer.hpp>

namespace fs = std::filesystem;

namespace drape {

namespace {

// The checkpoint `from` written anew to `to` in the current format (sealed,
// fixed-length strings), whatever format it was written in.
void rewrite_checkpoint(const fs::path& from, const fs::path& to) {
  const Checkpoint c = read_checkpoint(from);
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
                                const fs::path& out) {
  const Model model = Model::load(registry, model_file);
  const DatasetReader data(data_file);
  if (data.layout().body_vertices != model.assets().body.num_vertices())
    throw ConfigError(data_file.string() + ": its bodies have " + std::to_string(data.layout().body_vertices) +
                      " vertices; the model's body model has " + std::to_string(model.assets().body.num_vertices()));
  ModelDomain d = domain_of_dataset(data, model.assets_spec().body_model, model.body_model().shape_names(),
                                    model.assets().body.faces);
  d.source = data_file.filename().string();
  write_atomically(out, [&](const fs::path& tmp) {
    rewrite_checkpoint(model_file, tmp);
    h5::File f = h5::File::open(tmp, h5::Access::ReadWrite);
    write_domain(f, d);
    f.close();
  });
  return d;
}

}  // namespace drape
