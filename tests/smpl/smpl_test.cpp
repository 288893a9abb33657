// The SMPL body plugin on a small synthetic model file written by the test.
#include <drape/bodies/body.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/io/h5.hpp>

#include <catch2/catch.hpp>

#include <cmath>

#include "test_support.hpp"

using namespace drape;

namespace {

// A closed latitude-longitude ellipsoid standing on y = 0: 0.35 x 1.7 x 0.25 m.
void write_model(const std::filesystem::path& file) {
  const int rings = 24, segments = 32;
  std::vector<double> v;
  v.insert(v.end(), {0.0, 1.7, 0.0});  // top pole
  for (int r = 1; r < rings; ++r) {
    const double phi = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double theta = 2 * M_PI * s / segments;
      v.insert(v.end(), {0.175 * std::sin(phi) * std::cos(theta), 0.85 + 0.85 * std::cos(phi), 0.125 * std::sin(phi) * std::sin(theta)});
    }
  }
  v.insert(v.end(), {0.0, 0.0, 0.0});  // bottom pole
  const int n = static_cast<int>(v.size() / 3), bottom = n - 1;
  std::vector<std::int32_t> f;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) f.insert(f.end(), {0, ring(1, s + 1), ring(1, s)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      f.insert(f.end(), {ring(r, s), ring(r, s + 1), ring(r + 1, s)});
      f.insert(f.end(), {ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s)});
    }
  for (int s = 0; s < segments; ++s) f.insert(f.end(), {bottom, ring(rings - 1, s), ring(rings - 1, s + 1)});
  // Two blend shapes: beta0 widens in x and z (girth), beta1 is a sideways shear (no volume change).
  std::vector<float> dirs(static_cast<std::size_t>(n) * 3 * 2, 0.0f);
  for (int i = 0; i < n; ++i) {
    dirs[static_cast<std::size_t>((i * 3 + 0) * 2 + 0)] = static_cast<float>(0.1 * v[static_cast<std::size_t>(3 * i)]);
    dirs[static_cast<std::size_t>((i * 3 + 2) * 2 + 0)] = static_cast<float>(0.1 * v[static_cast<std::size_t>(3 * i + 2)]);
    dirs[static_cast<std::size_t>((i * 3 + 0) * 2 + 1)] = static_cast<float>(0.02 * v[static_cast<std::size_t>(3 * i + 1)]);
  }
  h5::File h = h5::File::create(file);
  h.write("/v_template", {static_cast<std::size_t>(n), 3}, v.data());
  h.write("/shapedirs", {static_cast<std::size_t>(n), 3, 2}, dirs.data());
  h.write("/f", {f.size() / 3, 3}, f.data());
  h.close();
}

std::unique_ptr<BodyModel> load(const std::filesystem::path& file) {
  const auto& d = test::plugins().get("smpl");
  return test::plugins().create_body("smpl", Params(d.params, {{"file", {YAML::Node(file.string()), {}}}}, "smpl"));
}

}  // namespace

TEST_CASE("the SMPL plugin applies shape blend shapes and solves BMI and height", "[smpl]") {
  test::TempDir dir;
  write_model(dir / "model.h5");
  const auto body = load(dir / "model.h5");
  CHECK(body->shape_names() == std::vector<std::string>{"beta0", "beta1", "scale"});
  const Eigen::MatrixX3d mean = body->vertices(body->mean_shape());
  CHECK(mean.rows() == body->num_vertices());
  CHECK(mean.col(1).maxCoeff() == Approx(1.7));
  // beta0 = 1 widens x by 10%.
  Eigen::VectorXd wide = body->mean_shape();
  wide[0] = 1.0;
  CHECK(body->vertices(wide).col(0).maxCoeff() == Approx(0.175 * 1.1).epsilon(1e-6));
  const auto [lo, hi] = body->bmi_range();
  REQUIRE(lo < hi);
  const double target = 0.5 * (lo + hi);
  const Eigen::VectorXd s = body->solve({target, 1.60, 1.0});
  const Eigen::MatrixX3d v = body->vertices(s);
  const double h = v.col(1).maxCoeff() - v.col(1).minCoeff();
  CHECK(h == Approx(1.60).epsilon(1e-9));
  CHECK(geometry::mesh_volume(v, body->faces()) * 985.0 / (h * h) == Approx(target).margin(0.01));
  // The shear beta does not change the volume, so the solve does not use it.
  CHECK(std::abs(s[1]) < 1e-3 * std::abs(s[0]) + 1e-9);
  CHECK_THROWS_WITH(body->solve({hi + 5, 1.60, 1.0}), Catch::Contains("outside"));
  CHECK_THROWS_AS(body->vertices(Eigen::VectorXd::Zero(2)), ConfigError);
}

TEST_CASE("a missing or malformed SMPL file is a clear error", "[smpl]") {
  test::TempDir dir;
  CHECK_THROWS_WITH(load(dir / "absent.h5"), Catch::Contains("absent.h5"));
  h5::File h = h5::File::create(dir / "bad.h5");
  const std::vector<double> v(9, 0.0);
  h.write("/v_template", {3, 3}, v.data());
  h.close();
  CHECK_THROWS_WITH(load(dir / "bad.h5"), Catch::Contains("shapedirs"));
}
