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

}  // namespace drape
