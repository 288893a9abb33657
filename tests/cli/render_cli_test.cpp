// `drape render`: the pictures a person looks at. The HTML page carries the
// meshes and its own renderer; where Debian's Chromium is installed, the page
// is loaded headless and must really draw (pixels differ from the background)
// and give a screenshot.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& file) { return test::read_file(file); }

std::string chromium() {
  if (const char* c = std::getenv("CHROMIUM")) return c;
  for (const char* c : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"})
    if (fs::exists(c)) return c;
  return "";
}

long attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  if (!std::regex_search(dom, m, std::regex(name + "=\"([0-9]+)\""))) return -1;
  return std::stol(m[1]);
}

}  // namespace

TEST_CASE("render writes an HTML viewer and an SVG of a predicted drape, with the colour asked for", "[render]") {
  test::TempDir dir;
  const std::string drape = test::drape_program().string() + " render ";
  std::string out;
  REQUIRE(test::run(drape + "--bmi 30 --colour strain --out " + (dir / "d.html").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("mean strain"));
  const std::string page = read(dir / "d.html");
  CHECK_THAT(page, Catch::StartsWith("<!DOCTYPE html>"));
  CHECK_THAT(page, Catch::Contains("id=\"figure-data\""));
  CHECK_THAT(page, Catch::Contains("edge length change| at each vertex, against the material space"));
  CHECK(page.find("http://") == std::string::npos);  // self-contained: nothing to fetch
  CHECK(page.find("https://") == std::string::npos);
  REQUIRE(test::run(drape + "--bmi 30 --out " + (dir / "d.svg").string(), out) == 0);
  CHECK_THAT(read(dir / "d.svg"), Catch::Contains("<svg"));
  // The title names the body as asked: its height, sex and pose (it said "for BMI 30.0" whatever they were).
  REQUIRE(test::run(drape + "--bmi 30 --height 1.6 --sex 0 --pose shoulder_abduction=60 --out " + (dir / "p.html").string(),
                    out) == 0);
  CHECK_THAT(read(dir / "p.html"), Catch::Contains("<title>drape render: prediction of tshirt-coarse-posed-human.h5 for "
                                                   "BMI 30, 1.60 m, sex 0, posed shoulder_abduction=60</title>"));
  CHECK_THAT(out, Catch::Contains("p = "));

  CHECK(test::run(drape + "--bmi 30 --colour heat --out " + (dir / "x.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("distance, error or strain"));
  CHECK(test::run(drape + "--bmi 30 --colour error --out " + (dir / "x.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--data"));
  CHECK(test::run(drape + "--bmi 30 --out " + (dir / "x.png").string(), out) == 2);
  CHECK(test::run(drape + "--body " + (dir / "d.svg").string() + " --bmi 30 --out " + (dir / "x.html").string(), out) == 2);
}

TEST_CASE("the 3D viewer page draws in headless Chromium and its screenshot is not blank", "[render][browser]") {
  const std::string browser = chromium();
  if (browser.empty()) {
    WARN("skipped: Chromium is not installed (apt-get install chromium, as scripts/setup.sh does; or set CHROMIUM)");
    return;
  }
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run(test::drape_program().string() + " render --bmi 35 --out " + (dir / "page.html").string(), out) == 0);
  const std::string flags = " --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir=" +
                            (dir / "profile").string() + " --window-size=900,700 ";
  const std::string url = "file://" + (dir / "page.html").string();
  std::string dom;
  REQUIRE(test::run(browser + flags + "--dump-dom " + url + " 2>/dev/null", dom) == 0);
  INFO(dom.substr(0, 300));
  // The page counts its own non-background pixels after drawing: one 420x560 panel, most of it covered.
  CHECK(attribute(dom, "data-triangles") > 5000);  // the body's front-facing half + the garment
  CHECK(attribute(dom, "data-drawn-pixels") > 20000);
  std::string shot_log;
  REQUIRE(test::run("cd " + dir.path().string() + " && " + browser + flags + "--screenshot=" + (dir / "shot.png").string() +
                        " " + url + " 2>&1",
                    shot_log) == 0);
  INFO(shot_log);
  const std::string png = read(dir / "shot.png");
  REQUIRE(png.size() > 8);
  CHECK(png.substr(1, 3) == "PNG");
  CHECK(png.size() > 20000);  // a white page compresses to a few kB; a shaded drape does not
}

TEST_CASE("render --simulated draws a dataset's own drape: the repository's body-space shard, expanded", "[render][dataset]") {
  const fs::path shard = test::source_dir() / "datasets/bodyspace2000/shard-00-of-40.h5";
  REQUIRE(fs::exists(shard));  // part of the repository (datasets/README.md)
  test::TempDir dir;
  const std::string drape = test::drape_program().string() + " ";
  const std::string data = (dir / "full.h5").string();
  std::string out;
  REQUIRE(test::run(drape + "dataset expand --out " + data + " " + shard.string(), out) == 0);
  REQUIRE(test::run(drape + "render --data " + data + " --sample 3 --simulated --out " + (dir / "s.svg").string(), out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("simulated drape, sample 3 of full.h5") && Catch::Contains("p = 0.00%"));
  // Coloured by its error against itself it was a flat "ME 0.00 cm", a perfect result to the eye: refused.
  CHECK(test::run(drape + "render --data " + data + " --sample 3 --simulated --colour error --out " + (dir / "e.svg").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--simulated draws that drape itself (its error is 0)"));
  CHECK_FALSE(fs::exists(dir / "e.svg"));
  // The prediction of the mannequin's model (the default, on the human rig, refuses these bodies).
  const std::string mannequin = " --model " + (test::source_dir() / "models/tshirt-coarse.h5").string();
  REQUIRE(test::run(drape + "render --data " + data + mannequin + " --sample 3 --colour error --out " + (dir / "p.svg").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("prediction of") && !Catch::Contains("ME 0.00 cm, max 0.00 cm"));
  // Without --model, the default's twin on the dataset's rig (the default,
  // on the human rig, refused these bodies: "but the template has 991 and 6904").
  REQUIRE(test::run(drape + "render --data " + data + " --sample 3 --out " + (dir / "d.svg").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("holds bodies of 6490 vertices (another rig than tshirt-coarse-human.h5's): draped by the "
                                  "shipped ") &&
                      Catch::Contains("prediction of tshirt-coarse.h5 for sample 3"));
  CHECK(test::run(drape + "render --bmi 30 --simulated --out " + (dir / "x.svg").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--simulated draws a dataset's own drape"));
}

TEST_CASE("render --simulated draws a human-rig drape on the human rig's body (the scene its dataset records)",
          "[render][dataset]") {
  const fs::path shard = test::source_dir() / "datasets/bodyspace2000-human/shard-00-of-40.h5";
  REQUIRE(fs::exists(shard));  // part of the repository (datasets/README.md)
  test::TempDir dir;
  const std::string drape = test::drape_program().string() + " ";
  const std::string data = (dir / "human.h5").string();
  std::string out;
  REQUIRE(test::run(drape + "dataset expand --out " + data + " " + shard.string(), out) == 0);
  // It drew on the shipped model's mannequin template, and refused: "has 991
  // garment and 6904 body vertices per sample, but the template has 991 and 6490".
  REQUIRE(test::run(drape + "render --data " + data + " --sample 5 --simulated --out " + (dir / "h.svg").string(), out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("simulated drape, sample 5 of human.h5") && Catch::Contains("p = 0.00%"));
  // A prediction needs a model of the human rig: the default is one; the mannequin's refuses.
  REQUIRE(test::run(drape + "render --data " + data + " --sample 5 --colour error --out " + (dir / "p.svg").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("prediction of tshirt-coarse-human.h5") && !Catch::Contains("ME 0.00 cm, max 0.00 cm"));
  const std::string mannequin = " --model " + (test::source_dir() / "models/tshirt-coarse.h5").string();
  CHECK(test::run(drape + "render --data " + data + mannequin + " --sample 5 --out " + (dir / "m.svg").string(), out) != 0);
  CHECK_THAT(out, Catch::Contains("6904 body vertices per sample, but the template has 991 and 6490 (bodies of another rig"));
}

TEST_CASE("the render page and SVG show the notes the command printed", "[render]") {
  // At BMI 35 the shipped model of sizes notes the size it chose, and the
  // one-size model that its one shirt is smaller around than the body: the
  // picture must carry the same line as the terminal.
  test::TempDir dir;
  const std::string regular = " --model " + (test::source_dir() / "models/tshirt-coarse-regular.h5").string();
  for (const auto& [model, note] : {std::pair{std::string(), "note: size "},
                                    std::pair{regular, "note: the model's garment is"}}) {
    const std::string drape = test::drape_program().string() + " render" + model + " --bmi 35 --out ";
    std::string out;
    REQUIRE(test::run(drape + (dir / "d.html").string(), out) == 0);
    INFO(out);
    const auto printed = out.find(note);
    REQUIRE(printed != std::string::npos);
    const std::string line = out.substr(printed, out.find('\n', printed) - printed);
    CHECK_THAT(read(dir / "d.html"), Catch::Contains("<p class=\"note\">" + line.substr(0, 60)));
    REQUIRE(test::run(drape + (dir / "d.svg").string(), out) == 0);
    CHECK_THAT(read(dir / "d.svg"), Catch::Contains(line.substr(0, 60)));
  }
  // A body that needs no note gets none (the one-size model, whose shirt fits it).
  std::string out;
  REQUIRE(test::run(test::drape_program().string() + " render" + regular + " --bmi 22 --out " + (dir / "q.html").string(),
                    out) == 0);
  CHECK(out.find("note:") == std::string::npos);
  CHECK(read(dir / "q.html").find("<p class=\"note\">") == std::string::npos);
}

TEST_CASE("a posed dataset's body is drawn with the model of posed drapes and refused by an A-pose model", "[render][dataset]") {
  // An outside check drew the posed held-out set with the default A-pose
  // model: a shredded shirt, "ME 16.20 cm", exit 0 even with --strict.
  const fs::path posed = test::source_dir() / "datasets/posespace-human-heldout/heldout-30.h5";
  REQUIRE(fs::exists(posed));  // part of the repository (datasets/README.md)
  test::TempDir dir;
  const std::string drape = "env -u DRAPE_MODEL " + test::drape_program().string() + " ";
  std::string out;
  REQUIRE(test::run(drape + "render --data " + posed.string() + " --sample 0 --colour error --out " + (dir / "p.svg").string(), out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("sample 0's body is posed") && Catch::Contains("prediction of tshirt-coarse-posed-human.h5"));
  std::smatch me;
  REQUIRE(std::regex_search(out, me, std::regex("ME ([0-9.]+) cm")));
  CHECK(std::stod(me[1]) < 3.0);  // the A-pose model's was 16.2 cm

  const std::string a_pose = " --model " + (test::source_dir() / "models/tshirt-coarse-human.h5").string();
  CHECK(test::run(drape + "render --data " + posed.string() + a_pose + " --sample 0 --out " + (dir / "a.svg").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("sample 0's body is posed") && Catch::Contains("drapes the A-pose only"));
  CHECK_FALSE(fs::exists(dir / "a.svg"));
  CHECK(test::run(drape + "eval --split all --data " + posed.string() + a_pose, out) == 2);
  CHECK_THAT(out, Catch::Contains("drapes the A-pose only") && Catch::Contains("--model models/tshirt-coarse-posed-human.h5"));
  // The A-pose model on A-pose bodies is measured as before.
  const fs::path a_pose_data = test::source_dir() / "datasets/bodyspace2000-human/shard-00-of-40.h5";
  const std::string expanded = (dir / "human.h5").string();
  REQUIRE(test::run(drape + "dataset expand --out " + expanded + " " + a_pose_data.string(), out) == 0);
  CHECK(test::run(drape + "render --data " + expanded + a_pose + " --sample 1 --out " + (dir / "h.svg").string(), out) == 0);
  // A body option beside --data was ignored without a word.
  CHECK(test::run(drape + "render --data " + expanded + " --sample 1 --height 1.2 --out " + (dir / "x.svg").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--height describes a body given by --bmi or --body"));
}

TEST_CASE("render draws a garment of its own topology on a body mesh, as the files give them", "[render]") {
  // An outside check could not look at its own mesh garment: "has 2136
  // vertices, but the model's garment template has 991".
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --bmi 30 --out " + (dir / "b.obj").string(), out) == 0);
  write_mesh(dir / "tube.obj", test::pattern_tube(0.2, 0.9, 1.3, 24, 6, 1.0));
  const std::string svg = (dir / "t.svg").string();
  REQUIRE(test::run_drape("render --body " + (dir / "b.obj").string() + " --garment " + (dir / "tube.obj").string() +
                              " --out " + svg, out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("tube.obj on " + (dir / "b.obj").string()));
  CHECK(read(svg).find("<path ") != std::string::npos);
  // Strain and error need the model's template or a dataset's drape.
  CHECK(test::run_drape("render --body " + (dir / "b.obj").string() + " --garment " + (dir / "tube.obj").string() +
                            " --colour strain --out " + (dir / "s.svg").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--colour distance"));
}

TEST_CASE("predict's picture shows the body asked for and the warnings the command prints", "[cli][svg]") {
  // An outside check: its caption said "p = 0.00%" beside a 6xlarge shirt on a BMI 15 body that the command
  // reported 32 edges through the body and through itself at 44 pairs; render showed them, predict did not.
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run("env -u DRAPE_MODEL " + test::drape_program().string() + " predict --bmi 15 --garment-size 6xlarge --out " +
                        (dir / "g.obj").string() + " --svg " + (dir / "p.svg").string(),
                    out) == 0);
  REQUIRE_THAT(out, Catch::Contains("warning: the garment passes through itself"));
  const std::string svg = test::read_file(dir / "p.svg");
  CHECK_THAT(svg, Catch::Contains("for BMI 15, size 6xlarge") && Catch::Contains("warning: the garment passes through") &&
                      Catch::Contains("crossing the body, through itself"));  // (wrapped: the words, not the line)
}
