// `drape hierarchy`: the multi-resolution levels of a garment, with their sizes
// and triangle quality; optionally writes every level as a mesh to look at.
#include "command.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/hierarchy.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/io/write_failure.hpp>

#include <Eigen/Geometry>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

struct Quality {
  double mean_edge = 0, min = 1, mean = 0;
};

Quality quality(const Mesh& m) {
  Quality q;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                          c = m.vertices.row(m.faces(f, 2));
    const double sum = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    const double value = sum > 0 ? 2 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / sum : 0.0;
    q.min = std::min(q.min, value);
    q.mean += value / m.num_faces();
    q.mean_edge += ((b - a).norm() + (c - b).norm() + (a - c).norm()) / (3.0 * m.num_faces());
  }
  return q;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape hierarchy");
  opts.add_options()("mesh", po::value<std::string>()->required(), "the garment, with UVs")(
      "levels", po::value<int>()->default_value(4), "number of levels, the garment included")(
      "ratio", po::value<double>()->default_value(4.0), "vertex ratio between consecutive levels")(
      "out", po::value<std::string>(), "folder to write level<l>.obj into");
  po::variables_map vm;
  if (!parse("drape hierarchy --mesh garment.obj [--levels 4] [--ratio 4] [--out folder]", args, opts, {}, vm)) return 0;
  // The output folder checked before the work (a file there, or /proc, failed after it with a raw filesystem error).
  if (vm.count("out")) check_output_folder(vm["out"].as<std::string>(), "--out");
  const Mesh mesh = read_mesh(vm["mesh"].as<std::string>());
  geometry::HierarchyOptions options;
  options.levels = vm["levels"].as<int>();
  options.ratio = vm["ratio"].as<double>();
  const auto start = std::chrono::steady_clock::now();
  const geometry::Hierarchy h = geometry::build_hierarchy(mesh, options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("%5s %9s %9s %7s %7s %11s %12s %12s\n", "level", "vertices", "faces", "ratio", "charts", "mean edge",
              "min quality", "mean quality");
  for (int l = 0; l < h.num_levels(); ++l) {
    const Mesh& m = h.levels[l].mesh;
    const Eigen::VectorXi& fc = h.levels[l].face_chart;
    const int charts = static_cast<int>(std::set<int>(fc.data(), fc.data() + fc.size()).size());
    const Quality q = quality(m);
    const double ratio = l > 0 ? double(h.levels[l - 1].mesh.num_vertices()) / m.num_vertices() : 1.0;
    std::printf("%5d %9d %9d %7.2f %7d %11.4g %12.3f %12.3f\n", l, m.num_vertices(), m.num_faces(), ratio, charts,
                q.mean_edge, q.min, q.mean);
  }
  std::printf("built in %.3f s\n", seconds);
  // Levels that repeat the one before (ratio 1.00 each, without a word before).
  for (int l = 1; l < h.num_levels(); ++l)
    if (h.levels[l].mesh.num_vertices() == h.levels[l - 1].mesh.num_vertices()) {
      std::printf("note: levels %d to %d repeat level %d (%d vertices): the mesh coarsens no further; --levels %d\n", l,
                  h.num_levels() - 1, l - 1, h.levels[l - 1].mesh.num_vertices(), l);
      break;
    }
  if (vm.count("out")) {
    const std::filesystem::path out = vm["out"].as<std::string>();
    std::filesystem::create_directories(out);
    for (int l = 0; l < h.num_levels(); ++l) write_mesh(out / ("level" + std::to_string(l) + ".obj"), h.levels[l].mesh);
  }
  return 0;
}

const RegisterCommand registration{{"hierarchy", "multi-resolution levels of a garment (sizes, quality)", run}};

}  // namespace
}  // namespace drape::cli
