#pragma once
// Helpers shared by the tests: the build tree's plugins, temporary folders,
// the optional shared assets, the drape program.
#include <drape/bodies/body.hpp>
#include <drape/mesh.hpp>
#include <drape/registry.hpp>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace drape::test {

// A registry holding every plugin of the build tree (loaded once).
const Registry& plugins();
// The parametric body model with its default parameters, or with those of a
// YAML map ("{rig: human}").
std::unique_ptr<BodyModel> parametric_body(const std::string& params_yaml = "{}");
// A body model without a skeleton (one triangle, no shape parameters): what a
// pose must be refused by.
std::unique_ptr<BodyModel> skeletonless_body();

// An open tube of `around` x `up` quads about the y axis (a skirt, a sleeve of
// a body): radius r, from y0 to y1. Its UVs are its unrolled pattern in
// metres times `pattern` (1: the cloth as long as the tube), the seam column
// with UVs of its own (a pattern edge sewn to the other).
Mesh pattern_tube(double r, double y0, double y1, int around, int up, double pattern = 1.0);

// A fresh empty directory under the system temp dir, removed at exit of the scope.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// ../shared/assets next to the source tree, or empty when absent.
std::filesystem::path shared_assets();
// The build's folders (test_paths.cpp, generated): the source tree, the build
// tree, the build tree's plugin folder, and where ../shared/assets would be.
std::filesystem::path source_dir();
std::filesystem::path binary_dir();
std::filesystem::path plugin_dir();
std::filesystem::path shared_assets_candidate();
std::filesystem::path drape_program();

// A file's bytes ("" when it cannot be read).
std::string read_file(const std::filesystem::path& path);

// The message of the exception fn throws, or "(no exception)".
std::string message_of(const std::function<void()>& fn);

// A scene that simulates in a fraction of a second: a ~300-vertex T-shirt,
// every effect, a few steps -- for tests that need real drapes (generate,
// experiments, benchmarks), not good ones.
const char* tiny_simulation_scene();
// The same on the parametric body's human rig (the shipped default models' body).
std::string tiny_human_simulation_scene();

// A shell prefix that runs the drape program from the source folder (where
// models/ and datasets/ are found), DRAPE_MODEL unset and its cache in `cache`.
std::string drape_in_source(const std::filesystem::path& cache);

// The commands that take a body mesh (append " --body FILE"): simulate (the
// tiny scene, written into `dir`), predict, render and optimize, with the
// mannequin's model, each writing into `dir`. For tests that a bad body is
// refused by every one of them.
std::vector<std::string> body_mesh_commands(const std::filesystem::path& dir);

// A latitude-longitude sphere about the origin (poles on Y),
// counter-clockwise seen from outside.
Mesh uv_sphere(double radius, int rings, int segments);

// The most strained edge of x (each face's three edges) against the lengths
// of the same edges in the UVs of `pattern` (a garment of x's topology: the
// template, or the size a body wore), 100 (l / rest - 1): strain_max's
// definition written out here, apart from the metric.
double strain_by_hand(const Mesh& pattern, const Eigen::MatrixX3d& x);

// Runs a shell command, returns its exit code; stdout+stderr go to `output`.
int run(const std::string& command, std::string& output);
// run() on the drape program with these arguments.
int run_drape(const std::string& args, std::string& output);

}  // namespace drape::test
