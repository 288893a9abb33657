// Options a command cannot honour are refused before any work, not ignored,
// clamped or left to fail half way (found by a sweep of bad input as a new
// user would bring it, 2026-12-06): each exits 2 with one line naming the
// option, and writes nothing.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "test_support.hpp"

using namespace drape;

TEST_CASE("a thread count beyond what any machine runs, or an output name too long for the files beside it, is refused before the work starts", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  const std::string scene = (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string();
  // 100,000 crashed OpenMP's start-up, 5,000 hung in it.
  for (const std::string threads : {"100000", "5000", "-1"}) {
    INFO(threads);
    CHECK(test::run_drape("simulate " + scene + " --threads " + threads + " --out " + (dir / "g.obj").string(), out) == 2);
    CHECK_THAT(out, Catch::Contains("--threads " + threads + ": expected 0 (every core) to 1024"));
  }
  CHECK(test::run_drape("generate " + scene + " --count 1 --threads 2000 --out " + (dir / "d.h5").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--threads 2000"));
  CHECK_FALSE(std::filesystem::exists(dir / "g.obj"));
  CHECK_FALSE(std::filesystem::exists(dir / "d.h5"));
  // A name the file system takes, but not with drape's partial and temporary
  // files beside it: train failed after an epoch ("H5Fcreate failed").
  const std::string long_name = (dir / (std::string(230, 'x') + ".h5")).string();
  CHECK(test::run_drape("generate " + scene + " --count 1 --out " + long_name, out) == 2);
  CHECK_THAT(out, Catch::Contains("its name is 233 characters long") && Catch::Contains("give a shorter name"));
  CHECK(test::run_drape("train " + (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string() + " --data " +
                            (test::source_dir() / "datasets/bodyspace2000/shard-00-of-40.h5").string() + " --epochs 1 --out " +
                            long_name, out) == 2);
  CHECK_THAT(out, Catch::Contains("characters long"));
}

TEST_CASE("two outputs naming one file are refused, however the path is spelt", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  const std::string a = (dir / "o.obj").string(), b = (dir / "." / "o.obj").string();
  CHECK(test::run_drape("predict --bmi 30 --out " + a + " --body-out " + b, out) == 2);
  CHECK_THAT(out, Catch::Contains("--out and --body-out name the same file"));
  CHECK_FALSE(std::filesystem::exists(a));
  // A picture needs a picture's extension: --svg o.png wrote SVG text into a .png.
  CHECK(test::run_drape("predict --bmi 30 --out " + a + " --svg " + (dir / "o.png").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--svg") && Catch::Contains("expected a .svg"));
}

TEST_CASE("drape body refuses options meant for another of its uses", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --param rig=human --bmi 30 --out " + (dir / "b.obj").string(), out) == 0);
  // --unpose reads the body off the mesh: a BMI, height or sex given beside it was ignored.
  for (const std::string other : {"--bmi 30", "--height 1.8", "--sex 0", "--girths 0.5", "--out-dir d"}) {
    INFO(other);
    CHECK(test::run_drape("body --param rig=human --unpose " + (dir / "b.obj").string() + " " + other, out) == 2);
    CHECK_THAT(out, Catch::Contains("--unpose reads the pose and the body off the mesh; leave out --"));
  }
  // The human rig's mesh to the body model's default rig: the count, and the rig that has it.
  CHECK(test::run_drape("body --unpose " + (dir / "b.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("has 6904 vertices, expected 6490") && Catch::Contains("--param rig=human"));
  // One body: the options of --sample were ignored without a word.
  CHECK(test::run_drape("body --bmi 30 --out-dir " + (dir / "d").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--out-dir goes with --sample"));
  CHECK(test::run_drape("body --bmi 30 --svg " + (dir / "s.svg").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--svg goes with --sample"));
  CHECK(test::run_drape("body --sample 2 --out-dir " + (dir / "d").string() + " --out " + (dir / "x.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--sample writes its bodies into --out-dir"));
  // A parameter given twice kept the last silently.
  CHECK(test::run_drape("body --param rig=human --param rig=mannequin --bmi 30", out) == 2);
  CHECK_THAT(out, Catch::Contains("--param rig is given twice"));
  // Not a body model: one line, with the kind's article.
  CHECK(test::run_drape("body --model barrier --bmi 30", out) == 2);
  CHECK_THAT(out, Catch::Contains("'barrier' is an energy, not a body model") && !Catch::Contains("drape body: plugin"));
  CHECK_FALSE(std::filesystem::exists(dir / "d"));
  CHECK_FALSE(std::filesystem::exists(dir / "x.obj"));
}

TEST_CASE("drape body --sample checks its ranges before drawing, and writes nothing when it refuses", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  const std::string folder = (dir / "bodies").string();
  // A range reaching past what the model makes is refused as given, not at
  // the first value drawn past it (9.5:30 passed whenever no draw fell below 10).
  CHECK(test::run_drape("body --sample 3 --bmi 9.5:30 --seed 3 --out-dir " + folder, out) == 2);
  CHECK_THAT(out, Catch::Contains("--bmi 9.5:30 reaches outside what body parametric makes, BMI 10 to 65"));
  CHECK(test::run_drape("body --sample 2 --height 1.0:1.6 --out-dir " + folder, out) == 2);
  CHECK_THAT(out, Catch::Contains("--height 1:1.6") && Catch::Contains("height 1 m is outside the reachable range"));
  // Just past a bound, printed as given ("sex 1 is outside [0, 1]" before).
  CHECK(test::run_drape("body --bmi 30 --sex 1.0000001 --out " + (dir / "b.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("sex 1.0000001 is outside [0, 1]"));
  CHECK(test::run_drape("body --sample 2 --girths 2 --out-dir " + folder, out) == 2);
  CHECK_FALSE(std::filesystem::exists(folder));  // not even an empty folder
  std::ofstream(dir / "a_file") << "x";
  CHECK(test::run_drape("body --sample 1 --out-dir " + (dir / "a_file").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("is a file, not a folder"));
  // In range: written as before.
  REQUIRE(test::run_drape("body --sample 2 --bmi 20:30 --out-dir " + folder, out) == 0);
  CHECK(std::filesystem::exists(std::filesystem::path(folder) / "body_00001.obj"));
}

TEST_CASE("counts and options that only apply elsewhere are refused, not clamped or ignored", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  CHECK(test::run_drape("bench infer --model " + (test::source_dir() / "models/tshirt-coarse.h5").string() + " --repeats 0", out) == 2);
  CHECK_THAT(out, Catch::Contains("--repeats 0: expected at least 1"));
  CHECK(test::run_drape("bench contact --repeats -1", out) == 2);
  CHECK(test::run_drape("bench contact --garment-level -1", out) == 2);
  CHECK_THAT(out, Catch::Contains("--garment-level -1"));
  CHECK(test::run_drape("render --bmi 30 --sample 5 --out " + (dir / "r.html").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--sample picks a sample of --data"));
  const std::string scene = (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string();
  CHECK(test::run_drape("optimize --scene " + scene + " --bmi 30 --shard 3/4 --out " + (dir / "o.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--shard goes with --data"));
  // --girth takes a comma list as --pose does (it said "the value is not a number").
  REQUIRE(test::run_drape("body --bmi 30 --girth chest=0.1,waist=0.05", out) == 0);
  CHECK_THAT(out, Catch::Contains("chest = 0.1") && Catch::Contains("waist = 0.05"));
  // A scene parameter's range as written in a scene, not with six decimals.
  CHECK(test::run_drape("simulate " + scene + " --height 150", out) == 2);
  CHECK_THAT(out, Catch::Contains("[0.5, 2.5]"));
}

TEST_CASE("generate and optimize refuse bad values before their output is begun, naming the option", "[cli][options]") {
  // Found by an outside check: these were refused after the output's
  // .partial was made, whose resume then refused the corrected command.
  test::TempDir dir;
  std::string out;
  const std::string scene = (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string();
  const std::string generate = "generate " + scene + " --count 2 --threads 1 --out " + (dir / "a.h5").string();
  CHECK(test::run_drape(generate + " --height 0.2", out) == 2);
  CHECK_THAT(out, Catch::Contains("height 0.2:0.2, sex 1:1: body parametric: height 0.2 m is outside the reachable range"));
  CHECK(test::run_drape(generate + " --sex 2", out) == 2);
  CHECK_THAT(out, Catch::Contains("height 1.75:1.75, sex 2:2: body parametric: sex 2 is outside [0, 1]"));
  // A range draws one of its ends: 0.3:0.6 gave only 0.3 and 0.6 (an outside check).
  CHECK(test::run_drape(generate + " --sex 0.3:0.6", out) == 2);
  CHECK_THAT(out, Catch::Contains("--sex 0.3:0.6: a range draws female (0) or male (1) with equal odds, so it is 0:1"));
  CHECK_FALSE(std::filesystem::exists(dir / "a.h5.partial"));
  CHECK(test::run_drape(generate + " --bmi nan", out) == 2);  // it said "expected lo <= hi"
  CHECK_THAT(out, Catch::Contains("--bmi 'nan': not a number (NaN)"));
  // More shards than samples: some shard would be an empty dataset sealed complete.
  CHECK(test::run_drape(generate + " --shard 0/4", out) == 2);
  CHECK_THAT(out, Catch::Contains("shard 0/4: 4 shards of a set of 2 samples leave some shards empty"));
  // A negative seed was read as 2^64 - 1.
  CHECK(test::run_drape(generate + " --seed -1", out) == 2);
  CHECK_THAT(out, Catch::Contains("--seed -1: expected a whole number 0 or more"));
  for (const std::string bad : {"--iters -1", "--lr -1", "--lr 0", "--lr 1e300"}) {
    INFO(bad);
    CHECK(test::run_drape("optimize --scene " + scene + " --data " + (dir / "none.h5").string() + " " + bad + " --out " +
                              (dir / "o.h5").string(), out) == 2);
    CHECK_THAT(out, Catch::Contains(bad.substr(0, bad.find(' ')) + " "));
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) FAIL_CHECK("left behind: " << entry.path());
}

TEST_CASE("a number option given infinity or NaN and an empty or unused list are refused", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  const std::string mesh = (dir / "quad.obj").string();
  std::ofstream(mesh) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  // spectral printed "inf mm" errors; hierarchy took an infinite ratio.
  CHECK(test::run_drape("spectral --mesh " + mesh + " --unit inf", out) == 2);
  CHECK_THAT(out, Catch::Contains("--unit inf: not a finite number"));
  CHECK(test::run_drape("hierarchy --mesh " + mesh + " --ratio nan --out " + (dir / "h").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--ratio") && Catch::Contains("not a finite number"));
  CHECK_FALSE(std::filesystem::exists(dir / "h"));
  CHECK(test::run_drape("predict --bmi inf --out " + (dir / "g.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--bmi inf: not a finite number"));
  // An empty list was the default: a shell variable never set.
  CHECK(test::run_drape("body --bmi 30 --girth '' --out " + (dir / "b.obj").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--girth is empty"));
  CHECK(test::run_drape("generate " + (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string() +
                            " --count 1 --poses draw --pose-range '' --out " + (dir / "d.h5").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("--pose-range is empty"));
  CHECK_FALSE(std::filesystem::exists(dir / "b.obj"));
  CHECK_FALSE(std::filesystem::exists(dir / "d.h5"));
  // A size the graph never names sized nothing.
  CHECK(test::run_drape("graph check " + (test::source_dir() / "graphs/drape.yaml").string() + " --dim garmnet_vertices=991", out) == 2);
  CHECK_THAT(out, Catch::Contains("--dim garmnet_vertices: the graph's inputs use no size of that name") &&
                      Catch::Contains("garment_vertices"));
  CHECK(test::run_drape("dataset info " + (test::source_dir() / "datasets/bodyspace2000/shard-00-of-40.h5").string() +
                            " --scene-lines -1", out) == 2);
  CHECK_THAT(out, Catch::Contains("--scene-lines -1: expected 0 or more"));
}

TEST_CASE("an HDF5 output named with another format's extension is refused before any work", "[cli][options]") {
  test::TempDir dir;
  std::string out;
  const std::string data = (test::source_dir() / "datasets/bodyspace2000/shard-00-of-40.h5").string();
  // generate --out drapes.obj wrote a dataset into a file every mesh viewer then failed to read.
  CHECK(test::run_drape("generate " + (test::source_dir() / "graphs/scenes/tshirt_coarse.yaml").string() +
                            " --count 1 --out " + (dir / "drapes.OBJ").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("drape writes an HDF5 file here, not a .obj file: name it drapes.h5"));
  CHECK(test::run_drape("dataset slim " + data + " --out " + (dir / "s.ply").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("not a .ply file"));
  CHECK(test::run_drape("train " + (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string() + " --data " + data +
                            " --epochs 1 --out " + (dir / "m.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("not a .yaml file"));
  CHECK(test::run_drape("model set " + (test::source_dir() / "models/tshirt-coarse.h5").string() +
                            " --set post.enabled=false --out " + (dir / "m.json").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("not a .json file"));
  CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("a missing positional argument is named as the usage line shows it", "[cli][options]") {
  std::string out;
  // It was "the option '--file' is required", an option the usage line never shows.
  CHECK(test::run_drape("graph check", out) == 2);
  CHECK_THAT(out, Catch::Contains("missing file: give it after the command") && !Catch::Contains("'--file'"));
  CHECK(test::run_drape("dataset info", out) == 2);
  CHECK_THAT(out, Catch::Contains("missing file"));
  // Ranges as a scene writes numbers (they were [1.000000, 4096.000000]).
  REQUIRE(test::run_drape("plugins --kind encoder", out) == 0);
  CHECK_THAT(out, Catch::Contains("range [1, 4096]") && !Catch::Contains(".000000"));
}

TEST_CASE("a drape file of another kind is named as what it is and the command that reads it", "[cli][options]") {
  // An experiment given to graph check was "unknown key 'name'; did you mean 'base'?".
  std::string out;
  const auto file = [](const char* name) { return (test::source_dir() / name).string(); };
  CHECK(test::run_drape("graph check " + file("graphs/experiments/table_6_6.yaml"), out) == 2);
  CHECK_THAT(out, Catch::Contains("table_6_6.yaml:1: this is an experiment file") && Catch::Contains("drape experiment"));
  CHECK(test::run_drape("graph check " + file("graphs/scenes/tshirt_coarse.yaml"), out) == 2);
  CHECK_THAT(out, Catch::Contains("this is a scene file") && Catch::Contains("drape simulate"));
  CHECK(test::run_drape("simulate " + file("graphs/drape.yaml") + " --bmi 30", out) == 2);
  CHECK_THAT(out, Catch::Contains("this is a graph file") && Catch::Contains("a scene file has body, garment"));
  CHECK(test::run_drape("experiment " + file("graphs/scenes/tshirt.yaml") + " --dry-run", out) == 2);
  CHECK_THAT(out, Catch::Contains("this is a scene file"));
}

TEST_CASE("drape graph given a file where its action goes says to put check first", "[cli][options]") {
  // It read the file as the action and said "missing file" of the file it was given.
  std::string out;
  const std::string graph = (test::source_dir() / "graphs/drape.yaml").string();
  CHECK(test::run_drape("graph " + graph, out) == 2);
  CHECK_THAT(out, Catch::Contains("is a file, not an action: drape graph check " + graph));
  CHECK(test::run_drape("graph chek " + graph, out) == 2);
  CHECK_THAT(out, Catch::Contains("unknown action 'chek'"));
}

TEST_CASE("a graph whose weights cannot be allocated names its node", "[cli][options]") {
  // An mlp of widths [65536] over 20,000 rows (15 GB of weights, each value in
  // range) ended in a bare "failed: std::bad_alloc", exit 1. Run under a 3 GB
  // address-space limit, so the allocation fails at once, whatever the machine.
  test::TempDir dir;
  std::ofstream(dir / "big.yaml") << "inputs:\n  body: [body_vertices, 3]\n  target: [garment_vertices, 3]\nnodes:\n"
                                     "  e: {type: cnn1d, in: body, params: {channels: [4]}}\n"
                                     "  g: {type: mlp, in: e.global, params: {widths: [65536], rows: 20000}}\n"
                                     "outputs: {garment: g}\n";
  std::string out;
  CHECK(test::run("ulimit -v 3000000; " + test::drape_program().string() + " graph check " + (dir / "big.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("big.yaml:6: node 'g' (mlp): its weights need more memory than this machine gives"));
}
