// The bodies a slim dataset left out, rebuilt from their shape parameters by
// the body model of the dataset's stored scene (expand, and DatasetReader).
#include "dataset_internal.hpp"

#include <drape/bodies/body.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/training/model.hpp>

namespace drape::dataset_detail {

Pose pose_of_row(const std::vector<std::string>& angles, const float* row) {
  Pose pose;
  for (std::size_t a = 0; a < angles.size(); ++a) pose.angles[angles[a]] = static_cast<double>(row[a]);
  return pose;
}

std::vector<float> rebuilt_bodies(const BodyModel& body_model, const std::vector<float>& params, std::size_t count,
                                  std::size_t body_params, const std::vector<std::string>& angles,
                                  const std::vector<float>& poses, const std::function<void()>& rebuilt) {
  const std::size_t nb = static_cast<std::size_t>(body_model.num_vertices());
  std::vector<float> out(count * nb * 3);
  for (std::size_t r = 0; r < count; ++r) {
    const Eigen::VectorXd shape =
        Eigen::Map<const Eigen::VectorXf>(params.data() + r * body_params, static_cast<Eigen::Index>(body_params)).cast<double>();
    const Eigen::MatrixX3d unposed = body_model.vertices(shape);
    // The generator posed the body of these (float) parameters in these
    // (float) angles: the same call gives the same body.
    const Eigen::MatrixX3d v =
        angles.empty() ? unposed : body_model.posed_vertices(unposed, pose_of_row(angles, poses.data() + r * angles.size()), 1.0);
    for (std::size_t i = 0; i < nb; ++i)
      for (int c = 0; c < 3; ++c)
        out[(r * nb + i) * 3 + static_cast<std::size_t>(c)] = static_cast<float>(v(static_cast<Eigen::Index>(i), c));
    if (rebuilt) rebuilt();
  }
  return out;
}

std::unique_ptr<BodyModel> dataset_body_model(const BodyModel* given, const DatasetLayout& layout, const std::string& file) {
  std::unique_ptr<BodyModel> made;
  if (!given) {
    // The default registry: what the drape program loaded (with its --plugin-path), or the shipped plugins.
    const Scene scene = parse_scene(layout.scene, file + " (its stored scene)");
    made = make_body_model(Registry::load_default(), assets_spec_for(scene, 0));
    given = made.get();
  }
  if (given->num_vertices() != layout.body_vertices || static_cast<int>(given->mean_shape().size()) != layout.body_params)
    throw ConfigError(file + ": its bodies have " + std::to_string(layout.body_vertices) + " vertices and " +
                      std::to_string(layout.body_params) + " shape parameters; the body model has " +
                      std::to_string(given->num_vertices()) + " and " + std::to_string(given->mean_shape().size()) +
                      " (not the model that generated them)");
  return made;
}

}  // namespace drape::dataset_detail
