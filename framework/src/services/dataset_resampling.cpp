// resample_dataset (services/dataset_resampling.hpp).
#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/body_resampling.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/dataset_copy.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/dataset_resampling.hpp>
#include <drape/training/model.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace drape {

namespace {

double quantile(Eigen::VectorXd v, double q) {
  std::sort(v.data(), v.data() + v.size());
  return v[static_cast<Eigen::Index>(q * static_cast<double>(v.size() - 1))];
}

std::string millimetres(double metres) {
  std::ostringstream s;
  s.precision(3);
  s << metres * 1000.0 << " mm";
  return s.str();
}

}  // namespace

ResampleSummary resample_dataset(const Registry& registry, const std::filesystem::path& in,
                                 const std::filesystem::path& onto, const std::filesystem::path& out,
                                 const std::function<void()>& done) {
  const DatasetReader reader(in);
  const DatasetLayout& have = reader.layout();
  if (!have.pose_angles.empty())
    throw ConfigError(in.string() + ": holds posed bodies; resampling reads A-pose bodies only (the target template "
                                    "is in its A-pose)");
  const Scene source_scene = parse_scene(have.scene, in.string() + " (its stored scene)");
  const Scene target_scene = load_scene(onto);
  // Only the template meshes are needed: no eigenbasis, one hierarchy level.
  const auto source = build_assets(registry, assets_spec_for(source_scene, 1, 1));
  const auto target = build_assets(registry, assets_spec_for(target_scene, 1, 1));
  if (target->garment->mesh.vertices.rows() != have.garment_vertices)
    throw ConfigError(onto.string() + ": its garment has " + std::to_string(target->garment->mesh.vertices.rows()) +
                      " vertices, the drapes of " + in.string() + " " + std::to_string(have.garment_vertices) +
                      ": resampling carries bodies, not garments, so both scenes must drape the same garment");
  if (source->body.vertices.rows() != have.body_vertices)
    throw ConfigError(in.string() + ": its bodies have " + std::to_string(have.body_vertices) +
                      " vertices, the template of its stored scene " + std::to_string(source->body.vertices.rows()));
  const geometry::BodyResampling map = geometry::body_resampling(source->body, target->body.vertices);
  const Eigen::VectorXd gap = (map.resampled_template - target->body.vertices).rowwise().norm();

  ResampleSummary summary;
  summary.source_vertices = map.source_vertices;
  summary.target_vertices = static_cast<int>(target->body.vertices.rows());
  summary.median_distance = quantile(gap, 0.5);
  summary.p90_distance = quantile(gap, 0.9);
  summary.max_distance = gap.maxCoeff();

  const std::vector<std::size_t> rows = reader.indices();
  DatasetLayout layout = have;
  layout.samples = rows.size();
  layout.body_vertices = summary.target_vertices;
  layout.body_vertices_stored = true;
  layout.created.clear();
  layout.scene = target_scene.yaml();
  layout.template_hash = template_hash(target->garment->mesh, target->body.faces);
  layout.attributes["source_scene"] = have.scene;
  layout.attributes["resampled_from"] =
      "drape dataset resample of " + in.filename().string() + " onto " + onto.filename().string() +
      ": drapes simulated on the bodies of the scene in source_scene (" + std::to_string(summary.source_vertices) +
      " vertices), each body read at the closest points of the " + std::to_string(summary.target_vertices) +
      " template vertices of the scene in `scene` on the source template (median " +
      millimetres(summary.median_distance) + " away, 90 % within " + millimetres(summary.p90_distance) + ", at most " +
      millimetres(summary.max_distance) + "); garments as simulated";
  DatasetWriter writer(out, layout);
  copy_done_samples(
      reader, writer,
      [&](const std::vector<std::size_t>& slice, std::vector<DatasetSample>& samples) {
        const Tensor bodies = reader.body_vertices(slice);
        for (std::size_t k = 0; k < slice.size(); ++k)
          samples[k].body_vertices =
              map.apply(bodies.mat(static_cast<int>(k)).cast<double>(), in.string() + ": sample " + std::to_string(slice[k]))
                  .cast<float>();
      },
      done);
  writer.finish();
  summary.samples = rows.size();
  return summary;
}

}  // namespace drape
