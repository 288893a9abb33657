// unpose_dataset (services/dataset_unposing.hpp).
#include <drape/assets/assets.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/errors.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/dataset_copy.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/dataset_unposing.hpp>
#include <drape/training/model.hpp>

#include <map>
#include <string>
#include <vector>

namespace drape {

std::size_t unpose_dataset(const Registry& registry, const std::filesystem::path& in, const std::filesystem::path& out,
                           const std::function<void()>& done) {
  const DatasetReader reader(in);
  const DatasetLayout& have = reader.layout();
  if (have.pose_angles.empty())
    throw ConfigError(in.string() + ": holds A-pose bodies (no /bodies/pose): there is nothing to unpose");
  const Scene scene = parse_scene(have.scene, in.string() + " (its stored scene)");
  // The skin node's weights: those of the template a model of these drapes is built on.
  const auto assets = build_assets(registry, assets_spec_for(scene, 1, 1));
  if (assets->garment_skinning.size() == 0)
    throw ConfigError(in.string() + ": its body model '" + scene.body_model + "' gives no skinning weights");
  const Eigen::MatrixXd weights = assets->garment_skinning.cast<double>();

  const std::vector<std::size_t> rows = reader.indices();
  DatasetLayout layout = have;
  layout.samples = rows.size();
  layout.pose_angles.clear();
  layout.body_vertices_stored = true;
  layout.created.clear();
  for (const std::string& a : have.pose_angles) layout.stats.push_back("pose_" + a);
  layout.attributes["unposed"] =
      "drape dataset unpose of " + in.filename().string() +
      ": garments and bodies in each body's rest pose (the skin node's weights inverted); the sample's joint angles "
      "are the statistics pose_<name>, degrees";
  DatasetWriter writer(out, layout);
  copy_done_samples(
      reader, writer,
      [&](const std::vector<std::size_t>& slice, std::vector<DatasetSample>& samples) {
        // The rest bodies and transforms once per slice (the reader keeps each body's posing once).
        const DatasetReader::Posing posing = reader.posing(slice);
        const Tensor angles = reader.poses(slice);
        for (std::size_t k = 0; k < slice.size(); ++k) {
          const int i = static_cast<int>(k);
          DatasetSample& s = samples[k];
          s.body_vertices = posing.unposed.mat(i);
          s.garment_vertices =
              unpose_garment(s.garment_vertices.cast<double>(), weights, transforms_of_rows(posing.transforms, i))
                  .cast<float>();
          for (std::size_t a = 0; a < have.pose_angles.size(); ++a)
            s.stats["pose_" + have.pose_angles[a]] = static_cast<double>(angles(i, 0, static_cast<int>(a)));
        }
      },
      done);
  writer.finish();
  return rows.size();
}

}  // namespace drape
