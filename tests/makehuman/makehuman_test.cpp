// The MakeHuman plugins on the CC0 data in ../shared/assets/makehuman; every
// test skips with a message when that folder is absent.
#include <drape/energy.hpp>
#include <drape/bodies/body.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/io/mesh_io.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

using namespace drape;

namespace {

bool assets_present() {
  if (!test::shared_assets().empty() && std::filesystem::exists(test::shared_assets() / "makehuman/base/base.obj")) return true;
  WARN("SKIPPED: ../shared/assets/makehuman is absent; the MakeHuman tests need it");
  return false;
}

ParamValues path_param() {
  return {{"path", {YAML::Node((test::shared_assets() / "makehuman").string()), {}}}};
}

std::unique_ptr<BodyModel> makehuman_body() {
  const auto& d = test::plugins().get("makehuman");
  return test::plugins().create_body("makehuman", Params(d.params, path_param(), "makehuman"));
}

double bmi_of(const Mesh& m) {
  const double h = m.vertices.col(1).maxCoeff() - m.vertices.col(1).minCoeff();
  return geometry::mesh_volume(m.vertices, m.faces) * 985.0 / (h * h);
}

}  // namespace

TEST_CASE("the MakeHuman body drops helpers, is in meters and hits a requested BMI", "[makehuman]") {
  if (!assets_present()) {
    SUCCEED("skipped");
    return;
  }
  const auto body = makehuman_body();
  CHECK(body->num_vertices() == 13380);  // the `body` group of hm08, helpers removed
  Mesh mean{body->vertices(body->mean_shape()), body->faces(), {}, {}};
  const double height = mean.vertices.col(1).maxCoeff() - mean.vertices.col(1).minCoeff();
  CHECK(height > 1.5);
  CHECK(height < 1.9);
  CHECK(mean.vertices.col(1).minCoeff() == Approx(0.0).margin(1e-9));
  const auto topo = geometry::check_topology(mean.faces, mean.num_vertices());
  INFO(topo.str());
  CHECK(topo.manifold());
  CHECK(geometry::mesh_volume(mean.vertices, mean.faces) > 0.03);  // a person is ~0.06-0.1 m^3

  const auto [lo, hi] = body->bmi_range();
  INFO("MakeHuman BMI range " << lo << " - " << hi);
  CHECK(lo < 16);
  CHECK(hi > 35);
  for (double target : {16.0, 22.0, 30.0, 35.0}) {
    const Eigen::VectorXd shape = body->solve({target, 1.75, 1.0, {}});
    Mesh m{body->vertices(shape), body->faces(), {}, {}};
    CHECK(bmi_of(m) == Approx(target).margin(0.5));
    CHECK(m.vertices.col(1).maxCoeff() - m.vertices.col(1).minCoeff() == Approx(1.75).margin(0.01));
  }
  CHECK_THROWS_WITH(body->solve({55.0, 1.75, 1.0, {}}), Catch::Contains("outside") && Catch::Contains("reaches BMI"));
}

TEST_CASE("a missing MakeHuman folder is a clear error", "[makehuman]") {
  const auto& d = test::plugins().get("makehuman");
  ParamValues bad{{"path", {YAML::Node("/nonexistent/makehuman"), {}}}};
  CHECK_THROWS_WITH(test::plugins().create_body("makehuman", Params(d.params, bad, "makehuman")),
                    Catch::Contains("/nonexistent/makehuman") && Catch::Contains("base.obj"));
}

namespace {

// The sliders of a heavy MakeHuman body (BMI 34, 1.75 m, male) as garment
// parameters on top of `values`, and that body's vertices.
struct HeavyBody {
  ParamValues values;
  Mesh mesh;
};
HeavyBody heavy_body(ParamValues values) {
  const auto body = makehuman_body();
  const Eigen::VectorXd heavy = body->solve({34.0, 1.75, 1.0, {}});
  const char* names[] = {"gender", "muscle", "weight", "height", "proportions"};
  for (int i = 0; i < 5; ++i) values[names[i]] = {YAML::Node(heavy[i]), {}};
  return {values, Mesh{body->vertices(heavy), body->faces(), {}, {}}};
}

// Garment vertices deeper than 5 mm inside the body.
int deeper_than_5mm(const Mesh& body, const Mesh& garment) {
  const geometry::BodySurface surface(body);
  int inside = 0;
  for (int v = 0; v < garment.num_vertices(); ++v)
    if (surface.closest(garment.vertices.row(v).transpose()).signed_distance < -0.005) ++inside;
  return inside;
}

// Front to back (the legs' spread sets the side to side extent in the A-pose).
double depth(const Mesh& m) { return m.vertices.col(2).maxCoeff() - m.vertices.col(2).minCoeff(); }

}  // namespace

TEST_CASE("the MakeHuman T-shirt loads, triangulates and dresses bodies through .mhclo", "[makehuman]") {
  if (!assets_present()) {
    SUCCEED("skipped");
    return;
  }
  const auto& d = test::plugins().get("makehuman_tshirt");
  for (const char* outfit : {"male_casualsuit04", "male_casualsuit06"}) {
    ParamValues values = path_param();
    values["outfit"] = {YAML::Node(outfit), {}};
    const Garment g = test::plugins().create_garment("makehuman_tshirt", Params(d.params, values, "shirt"))->build();
    INFO(outfit);
    CHECK(g.mesh.num_vertices() == (std::string(outfit) == "male_casualsuit04" ? 810 : 2822));
    CHECK(g.mesh.has_uv());
    const auto topo = geometry::check_topology(g.mesh.faces, g.mesh.num_vertices());
    INFO(topo.str());
    CHECK(topo.manifold());
    CHECK(topo.boundary_loops == 4);  // collar, two sleeves, hem
    // Material space in meters: the UV area is of the order of a shirt (~1 m^2).
    double uv_area = 0;
    for (int f = 0; f < g.mesh.num_faces(); ++f) {
      const Eigen::Vector2d a = g.mesh.uv.row(g.mesh.uv_faces(f, 0)), b = g.mesh.uv.row(g.mesh.uv_faces(f, 1)),
                            c = g.mesh.uv.row(g.mesh.uv_faces(f, 2));
      uv_area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    }
    CHECK(uv_area > 0.5);
    CHECK(uv_area < 2.0);
  }
  // Dressed on a heavy MakeHuman body, the shirt follows it: it widens, and few
  // vertices end up inside the body (MakeHuman's own binding, not a simulation).
  const HeavyBody heavy = heavy_body(path_param());
  const Garment thin_shirt = test::plugins().create_garment("makehuman_tshirt", Params(d.params, path_param(), "s"))->build();
  const Garment heavy_shirt = test::plugins().create_garment("makehuman_tshirt", Params(d.params, heavy.values, "s"))->build();
  CHECK(depth(heavy_shirt.mesh) > depth(thin_shirt.mesh) + 0.03);
  const int inside = deeper_than_5mm(heavy.mesh, heavy_shirt.mesh);
  INFO(inside << " of " << heavy_shirt.mesh.num_vertices() << " shirt vertices deeper than 5 mm in the body");
  CHECK(inside < heavy_shirt.mesh.num_vertices() / 20);
}

// Any piece of an outfit binds through the .mhclo: the trousers of
// male_casualsuit04 (piece 1, 886 vertices) follow a heavy body as the shirt
// does; a piece that does not exist, a group the .obj lacks and a binding made
// for another base mesh are refused naming the file.
TEST_CASE("MakeHuman clothes: any piece of an outfit binds to the body through its .mhclo", "[makehuman]") {
  if (!assets_present()) {
    SUCCEED("skipped");
    return;
  }
  const auto& d = test::plugins().get("makehuman_clothes");
  auto build = [&](ParamValues values) { return test::plugins().create_garment("makehuman_clothes", Params(d.params, values, "clothes"))->build(); };
  ParamValues values = path_param();
  // Piece 0 is the T-shirt piece: the same garment as makehuman_tshirt's.
  const Garment shirt = build(values);
  const auto& ds = test::plugins().get("makehuman_tshirt");
  const Garment tshirt = test::plugins().create_garment("makehuman_tshirt", Params(ds.params, path_param(), "s"))->build();
  CHECK(shirt.mesh.vertices == tshirt.mesh.vertices);
  CHECK(shirt.mesh.faces == tshirt.mesh.faces);
  values["piece"] = {YAML::Node("1"), {}};
  const Garment trousers = build(values);
  CHECK(trousers.mesh.num_vertices() == 886);
  CHECK(trousers.mesh.faces.maxCoeff() < trousers.mesh.num_vertices());
  CHECK(trousers.mesh.has_uv());
  // Below the shirt: trousers reach the ankles.
  CHECK(trousers.mesh.vertices.col(1).minCoeff() < 0.2);
  CHECK(trousers.mesh.vertices.col(1).maxCoeff() < shirt.mesh.vertices.col(1).maxCoeff());
  // They follow a heavy body: wider, and few vertices deeper than 5 mm inside it.
  const HeavyBody heavy = heavy_body(values);
  const Garment heavy_trousers = build(heavy.values);
  CHECK(depth(heavy_trousers.mesh) > depth(trousers.mesh) + 0.03);
  const int inside = deeper_than_5mm(heavy.mesh, heavy_trousers.mesh);
  INFO(inside << " of " << heavy_trousers.mesh.num_vertices() << " trouser vertices deeper than 5 mm in the body");
  CHECK(inside < heavy_trousers.mesh.num_vertices() / 20);

  values["piece"] = {YAML::Node("2"), {}};
  CHECK_THROWS_WITH(build(values), Catch::Contains("male_casualsuit04.obj") && Catch::Contains("2 connected pieces") &&
                                       Catch::Contains("no piece 2"));
  values["piece"] = {YAML::Node("jacket"), {}};
  CHECK_THROWS_WITH(build(values), Catch::Contains("male_casualsuit04.obj") && Catch::Contains("jacket"));

  // A binding for another base mesh: the outfit copied with one reference moved past the base mesh's vertices.
  test::TempDir dir;
  const auto root = test::shared_assets() / "makehuman";
  std::filesystem::create_directories(dir / "mh");
  for (const char* sub : {"base", "targets"}) std::filesystem::create_directory_symlink(root / sub, dir / "mh" / sub);
  const auto outfit = dir / "mh/clothes/male_casualsuit04";
  std::filesystem::create_directories(outfit);
  std::filesystem::copy_file(root / "clothes/male_casualsuit04/male_casualsuit04.obj", outfit / "male_casualsuit04.obj");
  std::ifstream in(root / "clothes/male_casualsuit04/male_casualsuit04.mhclo");
  std::ofstream out(outfit / "male_casualsuit04.mhclo");
  bool in_verts = false, changed = false;
  for (std::string line; std::getline(in, line);) {
    if (in_verts && !changed && std::count(line.begin(), line.end(), ' ') >= 2) {
      line = "99999" + line.substr(line.find(' '));
      changed = true;
    }
    if (line.rfind("verts", 0) == 0) in_verts = true;
    out << line << "\n";
  }
  out.close();
  REQUIRE(changed);
  ParamValues other{{"path", {YAML::Node((dir / "mh").string()), {}}}};
  CHECK_THROWS_WITH(build(other), Catch::Contains("male_casualsuit04.mhclo") && Catch::Contains("base vertex 99999") &&
                                      Catch::Contains("another base mesh"));
}

// A whole outfit in one scene (issue 54, item 5): piece "0,1" is the T-shirt
// and the jeans as one garment, each piece a material region of its own
// fabric; dressing lays the shirt's hem outside the jeans' waistband, which
// it would otherwise push through it.
TEST_CASE("MakeHuman clothes: a two-piece outfit drapes as one garment, each piece its own fabric", "[makehuman]") {
  if (!assets_present()) {
    SUCCEED("skipped");
    return;
  }
  const auto& d = test::plugins().get("makehuman_clothes");
  ParamValues values = path_param();
  values["piece"] = {YAML::Node("0, 1"), {}};
  const Garment suit = test::plugins().create_garment("makehuman_clothes", Params(d.params, values, "suit"))->build();
  CHECK(suit.mesh.num_vertices() == 810 + 886);
  REQUIRE(suit.materials.size() == 2);
  CHECK(suit.materials[0].name == "piece0");
  CHECK(suit.materials[1].name == "piece1");
  CHECK((suit.face_material.head(1528).array() == 0).all());  // the shirt's 1,528 triangles first
  CHECK((suit.face_material.tail(suit.mesh.num_faces() - 1528).array() == 1).all());
  // As fitted, the pieces are apart; dressed piece by piece on the body, the
  // jeans' waistband goes through the shirt.
  const Eigen::MatrixX3i shirt = suit.mesh.faces.topRows(1528), jeans = suit.mesh.faces.bottomRows(suit.mesh.num_faces() - 1528);
  CHECK(geometry::surface_crossings(suit.mesh.vertices, shirt, suit.mesh.vertices, jeans).total() == 0);
  const auto body = makehuman_body();
  Mesh mean;
  mean.vertices = body->vertices(body->mean_shape());
  mean.faces = body->faces();
  Garment unlaid = suit;
  DressOptions no_layers;
  no_layers.lay_pieces = false;
  no_layers.untangle_rounds = 0;  // dress's own untangling smooths some of it away too; the layers are what guarantees it
  dress(unlaid, mean, no_layers);
  CHECK(geometry::surface_crossings(unlaid.mesh.vertices, shirt, unlaid.mesh.vertices, jeans).total() > 0);

  // The shipped scene: denim for the jeans, dressed into layers.
  const Scene scene = load_scene(test::source_dir() / "graphs/scenes/makehuman_suit.yaml");
  Scene with_path = scene;
  with_path.garment_params["path"] = {YAML::Node((test::shared_assets() / "makehuman").string()), {}};
  const Simulation sim(test::plugins(), with_path);
  const Garment& g = sim.garment();
  CHECK(geometry::surface_crossings(g.mesh.vertices, shirt, g.mesh.vertices, jeans).total() == 0);
  REQUIRE(g.materials.size() == 2);
  CHECK(g.materials[1].name == "piece1");
  CHECK(g.materials[1].density > 1.5 * g.materials[0].density);  // 11 oz denim against the interlock knit
  // A vertex in two named pieces is refused.
  values["piece"] = {YAML::Node("0,0"), {}};
  CHECK_THROWS_WITH(test::plugins().create_garment("makehuman_clothes", Params(d.params, values, "suit"))->build(),
                    Catch::Contains("share vertex"));
}

// An outfit name that is not a folder of clothes/ names the close ones and
// every outfit there; a MakeHuman garment in a scene of another body model is
// refused naming both models, before it is dressed on a body it was not fitted to.
TEST_CASE("MakeHuman clothes: a misspelled outfit gets the close names, another body model is refused", "[makehuman]") {
  if (!assets_present()) {
    SUCCEED("skipped");
    return;
  }
  const auto& d = test::plugins().get("makehuman_clothes");
  ParamValues values = path_param();
  values["outfit"] = {YAML::Node("male_casualsuit4"), {}};
  CHECK_THROWS_WITH(test::plugins().create_garment("makehuman_clothes", Params(d.params, values, "clothes"))->build(),
                    Catch::Contains("no MakeHuman outfit 'male_casualsuit4'") &&
                        Catch::Contains("did you mean 'male_casualsuit04'") && Catch::Contains("(its outfits: male_casualsuit04"));
  const std::string path = (test::shared_assets() / "makehuman").string();
  const std::string why = test::message_of([&] {
    Simulation(test::plugins(), parse_scene("body: {model: parametric}\n"
                                            "garment: {template: makehuman_clothes, params: {path: " + path + ", piece: \"1\"}}\n"
                                            "effects: {gravity: {}, stretching: {}, barrier: {}}\n",
                                            "trousers.yaml"));
  });
  CHECK_THAT(why, Catch::Contains("trousers.yaml") && Catch::Contains("fitted to the body model 'makehuman'") &&
                      Catch::Contains("this scene's body is 'parametric'") && Catch::Contains("body: {model: makehuman}"));
}
