#include "test_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <random>
#include <sys/wait.h>

#include <yaml-cpp/yaml.h>

namespace fs = std::filesystem;

namespace drape::test {

const Registry& plugins() {
  static Registry* r = [] {
    auto* reg = new Registry;  // kept for the whole run: plugin code must stay loaded
    reg->load_path({plugin_dir().string()});
    return reg;
  }();
  return *r;
}

std::unique_ptr<BodyModel> parametric_body(const std::string& params_yaml) {
  const PluginDescriptor& d = plugins().get("parametric");
  return plugins().create_body("parametric",
                               Params(d.params, param_values_from_yaml(YAML::Load(params_yaml), "test"), "body parametric"));
}

Mesh pattern_tube(double r, double y0, double y1, int around, int up, double pattern) {
  Mesh m;
  m.vertices.resize(around * (up + 1), 3);
  for (int j = 0; j <= up; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * i / around;
      m.vertices.row(j * around + i) << r * std::sin(a), y0 + (y1 - y0) * j / up, r * std::cos(a);
    }
  m.uv.resize((around + 1) * (up + 1), 2);
  for (int j = 0; j <= up; ++j)
    for (int i = 0; i <= around; ++i)
      m.uv.row(j * (around + 1) + i) << pattern * 2 * M_PI * r * i / around, pattern * (y1 - y0) * j / up;
  m.faces.resize(2 * around * up, 3);
  m.uv_faces.resize(2 * around * up, 3);
  int f = 0;
  for (int j = 0; j < up; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      const int ta = j * (around + 1) + i, tb = ta + 1, tc = ta + around + 1, td = tb + around + 1;
      m.faces.row(f) << a, b, d;
      m.uv_faces.row(f++) << ta, tb, td;
      m.faces.row(f) << a, d, c;
      m.uv_faces.row(f++) << ta, td, tc;
    }
  return m;
}

std::unique_ptr<BodyModel> skeletonless_body() {
  struct Rigid final : BodyModel {
    Eigen::MatrixX3i f = Eigen::MatrixX3i::Zero(1, 3);
    int num_vertices() const override { return 3; }
    const Eigen::MatrixX3i& faces() const override { return f; }
    std::vector<std::string> shape_names() const override { return {}; }
    Eigen::VectorXd mean_shape() const override { return {}; }
    Eigen::MatrixX3d vertices(const Eigen::VectorXd&) const override { return Eigen::MatrixX3d::Identity(3, 3); }
    Eigen::VectorXd solve(const BodyRequest&) const override { return {}; }
    std::pair<double, double> bmi_range() const override { return {10, 65}; }
  };
  return std::make_unique<Rigid>();
}

TempDir::TempDir() {
  std::random_device rd;
  path_ = fs::temp_directory_path() / ("drape-test-" + std::to_string(rd()) + std::to_string(rd()));
  fs::create_directories(path_);
}
TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

fs::path shared_assets() {
  const fs::path p = shared_assets_candidate();
  return fs::is_directory(p) ? fs::canonical(p) : fs::path();
}
fs::path drape_program() { return binary_dir() / "bin" / "drape"; }

std::string message_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

int run_drape(const std::string& args, std::string& output) { return run(drape_program().string() + " " + args, output); }

int run(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}

const char* tiny_simulation_scene() {
  return R"(body: {model: parametric}
garment: {template: tshirt, params: {resolution: 300}}
effects:
  gravity: {}
  stretching: {}
  bending: {}
  collision: {stiffness: 1.0e8, margin: 0.004}
solver: {morph_steps: 2, settle_steps: 3}
)";
}

std::string tiny_human_simulation_scene() {
  std::string scene = tiny_simulation_scene();
  const std::string body = "{model: parametric}";
  return scene.replace(scene.find(body), body.size(), "{model: parametric, params: {rig: human}}");
}

std::string drape_in_source(const std::filesystem::path& cache) {
  return "cd " + source_dir().string() + " && env -u DRAPE_MODEL DRAPE_CACHE_DIR=" + cache.string() + " " +
         drape_program().string();
}

std::vector<std::string> body_mesh_commands(const std::filesystem::path& dir) {
  std::ofstream(dir / "tiny.yaml") << tiny_simulation_scene();
  const std::string garment = " --out " + (dir / "g.obj").string();
  // The mannequin's model, as the tiny scene's body is the mannequin (the default model is the human rig's).
  const std::string model = " --model models/tshirt-coarse.h5";
  return {"simulate " + (dir / "tiny.yaml").string() + garment, "predict" + model + garment,
          "render" + model + " --out " + (dir / "r.html").string(),
          "optimize" + model + " --scene graphs/scenes/tshirt_coarse.yaml --iters 5" + garment};
}

Mesh uv_sphere(double radius, int rings, int segments) {
  Mesh m;
  m.vertices.resize(2 + (rings - 1) * segments, 3);
  m.vertices.row(0) << 0, radius, 0;
  m.vertices.row(1) << 0, -radius, 0;
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double th = M_PI * r / rings, ph = 2 * M_PI * s / segments;
      m.vertices.row(2 + (r - 1) * segments + s) << radius * std::sin(th) * std::cos(ph), radius * std::cos(th),
          -radius * std::sin(th) * std::sin(ph);
    }
  std::vector<Eigen::Vector3i> f;
  auto id = [&](int r, int s) { return 2 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    f.emplace_back(0, id(1, s), id(1, s + 1));
    f.emplace_back(1, id(rings - 1, s + 1), id(rings - 1, s));
    for (int r = 1; r + 1 < rings; ++r) {
      f.emplace_back(id(r, s), id(r + 1, s), id(r + 1, s + 1));
      f.emplace_back(id(r, s), id(r + 1, s + 1), id(r, s + 1));
    }
  }
  m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) m.faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return m;
}

double strain_by_hand(const Mesh& pattern, const Eigen::MatrixX3d& x) {
  double worst = -1.0;
  for (Eigen::Index f = 0; f < pattern.faces.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const double rest = (pattern.uv.row(pattern.uv_faces(f, j)) - pattern.uv.row(pattern.uv_faces(f, (j + 1) % 3))).norm();
      worst = std::max(worst, (x.row(pattern.faces(f, j)) - x.row(pattern.faces(f, (j + 1) % 3))).norm() / rest - 1.0);
    }
  return 100.0 * worst;
}

}  // namespace drape::test
