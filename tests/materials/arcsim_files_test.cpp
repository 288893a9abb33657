// ArcSim material files (graphs/materials/arcsim/*.json) as material presets:
// the shipped files against ArcSim's numbers, the presets that inline them,
// the model and file keys, multipliers over the tables, scenes naming files,
// and every way a file can be rejected (file, line and field in the message).
#include <drape/materials/materials.hpp>
#include <drape/scene/scene.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kShipped{"11oz-black-denim",   "aluminium",         "camel-ponte-roma", "gray-interlock",
                                        "ivory-rib-knit",     "navy-sparkle-sweat", "paper",            "pink-ribbon-brown",
                                        "royal-target",       "tango-red-jet-set", "white-dots-on-blk", "white-swim-solid"};

fs::path shipped(const std::string& name) { return test::source_dir() / "graphs/materials/arcsim" / (name + ".json"); }

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// A valid ArcSim file with line `line` (1-based) replaced by `replacement`.
// Lines: 1 {, 2 density, 3 "stretching": [, 4-9 rows 0-5, 10 ], 11 "bending": [, 12-14 rows, 15 ], 16 }.
std::string arcsim_text(int line = 0, const std::string& replacement = "") {
  std::vector<std::string> lines{
      "{",
      "  \"density\": 0.2,",
      "  \"stretching\": [",
      "    [20, -10, 30, 40],",
      "    [40, 50, 260, -30],",
      "    [50, 80, 200, 20],",
      "    [120, 100, 360, 40],",
      "    [140, 70, 410, -170],",
      "    [130, 80, 400, 30]",
      "  ],",
      "  \"bending\": [",
      "    [20e-6, 30e-6, 30e-6, 40e-6, 20e-6],",
      "    [25e-6, 18e-6, 16e-6, 25e-6, 9e-6],",
      "    [14e-6, 7e-6, 14e-6, 24e-6, 19e-6]",
      "  ]",
      "}"};
  if (line > 0) lines[static_cast<std::size_t>(line - 1)] = replacement;
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

// The message of loading `text` as the ArcSim file dir/name.
std::string file_error(const test::TempDir& dir, const std::string& name, const std::string& text) {
  write(dir / name, text);
  return test::message_of([&] { load_arcsim_material(dir / name); });
}

void check_same(const Material& a, const Material& b) {
  CHECK(a.model == b.model);
  CHECK(a.density == b.density);
  CHECK(a.thickness == b.thickness);
  for (std::size_t r = 0; r < 6; ++r) CHECK(a.arcsim.stretching[r] == b.arcsim.stretching[r]);
  CHECK(a.arcsim.bending == b.arcsim.bending);
}

YAML::Node yaml_node(const std::string& text) { return YAML::Load(text); }

}  // namespace

TEST_CASE("arcsim files: every shipped file loads with ArcSim's numbers", "[materials][arcsim]") {
  for (const auto& name : kShipped) {
    INFO(name);
    const Material m = load_arcsim_material(shipped(name));
    CHECK(m.name == name);
    CHECK(m.model == Material::Model::Arcsim);
    CHECK(m.thickness == 4.7e-4);  // ArcSim's data has none: drape's default
  }
  // Typed in from ArcSim's materials/gray-interlock.json (Wang et al. 2011).
  const Material knit = load_arcsim_material(shipped("gray-interlock"));
  CHECK(knit.density == 0.187);
  CHECK(knit.arcsim.stretching[0] == Eigen::Vector4d(16.593832, -14.695990, 34.477123, 36.860302));
  CHECK(knit.arcsim.stretching[4] == Eigen::Vector4d(139.686325, 73.592560, 413.553162, -174.43853));
  CHECK(knit.arcsim.stretching[5] == Eigen::Vector4d(127.443810, 85.848587, 405.872833, 32.238411));
  CHECK(knit.arcsim.bending[0][0] == 23.191698e-6);
  CHECK(knit.arcsim.bending[1][4] == 8.860165e-6);
  CHECK(knit.arcsim.bending[2][4] == 19.383726e-6);

  const Material denim = load_arcsim_material(shipped("11oz-black-denim"));
  CHECK(denim.density == 0.324);
  CHECK(denim.arcsim.stretching[0] == Eigen::Vector4d(205.352005, 10.234077, 1013.88629, 53.387184));
  CHECK(denim.arcsim.bending[2][3] == 120.569740e-6);

  CHECK(load_arcsim_material(shipped("royal-target")).arcsim.stretching[3][0] == 2110.33349);
  CHECK(load_arcsim_material(shipped("navy-sparkle-sweat")).arcsim.stretching[0][2] == 3.272434);

  // aluminium.json and paper.json start with `//` comment lines.
  const Material foil = load_arcsim_material(shipped("aluminium"));
  CHECK(foil.density == 0.071);
  for (const auto& row : foil.arcsim.stretching) CHECK(row == Eigen::Vector4d(1.8e6, 0, 1.8e6, 1.8e6));
  for (const auto& row : foil.arcsim.bending) CHECK(row == std::array<double, 5>{96e-6, 96e-6, 96e-6, 96e-6, 96e-6});
  const Material paper = load_arcsim_material(shipped("paper"));
  CHECK(paper.density == 0.1);
  CHECK(paper.arcsim.stretching[5] == Eigen::Vector4d(0.5e6, 0, 0.5e6, 0.5e6));
  CHECK(paper.arcsim.bending[1][2] == 0.4e-3);
}

TEST_CASE("arcsim files: the built-in presets are the shipped files, number for number", "[materials][arcsim]") {
  const MaterialTable table = MaterialTable::builtin();
  for (const auto& name : kShipped) {
    INFO(name);
    REQUIRE(table.contains(name));
    check_same(table.get(name), load_arcsim_material(shipped(name)));
  }
  // gray-interlock read from presets.yaml and from its file, by hand.
  const Material knit = table.get("gray-interlock");
  CHECK(knit.model == Material::Model::Arcsim);
  CHECK(knit.arcsim.stretching[0] == Eigen::Vector4d(16.593832, -14.695990, 34.477123, 36.860302));
  CHECK(knit.arcsim.stretching[5] == Eigen::Vector4d(127.443810, 85.848587, 405.872833, 32.238411));
  CHECK(knit.arcsim.bending[2][4] == 19.383726e-6);
  CHECK(table.get("11oz-black-denim").density == 0.324);
}

TEST_CASE("arcsim files: screen-print is the knit's tables scaled, and so is screen-print.json", "[materials][arcsim]") {
  const MaterialTable table = MaterialTable::builtin();
  const Material knit = table.get("gray-interlock"), print = table.get("screen-print");
  CHECK(print.model == Material::Model::Arcsim);
  CHECK(print.density == 2 * knit.density);
  CHECK(print.thickness == 2 * knit.thickness);
  for (std::size_t r = 0; r < 6; ++r) CHECK(print.arcsim.stretching[r] == 5 * knit.arcsim.stretching[r]);
  for (std::size_t b = 0; b < 3; ++b)
    for (std::size_t j = 0; j < 5; ++j) CHECK(print.arcsim.bending[b][j] == 10 * knit.arcsim.bending[b][j]);

  // The same print as an ArcSim-format file (decimal products, so equal to rounding).
  const Material file = load_arcsim_material(test::source_dir() / "graphs/materials/screen-print.json");
  CHECK(file.name == "screen-print");
  CHECK(file.density == Approx(print.density).epsilon(1e-15));
  CHECK(file.thickness == Approx(print.thickness).epsilon(1e-15));
  for (std::size_t r = 0; r < 6; ++r)
    for (int c = 0; c < 4; ++c) CHECK(file.arcsim.stretching[r][c] == Approx(print.arcsim.stretching[r][c]).epsilon(1e-14));
  for (std::size_t b = 0; b < 3; ++b)
    for (std::size_t j = 0; j < 5; ++j) CHECK(file.arcsim.bending[b][j] == Approx(print.arcsim.bending[b][j]).epsilon(1e-14));
  CHECK(file.arcsim.stretching[0][0] == 82.96916);  // 16.593832 * 5, typed in
}

TEST_CASE("arcsim files: comments are blanked and lines still point at the file's lines", "[materials][arcsim]") {
  test::TempDir dir;
  // Line and block comments, a `//` inside a string, tabs; the error is on line 9.
  write(dir / "c.json",
        "// a measured cloth\n"
        "/* several\n"
        "   lines */ {\n"
        "  \"doc\": \"see http://graphics.berkeley.edu // not a comment\",  // a comment\n"
        "\t\"density\": 0.2,\n"
        "  \"stretching\": [[20, -10, 30, 40], [40, 50, 260, -30], [50, 80, 200, 20],\n"
        "                 [120, 100, 360, 40], [140, 70, 410, -170], [130, 80, 400, 30]],\n"
        "  \"bending\": [[1e-5, 1e-5, 1e-5, 1e-5, 1e-5], [1e-5, 1e-5, 1e-5, 1e-5, 1e-5],\n"
        "              [1e-5, 1e-5, -1e-5, 1e-5, 1e-5]]  /* the bad one */\n"
        "}\n");
  const std::string e = test::message_of([&] { load_arcsim_material(dir / "c.json"); });
  CHECK_THAT(e, Catch::Contains("c.json:9") && Catch::Contains("`bending[2][2]` must be >= 0 N*m") &&
                    Catch::Contains("-1e-5"));

  write(dir / "ok.json", "// header\n" + arcsim_text(2, "  \"density\": 0.2, // kg/m^2\n  \"doc\": \"a // b\","));
  const MaterialTable table;
  const Material m = table.resolve(YAML::Node((dir / "ok.json").string()), "scene.yaml");
  CHECK(m.density == 0.2);
  CHECK(m.arcsim.stretching[5] == Eigen::Vector4d(130, 80, 400, 30));
  CHECK(MaterialTable().resolve(yaml_node("{file: " + (dir / "ok.json").string() + "}"), "s.yaml").name == "ok");
}

TEST_CASE("arcsim files: bad files are rejected naming the file, the line and the field", "[materials][arcsim]") {
  test::TempDir dir;
  REQUIRE(file_error(dir, "good.json", arcsim_text()) == "(no exception)");

  // Missing fields: at the file's map (line 1).
  std::string e = file_error(dir, "m.json", "{\n  \"stretching\": [],\n  \"bending\": 3\n}\n");
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("`stretching` has 0 rows") && Catch::Contains("expected 6x4"));
  e = file_error(dir, "m.json", arcsim_text(2, ""));
  CHECK_THAT(e, Catch::Contains("m.json:1") && Catch::Contains("missing: density"));
  e = file_error(dir, "m.json", "{\"density\": 0.2}\n");
  CHECK_THAT(e, Catch::Contains("m.json:1") && Catch::Contains("missing: stretching, bending"));

  // Shapes: 6x4 and 3x5, saying what was found.
  e = file_error(dir, "m.json", arcsim_text(9, "    []"));
  CHECK_THAT(e, Catch::Contains("m.json:9") && Catch::Contains("`stretching[5]` has 0 numbers") &&
                    Catch::Contains("expected 6x4"));
  e = file_error(dir, "m.json", arcsim_text(8, ""));  // 5 rows
  CHECK_THAT(e, Catch::Contains("m.json:3") && Catch::Contains("`stretching` has 5 rows (expected 6x4"));
  e = file_error(dir, "m.json", arcsim_text(6, "    [50, 80, 200],"));
  CHECK_THAT(e, Catch::Contains("m.json:6") && Catch::Contains("`stretching[2]` has 3 numbers (expected 6x4"));
  e = file_error(dir, "m.json", arcsim_text(6, "    50,"));
  CHECK_THAT(e, Catch::Contains("m.json:6") && Catch::Contains("`stretching[2]` must be a list of 4 numbers") &&
                    Catch::Contains("got '50'"));
  e = file_error(dir, "m.json", arcsim_text(14, "    [14e-6, 7e-6, 14e-6, 24e-6, 19e-6, 1e-6]"));
  CHECK_THAT(e, Catch::Contains("m.json:14") && Catch::Contains("`bending[2]` has 6 numbers (expected 3x5"));
  e = file_error(dir, "m.json", arcsim_text(13, "    [25e-6, 18e-6, 16e-6, 25e-6, 9e-6], [1, 1, 1, 1, 1],"));
  CHECK_THAT(e, Catch::Contains("m.json:11") && Catch::Contains("`bending` has 4 rows (expected 3x5"));

  // Values.
  e = file_error(dir, "m.json", arcsim_text(5, "    [40, 50, \"stiff\", -30],"));
  CHECK_THAT(e, Catch::Contains("m.json:5") && Catch::Contains("`stretching[1][2]` must be a number, got 'stiff'"));
  // A quoted number is text (it was read as the number).
  e = file_error(dir, "m.json", arcsim_text(2, "  \"density\": \"0.187\","));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("`density` must be a number, got the text \"0.187\""));
  e = file_error(dir, "m.json", arcsim_text(7, "    [120, .nan, 360, 40],"));
  CHECK_THAT(e, Catch::Contains("m.json:7") && Catch::Contains("`stretching[3][1]` must be a finite number"));
  e = file_error(dir, "m.json", arcsim_text(12, "    [20e-6, 30e-6, .inf, 40e-6, 20e-6],"));
  CHECK_THAT(e, Catch::Contains("m.json:12") && Catch::Contains("`bending[0][2]` must be a finite number"));
  e = file_error(dir, "m.json", arcsim_text(2, "  \"density\": 0,"));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("`density` must be > 0"));
  e = file_error(dir, "m.json", arcsim_text(2, "  \"density\": -0.2,"));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("`density` must be > 0"));
  e = file_error(dir, "m.json", arcsim_text(13, "    [25e-6, 18e-6, 16e-6, -25e-6, 9e-6],"));
  CHECK_THAT(e, Catch::Contains("m.json:13") && Catch::Contains("`bending[1][3]` must be >= 0 N*m, got -25e-6"));
  // Values no cloth or sheet has: a typo or a unit mistake, named before anything is simulated.
  e = file_error(dir, "m.json", arcsim_text(2, "  \"density\": 1e30,"));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("`density` is 1e+30 kg/m^2, beyond any cloth"));
  e = file_error(dir, "m.json", arcsim_text(7, "    [120, 2e9, 360, 40],"));
  CHECK_THAT(e, Catch::Contains("m.json:7") && Catch::Contains("`stretching[3][1]` is 2e+09 N/m, beyond any cloth"));
  e = file_error(dir, "m.json", arcsim_text(13, "    [25e-6, 18e-6, 16e-6, 5e3, 9e-6],"));
  CHECK_THAT(e, Catch::Contains("m.json:13") && Catch::Contains("`bending[1][3]` is 5000 N*m, beyond any cloth"));
  // A steel sheet is still a material (7.8 kg/m^2, 2e8 N/m).
  CHECK(file_error(dir, "m.json", arcsim_text(2, "  \"density\": 7.8,")) == "(no exception)");

  // The zero-strain row: ArcSim clamps negatives to 0, leaving no stiffness at rest.
  e = file_error(dir, "m.json", arcsim_text(4, "    [-20, -10, 30, 40],"));
  CHECK_THAT(e, Catch::Contains("m.json:4") && Catch::Contains("`stretching[0]` (zero strain)") &&
                    Catch::Contains("k_uu = -20") && Catch::Contains("no stiffness along u at rest"));
  e = file_error(dir, "m.json", arcsim_text(4, "    [20, -10, 0, 40],"));
  CHECK_THAT(e, Catch::Contains("m.json:4") && Catch::Contains("no stiffness along v at rest"));
  // Negative samples elsewhere are ArcSim's data (gray-interlock's row 4 has k_shear = -174).
  CHECK(file_error(dir, "m.json", arcsim_text(5, "    [-40, -50, -260, -30],")) == "(no exception)");

  // Not a material file at all.
  e = file_error(dir, "m.json", "// nothing but a comment\n");
  CHECK_THAT(e, Catch::Contains("m.json:1") && Catch::Contains("must be a map {density, stretching, bending}"));
  e = file_error(dir, "m.json", "[1, 2]\n");
  CHECK_THAT(e, Catch::Contains("m.json:1") && Catch::Contains("must be a map {density, stretching, bending}"));
  e = file_error(dir, "m.json", "{\"density\": 0.2,\n \"stretching\": [[1, 2, 3, 4]\n");
  CHECK_THAT(e, Catch::Contains("m.json:") && Catch::Contains("malformed"));
  e = file_error(dir, "m.json", arcsim_text(2, "  \"densty\": 0.2,"));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("unknown key 'densty'") &&
                    Catch::Contains("did you mean 'density'"));
  e = file_error(dir, "m.json", arcsim_text(2, "  \"base\": \"gray-interlock\", \"density\": 0.2,"));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("unknown key 'base'"));
  e = file_error(dir, "m.json", arcsim_text(2, "  \"stretch\": [1, 0, 1, 1], \"density\": 0.2,"));
  CHECK_THAT(e, Catch::Contains("m.json:2") && Catch::Contains("unknown key 'stretch'; did you mean 'stretching'"));

  // Unreadable: where it is named, with the path.
  e = test::message_of([&] { MaterialTable().resolve(yaml_node("{file: absent.json}"), (dir / "scene.yaml").string()); });
  CHECK_THAT(e, Catch::Contains("scene.yaml:1") && Catch::Contains("cannot read ArcSim material file") &&
                    Catch::Contains((dir / "absent.json").string()) && Catch::Contains("No such file"));
  e = test::message_of([&] { MaterialTable().resolve(yaml_node("\n\nabsent.json"), (dir / "scene.yaml").string()); });
  CHECK_THAT(e, Catch::Contains("scene.yaml:3") && Catch::Contains((dir / "absent.json").string()));
  fs::create_directories(dir / "dir.json");
  e = test::message_of([&] { load_arcsim_material(dir / "dir.json"); });
  CHECK_THAT(e, Catch::Contains("dir.json") && Catch::Contains("is a directory"));
}

TEST_CASE("arcsim files: the model key, and an ArcSim map as a preset", "[materials][arcsim]") {
  test::TempDir dir;
  const MaterialTable builtin = MaterialTable::builtin();
  // ArcSim's own map, pasted into a preset file, is a preset (model inferred).
  std::string pasted_text;  // ArcSim's map, indented under its preset name
  for (std::size_t start = 0, end; (end = arcsim_text().find('\n', start)) != std::string::npos; start = end + 1)
    pasted_text += "  " + arcsim_text().substr(start, end - start + 1);
  write(dir / "mine.yaml", "pasted:\n" + pasted_text +
                               "thick:\n  model: arcsim\n  thickness: 1e-3\n  density: 0.2\n"
                               "  stretching: [[1, 0, 1, 1], [1, 0, 1, 1], [1, 0, 1, 1], [1, 0, 1, 1], [1, 0, 1, 1], [1, 0, 1, 1]]\n"
                               "  bending: [[0, 0, 0, 0, 0], [0, 0, 0, 0, 0], [0, 0, 0, 0, 0]]\n");
  const MaterialTable mine = MaterialTable::load(dir / "mine.yaml");
  const Material pasted = mine.get("pasted");
  CHECK(pasted.model == Material::Model::Arcsim);
  CHECK(pasted.thickness == 4.7e-4);
  CHECK(pasted.arcsim.stretching[0] == Eigen::Vector4d(20, -10, 30, 40));
  CHECK(mine.get("thick").thickness == 1e-3);
  CHECK(mine.preset("thick").model == Material::Model::Arcsim);
  CHECK(builtin.get("snug-knit").model == Material::Model::Linear);  // no model key, no stretching: linear

  std::string e = test::message_of([&] { builtin.resolve(yaml_node("{model: arcsm}"), "s.yaml"); });
  CHECK_THAT(e, Catch::Contains("s.yaml:1") && Catch::Contains("`model` must be linear or arcsim") &&
                    Catch::Contains("did you mean 'arcsim'"));
  e = test::message_of([&] {
    builtin.resolve(yaml_node("model: linear\ndensity: 0.2\nstretching: [[1, 0, 1, 1]]\n"), "s.yaml");
  });
  CHECK_THAT(e, Catch::Contains("s.yaml:3") && Catch::Contains("`stretching` is a field of model arcsim"));
  e = test::message_of([&] { builtin.resolve(yaml_node("model: arcsim\ndensity: 0.2\nbending: 1e-5\n"), "s.yaml"); });
  CHECK_THAT(e, Catch::Contains("s.yaml:3") && Catch::Contains("`bending` must be a list of 3 rows of 5 numbers") &&
                    Catch::Contains("expected 3x5"));
  e = test::message_of([&] { builtin.resolve(yaml_node("model: arcsim\ndensity: 0.2\n"), "s.yaml"); });
  CHECK_THAT(e, Catch::Contains("s.yaml:1") && Catch::Contains("missing: stretching, bending"));
  // A preset keeps its base's model.
  e = test::message_of([&] { builtin.resolve(yaml_node("base: gray-interlock\n\nbending: 2e-5\n"), "s.yaml"); });
  CHECK_THAT(e, Catch::Contains("s.yaml:3") && Catch::Contains("is model linear but its base 'gray-interlock' is model arcsim"));
  e = test::message_of([&] { builtin.resolve(yaml_node("base: gray-interlock-linear\nmodel: arcsim\n"), "s.yaml"); });
  CHECK_THAT(e, Catch::Contains("s.yaml:2") && Catch::Contains("is model arcsim but its base"));
}

TEST_CASE("arcsim files: multipliers scale every sample of the tables", "[materials][arcsim]") {
  test::TempDir dir;
  const MaterialTable table = MaterialTable::builtin();
  const Material knit = table.get("gray-interlock");
  const Material m =
      table.resolve(yaml_node("{base: gray-interlock, multipliers: {stretch: 2, bend: 3, density: 0.5, thickness: 4}}"), "s.yaml");
  CHECK(m.name == "gray-interlock");
  CHECK(m.model == Material::Model::Arcsim);
  CHECK(m.density == 0.5 * knit.density);
  CHECK(m.thickness == 4 * knit.thickness);
  for (std::size_t r = 0; r < 6; ++r) CHECK(m.arcsim.stretching[r] == 2 * knit.arcsim.stretching[r]);
  for (std::size_t b = 0; b < 3; ++b)
    for (std::size_t j = 0; j < 5; ++j) CHECK(m.arcsim.bending[b][j] == 3 * knit.arcsim.bending[b][j]);

  // A table set over a base replaces it; multipliers scale what is not set.
  const Material own = table.resolve(yaml_node("base: gray-interlock\nmultipliers: {stretch: 2}\n"
                                          "bending: [[1e-5, 1e-5, 1e-5, 1e-5, 1e-5], [0, 0, 0, 0, 0], [2e-5, 2e-5, 2e-5, 2e-5, 2e-5]]\n"),
                                     "s.yaml");
  CHECK(own.arcsim.bending[2][0] == 2e-5);
  CHECK(own.arcsim.stretching[3] == 2 * knit.arcsim.stretching[3]);
  std::string e = test::message_of([&] {
    table.resolve(yaml_node("base: gray-interlock\nmultipliers: {stretch: 2}\nstretching: []\n"), "s.yaml");
  });
  CHECK_THAT(e, Catch::Contains("s.yaml:3") && Catch::Contains("expected 6x4"));

  // Over a file: as ArcSim's stretching_mult and bending_mult.
  write(dir / "cloth" / "denim.json", "// ArcSim's\n" + arcsim_text());
  write(dir / "mine.yaml", "stiff-denim:\n  doc: twice as stiff\n  file: cloth/denim.json\n  thickness: 6e-4\n"
                           "  multipliers: {stretch: 2, bend: 10, density: 3}\n");
  const MaterialTable mine = MaterialTable::load(dir / "mine.yaml");
  const Material stiff = mine.get("stiff-denim");
  const Material denim = load_arcsim_material(dir / "cloth" / "denim.json");
  CHECK(mine.preset("stiff-denim").doc == "twice as stiff");
  CHECK(stiff.thickness == 6e-4);
  CHECK(stiff.density == 3 * denim.density);
  for (std::size_t r = 0; r < 6; ++r) CHECK(stiff.arcsim.stretching[r] == 2 * denim.arcsim.stretching[r]);
  CHECK(stiff.arcsim.bending[1][1] == 10 * denim.arcsim.bending[1][1]);

  e = test::message_of([&] { MaterialTable::load(dir / "mine.yaml"); });
  CHECK(e == "(no exception)");
  write(dir / "bad.yaml", "a:\n  file: cloth/denim.json\n  density: 0.3\n");
  e = test::message_of([&] { MaterialTable::load(dir / "bad.yaml"); });
  CHECK_THAT(e, Catch::Contains("bad.yaml:3") && Catch::Contains("`density` and `file` both given"));
  write(dir / "bad.yaml", "a:\n  file: cloth/denim.json\n  thickness: 1e-3\n  multipliers: {thickness: 2}\n");
  e = test::message_of([&] { MaterialTable::load(dir / "bad.yaml"); });
  CHECK_THAT(e, Catch::Contains("bad.yaml:4") && Catch::Contains("`multipliers.thickness` and `thickness` both given"));
  write(dir / "bad.yaml", "a:\n  file: cloth/denm.json\n");
  e = test::message_of([&] { MaterialTable::load(dir / "bad.yaml"); });
  CHECK_THAT(e, Catch::Contains("bad.yaml:2") && Catch::Contains("cannot read ArcSim material file") &&
                    Catch::Contains("denm.json"));
  // An error inside the named file points into that file.
  write(dir / "cloth" / "broken.json", arcsim_text(13, "    [25e-6, 18e-6, 16e-6, -25e-6, 9e-6],"));
  write(dir / "bad.yaml", "a:\n  file: cloth/broken.json\n");
  e = test::message_of([&] { MaterialTable::load(dir / "bad.yaml"); });
  CHECK_THAT(e, Catch::Contains("broken.json:13") && Catch::Contains("`bending[1][3]`"));
}

TEST_CASE("arcsim files: a scene names a file relative to itself and serialises its data", "[materials][arcsim][scene]") {
  test::TempDir dir;
  write(dir / "cloth" / "denim.json", "// ArcSim's\n" + arcsim_text());
  write(dir / "scenes" / "base.yaml", "garment: {template: tshirt}\n"
                                      "materials:\n"
                                      "  knit: ../cloth/denim.json\n"
                                      "  print: {file: ../cloth/denim.json, multipliers: {stretch: 5}, thickness: 1e-3}\n");
  // A derived scene in another folder: the base's paths stay relative to the base.
  write(dir / "derived.yaml", "base: scenes/base.yaml\ndescription: derived\n");
  const MaterialTable table = MaterialTable::builtin();
  const Material denim = load_arcsim_material(dir / "cloth" / "denim.json");

  const Scene s = load_scene(dir / "derived.yaml");
  REQUIRE(s.materials.size() == 2);
  const Material knit = table.resolve(s.materials[0].spec, s.materials[0].file);
  const Material print = table.resolve(s.materials[1].spec, s.materials[1].file);
  CHECK(knit.name == "denim");
  check_same(knit, denim);
  CHECK(print.arcsim.stretching[2] == 5 * denim.arcsim.stretching[2]);
  CHECK(print.thickness == 1e-3);

  // The serialised scene carries the data, not the path: it reads back the
  // same from any folder (a dataset stores this text).
  const std::string text = s.yaml();
  CHECK(text.find(".json") == std::string::npos);
  CHECK_THAT(text, Catch::Contains("arcsim"));
  write(dir / "elsewhere" / "stored.yaml", text);
  const Scene again = load_scene(dir / "elsewhere" / "stored.yaml");
  REQUIRE(again.materials.size() == 2);
  check_same(table.resolve(again.materials[0].spec, again.materials[0].file), knit);
  check_same(table.resolve(again.materials[1].spec, again.materials[1].file), print);
  const Scene from_text = parse_scene(text, "<dataset>");
  check_same(table.resolve(from_text.materials[1].spec, from_text.materials[1].file), print);
  // Numbers as written (shortest round trip); presets by name stay names.
  CHECK_THAT(text, Catch::Contains("density: 0.2,") && Catch::Contains("thickness: 0.00047}") &&
                       Catch::Contains("[130, 80, 400, 30]") && Catch::Contains("2e-05"));
  CHECK(parse_scene("materials: {knit: gray-interlock}\n", "x").yaml().find("knit: gray-interlock") != std::string::npos);

  // A scene naming a missing file fails at its own line.
  write(dir / "scenes" / "missing.yaml", "materials:\n  knit: ../cloth/absent.json\n");
  const Scene missing = load_scene(dir / "scenes" / "missing.yaml");
  const std::string e = test::message_of([&] { table.resolve(missing.materials[0].spec, missing.materials[0].file); });
  CHECK_THAT(e, Catch::Contains("missing.yaml:2") && Catch::Contains("absent.json"));
}
