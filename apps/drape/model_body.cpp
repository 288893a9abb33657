#include "model_body.hpp"

#include <drape/mesh_io.hpp>

namespace drape::cli {

SampleBatch model_body(const Model& model, const po::variables_map& vm) {
  SampleBatch batch;
  if (vm.count("body")) {
    const std::string file = vm["body"].as<std::string>();
    const Mesh given = read_mesh(file);
    require_vertex_count(given, model.assets().body.num_vertices(), file,
                         "the model's body model '" + model.assets_spec().body_model + "' has that many");
    if (model.needs_body_params())
      throw ConfigError("this model's graph takes the body parameters (input body_params), which a mesh does not "
                        "give: use --bmi");
    batch.body = Tensor(1, given.num_vertices(), 3);
    batch.body.mat(0) = given.vertices.cast<float>();
    return batch;
  }
  BodyRequest request;
  request.bmi = vm["bmi"].as<double>();
  if (vm.count("height")) request.height = vm["height"].as<double>();
  if (vm.count("sex")) request.sex = vm["sex"].as<double>();
  return model.body_for(request);
}

}  // namespace drape::cli
