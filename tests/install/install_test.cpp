// What a user of an installed drape does: install this build to a fresh prefix,
// build examples/wind_energy out of tree against it with find_package(drape),
// list it with the installed program, and load it and check its derivatives.
#include <catch2/catch.hpp>

#include <drape/energy.hpp>
#include <drape/gradcheck.hpp>
#include <drape/registry.hpp>

#include <cmath>
#include <filesystem>
#include <random>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string quote(const fs::path& p) { return "'" + p.string() + "'"; }

// A flat nx-by-ny grid of square cells of side h in material space (UV, meters),
// crumpled in 3D so that positions and UVs differ.
Garment uv_grid(int nx, int ny, double h) {
  Garment g;
  g.materials.resize(1);
  Mesh& m = g.mesh;
  const int cols = nx + 1;
  m.vertices.resize((nx + 1) * (ny + 1), 3);
  m.uv.resize(m.vertices.rows(), 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double u = i * h, v = j * h;
      m.uv.row(j * cols + i) << u, v;
      m.vertices.row(j * cols + i) << u + jitter(rng), 1.2 - v + jitter(rng), 0.05 * std::sin(20 * u) + jitter(rng);
    }
  m.faces.resize(2 * nx * ny, 3);
  for (int j = 0, f = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * cols + i, b = a + 1, c = a + cols, d = c + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
  m.uv_faces = m.faces;  // no seams: one UV per vertex
  return g;
}

Params wind_params(const PluginDescriptor& d, const std::string& yaml) {
  return Params(d.params, param_values_from_yaml(YAML::Load(yaml), "install_test"), d.name);
}

}  // namespace

TEST_CASE("an installed drape builds, lists and loads an out-of-tree energy plugin", "[install]") {
  test::TempDir tmp;  // declared first: removed only after the plugin is unloaded
  const fs::path prefix = tmp / "prefix";
  const fs::path example_build = tmp / "wind-build";
  const std::string cmake = quote(DRAPE_CMAKE_COMMAND);
  std::string out;

  // 1. Install.
  INFO("cmake --install");
  const int installed = test::run(cmake + " --install " + quote(test::binary_dir().string()) + " --prefix " + quote(prefix), out);
  INFO(out);
  REQUIRE(installed == 0);
  const fs::path libdir = prefix / DRAPE_INSTALL_LIBDIR;
  CHECK(fs::is_regular_file(prefix / DRAPE_INSTALL_BINDIR / "drape"));
  CHECK(fs::exists(libdir / "libdrape_framework.so"));
  CHECK(fs::is_regular_file(prefix / DRAPE_INSTALL_INCLUDEDIR / "drape" / "plugin.hpp"));
  CHECK(fs::is_regular_file(libdir / "cmake" / "drape" / "drapeConfig.cmake"));
  CHECK(fs::is_regular_file(libdir / "drape" / "plugins" / "libdrape_plugin_l2.so"));

  // 2. Build the example against the installed package only.
  const int configured = test::run(cmake + " -S " + quote(test::source_dir() / "examples" / "wind_energy") + " -B " +
                                       quote(example_build) + " -DCMAKE_PREFIX_PATH=" + quote(prefix) +
                                       " -DCMAKE_CXX_COMPILER=" + quote(DRAPE_CXX_COMPILER) + " -DCMAKE_BUILD_TYPE=Release",
                                   out);
  INFO(out);
  REQUIRE(configured == 0);
  const int built = test::run(cmake + " --build " + quote(example_build), out);
  INFO(out);
  REQUIRE(built == 0);
  const fs::path wind_file = fs::canonical(example_build / "libdrape_plugin_wind.so");

  // 3. The installed program finds its own plugins next to its library (not the
  // build tree's) plus the example through --plugin-path.
  const std::string drape = "env -u DRAPE_PLUGIN_PATH " + quote(prefix / DRAPE_INSTALL_BINDIR / "drape");
  const int listed = test::run(drape + " plugins --plugin-path " + quote(example_build), out);
  INFO(out);
  REQUIRE(listed == 0);
  CHECK_THAT(out, Catch::Contains("energy wind\n") && Catch::Contains("file: " + wind_file.string()) &&
                      Catch::Contains("param pressure") && Catch::Contains("param direction"));
  CHECK_THAT(out, Catch::Contains("loss l2\n") &&
                      Catch::Contains("file: " + fs::canonical(libdir / "drape" / "plugins" / "libdrape_plugin_l2.so").string()));
  CHECK(out.find(test::plugin_dir().string()) == std::string::npos);
  REQUIRE(test::run(drape + " plugins --kind energy --brief --plugin-path " + quote(example_build), out) == 0);
  out = "\n" + out;  // other energies (gravity) may sort before wind
  CHECK_THAT(out, Catch::Contains("\nenergy wind - "));
  CHECK(out.find("\nloss ") == std::string::npos);

  // Every plugin of the build tree was installed and loads from the prefix
  // (a plugin whose own libraries were not installed would be refused).
  REQUIRE(test::run(drape + " plugins --brief", out) == 0);
  out = "\n" + out;
  for (const PluginDescriptor* p : test::plugins().all())
    CHECK_THAT(out, Catch::Contains("\n" + p->kind + " " + p->name + " - "));
  std::size_t refused = 0;
  for (std::size_t at = out.find("\nrefused "); at != std::string::npos; at = out.find("\nrefused ", at + 1)) ++refused;
  CHECK(refused == test::plugins().refused().size());

  // 4. Load the built plugin here and check the physics.
  Registry registry;
  registry.load_file(wind_file);
  const PluginDescriptor& d = registry.get("wind");
  CHECK(d.kind == "energy");
  CHECK(d.file == wind_file.string());

  const int nx = 4, ny = 3;
  const double h = 0.1, pressure = 3.5;
  const Garment garment = uv_grid(nx, ny, h);
  EnergyContext context;
  context.garment = &garment;
  auto wind = registry.create_energy("wind", wind_params(d, "{direction: [1, 2, 2], pressure: 3.5}"));
  wind->bind(context);
  const Eigen::MatrixX3d& x = garment.mesh.vertices;

  const GradCheckReport report = check_energy_derivatives(*wind, x);
  INFO(report.str());
  CHECK(report.ok(1e-6));

  // The total force is pressure * material area along the unit direction,
  // however the cloth is crumpled.
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
  const double e = wind->add_gradient(x, g);
  CHECK(e == Approx(wind->value(x)));
  const Eigen::Vector3d force = -g.colwise().sum().transpose();
  const Eigen::Vector3d expected = pressure * (nx * h) * (ny * h) * Eigen::Vector3d(1, 2, 2) / 3.0;
  CHECK((force - expected).norm() < 1e-12 * expected.norm());
  // Moving the garment along the wind lowers the energy by force . shift.
  const Eigen::RowVector3d shift(0.3, -0.2, 0.5);
  CHECK(wind->value(x.rowwise() + shift) - wind->value(x) == Approx(-expected.dot(shift.transpose())));

  // Defaults: 1 Pa along +z.
  auto calm = registry.create_energy("wind", wind_params(d, "{}"));
  calm->bind(context);
  Eigen::MatrixX3d g0 = Eigen::MatrixX3d::Zero(x.rows(), 3);
  calm->add_gradient(x, g0);
  CHECK(-g0.col(2).sum() == Approx((nx * h) * (ny * h)));
  CHECK(g0.leftCols(2).cwiseAbs().maxCoeff() == 0.0);

  // Bad parameters and a garment without material space are one clear error each.
  CHECK_THROWS_WITH(registry.create_energy("wind", wind_params(d, "{direction: [0, 0, 0]}")),
                    Catch::Contains("direction"));
  CHECK_THROWS_WITH(registry.create_energy("wind", wind_params(d, "{direction: [1, 0]}")),
                    Catch::Contains("direction") && Catch::Contains("3"));
  CHECK_THROWS_AS(wind_params(d, "{pressure: -1.0}"), ConfigError);
  Garment no_uv = garment;
  no_uv.mesh.uv.resize(0, 2);
  no_uv.mesh.uv_faces.resize(0, 3);
  EnergyContext bad;
  bad.garment = &no_uv;
  CHECK_THROWS_AS(calm->bind(bad), ConfigError);
}
