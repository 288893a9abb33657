// assets_for_dataset and check_dataset_template (assets/dataset_assets.hpp).
#include <drape/assets/dataset_assets.hpp>
#include <drape/errors.hpp>
#include <drape/io/dataset.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/training/model.hpp>

namespace fs = std::filesystem;

namespace drape {

std::shared_ptr<const Assets> assets_for_dataset(const Registry& registry, const DatasetReader& reader,
                                                 const fs::path& data, int eigen_k, const fs::path& cache_dir,
                                                 AssetsSpec* spec, const std::string& encoder_body) {
  const DatasetLayout& layout = reader.layout();
  Scene scene = parse_scene(layout.scene, data.string() + " (scene attribute)");
  // Drapes in each body's own size share the design size's template.
  if (garment_size_is_auto(scene)) scene = with_garment_size(scene, default_garment_size(registry, scene));
  AssetsSpec assets_spec = assets_spec_for(scene, eigen_k);
  assets_spec.encoder_body = encoder_body;
  auto assets = build_assets(registry, assets_spec, cache_dir);
  check_dataset_template(reader, data, *assets);
  if (spec) *spec = assets_spec;
  return assets;
}

void check_dataset_template(const DatasetReader& reader, const fs::path& data, const Assets& assets) {
  const DatasetLayout& layout = reader.layout();
  const int ng = assets.garment->mesh.num_vertices(), nb = assets.body.num_vertices();
  if (layout.garment_vertices != ng || layout.body_vertices != nb)
    throw ConfigError(data.string() + " has " + std::to_string(layout.garment_vertices) + " garment and " +
                      std::to_string(layout.body_vertices) + " body vertices per sample, but the template has " +
                      std::to_string(ng) + " and " + std::to_string(nb) +
                      (layout.body_vertices != nb
                           ? " (bodies of another rig or body model: give a model or scene of the dataset's; the "
                             "shipped models of each rig are listed in docs/bodies.md)"
                           : ""));
  const std::string hash = template_hash(assets.garment->mesh, assets.body.faces);
  if (!layout.template_hash.empty() && layout.template_hash != hash)
    throw ConfigError(data.string() + ": made for template " + layout.template_hash + ", but the template here is " +
                      hash + " (another garment, size or resolution, or the plugin changed: regenerate the dataset)");
}

}  // namespace drape
