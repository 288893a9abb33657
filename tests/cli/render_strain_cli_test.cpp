// The strain of a garment file is measured against the file's own UVs (its
// material space): predict now writes the UVs of the size the body wears, as
// simulate does, and render --garment --colour strain reads them. An outside
// check found a drape simulated in size large shown 8 % strained (measured
// against the size the tailor's rule gives the body) and predicted OBJs of an
// xlarge shirt carrying the regular pattern (16 % strained by their own UVs).
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>

#include <fstream>
#include <regex>

#include "test_support.hpp"

using namespace drape;

namespace {

// Render's definition (docs): per vertex, the mean |length / rest - 1| of the
// face edges at it, in percent; the caption's mean is over the vertices.
double mean_vertex_strain_by_hand(const Mesh& pattern, const Eigen::MatrixX3d& x) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(x.rows()), count = sum;
  for (Eigen::Index f = 0; f < pattern.faces.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int a = pattern.faces(f, j), b = pattern.faces(f, (j + 1) % 3);
      const double rest = (pattern.uv.row(pattern.uv_faces(f, j)) - pattern.uv.row(pattern.uv_faces(f, (j + 1) % 3))).norm();
      const double s = 100.0 * std::abs((x.row(a) - x.row(b)).norm() / rest - 1.0);
      sum(a) += s, sum(b) += s, count(a) += 1, count(b) += 1;
    }
  return sum.cwiseQuotient(count.cwiseMax(1.0)).mean();
}

}  // namespace

TEST_CASE("predict writes the UVs of the size worn and render measures a garment file's strain against its own UVs",
          "[render][sizes]") {
  test::TempDir dir;
  const std::string body = (dir / "b.obj").string(), garment = (dir / "g.obj").string();
  std::string out;
  REQUIRE(test::run_drape("predict --bmi 45 --out " + garment + " --body-out " + body, out) == 0);
  INFO(out);
  std::smatch size;
  REQUIRE(std::regex_search(out, size, std::regex("size ([a-z0-9]+) by the tailor's rule")));
  REQUIRE(size[1] != "regular");  // the case the files got wrong
  REQUIRE(test::run_drape("predict --bmi 45 --garment-size regular --out " + (dir / "regular.obj").string(), out) == 0);
  const Mesh worn = read_mesh(garment), regular = read_mesh(dir / "regular.obj");
  REQUIRE(worn.has_uv());
  REQUIRE(regular.has_uv());
  // Against its own UVs the prediction is nearly at rest; against the regular
  // pattern the same vertices are strained several times more.
  const double own = mean_vertex_strain_by_hand(worn, worn.vertices);
  Mesh as_regular = worn;
  as_regular.uv = regular.uv, as_regular.uv_faces = regular.uv_faces;
  const double against_regular = mean_vertex_strain_by_hand(as_regular, worn.vertices);
  CHECK(own < 5.0);
  CHECK(against_regular > 2 * own);

  const std::string page = (dir / "s.html").string();
  REQUIRE(test::run_drape("render --body " + body + " --garment " + garment + " --colour strain --out " + page, out) == 0);
  CHECK_THAT(out, Catch::Contains("own UVs"));
  // Nothing is predicted: no word of the size a prediction would wear (an
  // outside check was told "the prediction may be wrong" of a simulated drape).
  CHECK_THAT(out, !Catch::Contains("by the tailor's rule") && !Catch::Contains("prediction"));
  std::smatch caption;
  REQUIRE(std::regex_search(out, caption, std::regex("mean strain ([0-9.]+)%")));
  CHECK(std::stod(caption[1]) == Approx(own).margin(0.006));
}

TEST_CASE("render refuses a garment file without faces or far from the body and an output under a file", "[render]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --bmi 30 --out " + (dir / "b.obj").string(), out) == 0);
  std::ofstream(dir / "points.obj") << "v 0 1 0\nv 0.1 1 0\nv 0 1.1 0\n";
  CHECK(test::run_drape("render --body " + (dir / "b.obj").string() + " --garment " + (dir / "points.obj").string() +
                            " --out " + (dir / "p.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("points.obj: has no faces"));
  CHECK_FALSE(std::filesystem::exists(dir / "p.html"));
  // A vertex at 1e39 m (infinite in the page's float32) drew a squashed picture, exit 0.
  std::ofstream(dir / "far.obj") << "v 0 1 0\nv 0.1 1 0\nv 1e39 1.1 0\nf 1 2 3\n";
  CHECK(test::run_drape("render --body " + (dir / "b.obj").string() + " --garment " + (dir / "far.obj").string() +
                            " --out " + (dir / "f.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("far.obj: vertex 2 lies 1e+39 m from the body's bounding box"));
  CHECK_FALSE(std::filesystem::exists(dir / "f.html"));
  CHECK(test::run_drape("render --bmi 30 --out " + (dir / "b.obj" / "x.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("b.obj' is a file, not a folder"));
}
