// `drape dataset merge`, `info` and `potential` on tiny datasets written here.
#include <catch2/catch.hpp>

#include <drape/io/dataset.hpp>
#include <drape/io/h5.hpp>

#include <algorithm>
#include <fstream>
#include <regex>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

DatasetLayout layout(std::size_t samples, int garment_vertices = 4) {
  DatasetLayout l;
  l.samples = samples;
  l.body_params = 2;
  l.body_vertices = 3;
  l.garment_vertices = garment_vertices;
  l.stats = {"energy", "seconds"};
  l.scene = "# tiny test scene\nbody: {model: parametric}\ngarment: tshirt\neffects: [gravity]\n";
  l.template_hash = "feedbeef";
  return l;
}

// Sample `i` of shard `shard`: its first body parameter identifies it.
DatasetSample sample(const DatasetLayout& l, int shard, std::size_t i) {
  DatasetSample s;
  s.body_params = Eigen::VectorXf::Constant(l.body_params, static_cast<float>(100 * shard + static_cast<int>(i)));
  s.body_vertices = MatrixRM::Constant(l.body_vertices, 3, 0.5f);
  s.garment_vertices = MatrixRM::Constant(l.garment_vertices, 3, 0.25f);
  s.split = static_cast<Split>(i % 3);
  s.stats = {{"energy", 1.0 + static_cast<double>(i)}};  // seconds not recorded
  return s;
}

// A shard with `done` of `samples` written; finished when all are.
void write_shard(const fs::path& path, int shard, std::size_t samples, std::size_t done, int garment_vertices = 4) {
  const DatasetLayout l = layout(samples, garment_vertices);
  DatasetWriter writer(path, l);
  for (std::size_t i = 0; i < done; ++i) writer.write(i, sample(l, shard, i));
  if (done == samples) writer.finish();
}

}  // namespace

TEST_CASE("drape dataset merge joins shards in order", "[cli][dataset]") {
  test::TempDir dir;
  write_shard(dir / "a.h5", 0, 3, 3);
  write_shard(dir / "b.h5", 1, 2, 2);
  const std::string a = (dir / "a.h5").string(), b = (dir / "b.h5").string(), all = (dir / "all.h5").string();
  std::string out;
  REQUIRE(test::run_drape("dataset merge --out " + all + " " + a + " " + b, out) == 0);
  CHECK_THAT(out, Catch::Contains("merged 5 samples from 2 shards"));
  {
    const DatasetReader merged(all);
    REQUIRE(merged.size() == 5);
    CHECK(merged.indices().size() == 5);
    CHECK(merged.sample(2).body_params[0] == 2.0f);    // a's last
    CHECK(merged.sample(3).body_params[0] == 100.0f);  // b's first
    CHECK(merged.layout().attributes.at("merged_from") == "a.h5\nb.h5");
  }
  // A finished dataset is not overwritten without --force.
  CHECK(test::run_drape("dataset merge --out " + all + " " + b, out) == 2);
  CHECK_THAT(out, Catch::Contains("all.h5") && Catch::Contains("--force"));
  REQUIRE(test::run_drape("dataset merge --force -o " + all + " " + b, out) == 0);
  CHECK(DatasetReader(all).size() == 2);
  // A quoted pattern joins the files it matches, in order, as the readers read it.
  REQUIRE(test::run_drape("dataset merge --force --out " + all + " '" + (dir / "[ab].h5").string() + "'", out) == 0);
  CHECK_THAT(out, Catch::Contains("merged 5 samples from 2 shards"));
}

TEST_CASE("drape dataset merge refuses unfinished or mismatched shards", "[cli][dataset]") {
  test::TempDir dir;
  write_shard(dir / "a.h5", 0, 3, 3);
  write_shard(dir / "c.h5", 2, 3, 1);  // leaves c.h5.partial with 1 of 3 done
  write_shard(dir / "d.h5", 3, 2, 2, 5);
  const std::string a = (dir / "a.h5").string(), c = (dir / "c.h5.partial").string(), d = (dir / "d.h5").string();
  std::string out;
  CHECK(test::run_drape("dataset merge --out " + (dir / "x.h5").string() + " " + a + " " + c, out) == 2);
  CHECK_THAT(out, Catch::Contains("c.h5.partial") && Catch::Contains("only 1 of 3 samples are done"));
  CHECK(!fs::exists(dir / "x.h5"));
  REQUIRE(test::run_drape("dataset merge --allow-incomplete --out " + (dir / "x.h5").string() + " " + a + " " + c, out) == 0);
  CHECK_THAT(out, Catch::Contains("merged 4 samples"));
  CHECK(DatasetReader(dir / "x.h5").sample(3).body_params[0] == 200.0f);

  CHECK(test::run_drape("dataset merge --out " + (dir / "y.h5").string() + " " + a + " " + d, out) == 2);
  CHECK_THAT(out, Catch::Contains("d.h5") && Catch::Contains("garment_vertices"));
  CHECK(test::run_drape("dataset merge --out " + (dir / "y.h5").string() + " " + (dir / "absent.h5").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("absent.h5"));
  CHECK(test::run_drape("dataset merge " + a, out) == 2);  // no --out
  CHECK_THAT(out, Catch::Contains("out"));
}

TEST_CASE("drape dataset info shows layout, splits, stats and the scene", "[cli][dataset]") {
  test::TempDir dir;
  write_shard(dir / "a.h5", 0, 3, 3);
  write_shard(dir / "b.h5", 1, 4, 2);
  std::string out;
  REQUIRE(test::run_drape("dataset info " + (dir / "a.h5").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("drape dataset, complete") && Catch::Contains("samples   3, done 3") &&
                      Catch::Contains("P = 2") && Catch::Contains("Nb = 3") && Catch::Contains("Ng = 4") &&
                      Catch::Contains("train 1, val 1, test 1") && Catch::Contains("stats     2 per sample") && Catch::Contains("energy: 3 of 3 recorded, mean 2, min 1, max 3") &&
                      Catch::Contains("seconds: 0 of 3 recorded") && Catch::Contains("template  feedbeef") &&
                      Catch::Contains("scene     4 lines") && Catch::Contains("| # tiny test scene") &&
                      Catch::Contains("| effects: [gravity]"));

  REQUIRE(test::run_drape("dataset info --scene-lines 1 " + (dir / "b.h5.partial").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("drape dataset, incomplete") && Catch::Contains("samples   4, done 2") &&
                      Catch::Contains("train 1, val 1, test 0") && Catch::Contains("| # tiny test scene") &&
                      Catch::Contains("(3 more)"));

  REQUIRE(test::run_drape("dataset merge --out " + (dir / "all.h5").string() + " " + (dir / "a.h5").string() + " " +
                        (dir / "a.h5").string(), out) == 0);
  REQUIRE(test::run_drape("dataset info " + (dir / "all.h5").string(), out) == 0);
  CHECK_THAT(out, Catch::Contains("samples   6, done 6") && Catch::Contains("merged_from: a.h5, a.h5"));

  CHECK(test::run_drape("dataset info " + (dir / "absent.h5").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("absent.h5"));
  CHECK(test::run_drape("dataset", out) == 2);
  CHECK(test::run_drape("dataset mrege", out) == 2);
  CHECK_THAT(out, Catch::Contains("did you mean 'merge'"));
  REQUIRE(test::run_drape("dataset --help", out) == 0);
  CHECK_THAT(out, Catch::Contains("drape dataset merge") && Catch::Contains("drape dataset info"));
}

TEST_CASE("drape dataset potential re-evaluates stored drapes under a scene", "[cli][dataset]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string data = (dir / "tiny.h5").string(), scene = (dir / "tiny.yaml").string();
  std::string out;
  REQUIRE(test::run_drape("generate " + scene + " --count 4 --bmi 15:40 --seed 2 --out " + data, out) == 0);
  REQUIRE(test::run_drape("dataset potential " + data + " --scene " + scene + " --split train,val,test", out) == 0);
  INFO(out);
  // Under the scene that made them, the energies are the ones the simulation
  // recorded (up to the float32 storage of the vertices).
  const DatasetReader reader(data);
  const std::vector<std::size_t> all = reader.indices();
  for (const char* effect : {"gravity", "stretching", "bending", "collision"}) {
    const std::vector<double> recorded = reader.stat(std::string("energy_") + effect, all);
    double mean = 0;
    for (double v : recorded) mean += v / static_cast<double>(recorded.size());
    std::smatch m;
    const std::regex row("\\| " + std::string(effect) + " \\| ([-0-9.e+]+) \\|");
    REQUIRE(std::regex_search(out, m, row));
    CHECK(std::stod(m[1]) == Approx(mean).epsilon(2e-3).margin(1e-6));
  }
  CHECK_THAT(out, Catch::Contains("4 drapes under the effects of") && Catch::Contains("| L_p (total) |") &&
                      Catch::Contains("penetration p: mean"));

  // Another resolution of the garment is refused with both sizes named.
  std::ofstream(dir / "coarse.yaml") << "base: tiny.yaml\ngarment: {template: tshirt, params: {resolution: coarse}}\n";
  CHECK(test::run_drape("dataset potential " + data + " --scene " + (dir / "coarse.yaml").string(), out) == 2);
  CHECK_THAT(out, Catch::Contains("but the scene's garment has"));
}

TEST_CASE("drape dataset slim and expand: the bodies rebuilt by the scene's body model are the simulated ones", "[cli][dataset]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string data = (dir / "tiny.h5").string(), slim = (dir / "slim.h5").string(),
                    full = (dir / "full.h5").string();
  std::string out;
  REQUIRE(test::run_drape("generate " + (dir / "tiny.yaml").string() + " --count 3 --bmi 15:40 --seed 4 --out " + data, out) == 0);
  REQUIRE(test::run_drape("dataset slim " + data + " --out " + slim, out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("3 samples without body vertices"));
  CHECK(fs::file_size(slim) * 3 < fs::file_size(data));
  REQUIRE(test::run_drape("dataset info " + slim, out) == 0);
  CHECK_THAT(out, Catch::Contains("(not stored: a slim dataset, rebuilt as they are read, each checked against the witness of the simulated body)"));
  // A command that needs the bodies reads the slim file as it is: they are rebuilt as it reads.
  CHECK(test::run_drape("dataset potential " + slim + " --scene " + (dir / "tiny.yaml").string(), out) == 0);
  CHECK(test::run_drape("dataset slim " + data + " --out " + slim, out) == 2);  // never overwritten silently
  CHECK_THAT(out, Catch::Contains("--force"));
  // --drop by the generator's global index (a count of 3 numbers them 0-2): listed in the copy's info.
  const std::string dropped = (dir / "dropped.h5").string();
  REQUIRE(test::run_drape("dataset slim " + data + " --out " + dropped + " --drop 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("2 samples without body vertices (1 global index dropped: 1 row)"));
  // The same file merged twice (oversampling) repeats each index: a drop removes both rows, and says so.
  REQUIRE(test::run_drape("dataset merge " + data + " " + data + " --out " + (dir / "twice.h5").string() + " --drop 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("merged 4 samples") && Catch::Contains("(1 global index dropped: 2 rows, as an index repeats"));
  REQUIRE(test::run_drape("dataset info " + dropped, out) == 0);
  CHECK_THAT(out, Catch::Contains("dropped: 1"));
  CHECK(test::run_drape("dataset slim " + data + " --out " + (dir / "x.h5").string() + " --drop 3", out) == 2);
  CHECK_THAT(out, Catch::Contains("--drop 3: no sample"));
  CHECK(test::run_drape("dataset slim " + data + " --out " + (dir / "x.h5").string() + " --drop 1,x", out) == 2);
  CHECK_THAT(out, Catch::Contains("'x' is not a global index"));
  // A quoted pattern of shards is expanded as the readers expand it (it was "no such file": an outside check).
  CHECK(test::run_drape("dataset merge --out " + (dir / "p.h5").string() + " '" + (dir / "nomatch-*.h5").string() + "'", out) == 2);
  CHECK_THAT(out, Catch::Contains("no dataset file matches this pattern"));
  // An empty list dropped nothing without a word (a shell variable never set: an outside check).
  CHECK(test::run_drape("dataset slim " + data + " --out " + (dir / "x.h5").string() + " --drop ''", out) == 2);
  CHECK_THAT(out, Catch::Contains("--drop is empty"));
  CHECK_FALSE(fs::exists(dir / "x.h5"));

  REQUIRE(test::run_drape("dataset expand " + slim + " --out " + full, out) == 0);
  CHECK_THAT(out, Catch::Contains("rebuilt by body model 'parametric'"));
  const DatasetReader made(data), rebuilt(full);
  const std::vector<std::size_t> all = made.indices();
  REQUIRE(rebuilt.indices() == all);
  const Tensor want = made.body_vertices(all), got = rebuilt.body_vertices(all);
  REQUIRE(got.size() == want.size());
  float worst = 0;
  for (std::size_t k = 0; k < want.size(); ++k) worst = std::max(worst, std::abs(got.data()[k] - want.data()[k]));
  CHECK(worst < 1e-6f);  // metres: the float parameters' rounding, nothing more
  const Tensor g0 = made.garment_vertices(all), g1 = rebuilt.garment_vertices(all);
  CHECK(std::equal(g0.data(), g0.data() + g0.size(), g1.data()));

  // A body model that no longer builds the simulated bodies (here every
  // sample's hips girth moved 0.02 towards the mean, as a changed body model
  // would move its body) is refused by every reader of the slim file, naming
  // the file and the sample, not paired silently with the stored drape.
  const std::string changed = (dir / "changed.h5").string();
  fs::copy_file(slim, changed);
  {
    h5::File file = h5::File::open(changed, h5::Access::ReadWrite);
    std::vector<float> params = file.read<float>("/bodies/params");
    const std::size_t p = params.size() / 3, hips = 6;  // the parametric body's shape: height, sex, weight, chest, waist, belly, hips
    for (std::size_t row = 0; row < 3; ++row) {
      float& girth = params[row * p + hips];
      girth += girth > 0 ? -0.02f : 0.02f;
    }
    file.write_rows("/bodies/params", 0, 3, params.data());
  }
  for (const std::string& command : {"dataset expand " + changed + " --out " + (dir / "bad.h5").string(),
                                     "dataset potential " + changed + " --scene " + (dir / "tiny.yaml").string()}) {
    INFO(command);
    CHECK(test::run_drape(command, out) == 2);
    CHECK_THAT(out, Catch::Contains("changed.h5: sample ") && Catch::Contains("'s body, rebuilt from its parameters") &&
                        Catch::Contains("not the body its drape was simulated on"));
  }
  CHECK_FALSE(fs::exists(dir / "bad.h5"));
}

TEST_CASE("merge --mixed-sizes refuses shards whose scenes differ in more than the garment's size", "[cli][dataset]") {
  // An outside check: --mixed-sizes compared nothing of the scenes, and a
  // shard without friction merged with one with it, labelled as the first.
  test::TempDir dir;
  std::string scene = test::tiny_simulation_scene();
  std::ofstream(dir / "a.yaml") << scene;
  const std::string stiffness = "stiffness: 1.0e8";
  std::ofstream(dir / "b.yaml") << scene.replace(scene.find(stiffness), stiffness.size(), "stiffness: 2.0e8");
  std::string out;
  for (const char* name : {"a", "b"})
    REQUIRE(test::run_drape("generate " + (dir / (std::string(name) + ".yaml")).string() + " --count 1 --seed 1 --threads 1 --out " +
                                (dir / (std::string(name) + ".h5")).string(),
                            out) == 0);
  CHECK(test::run_drape("dataset merge --mixed-sizes --out " + (dir / "m.h5").string() + " " + (dir / "a.h5").string() + " " +
                            (dir / "b.h5").string(),
                        out) == 2);
  CHECK_THAT(out, Catch::Contains("their scenes differ in more than the garment's size"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.h5"));
  // Without it, the difference says each value with its own file (the first
  // shard's value was said to be "in the file" of the shard named first).
  CHECK(test::run_drape("dataset merge --out " + (dir / "m.h5").string() + " " + (dir / "a.h5").string() + " " +
                            (dir / "b.h5").string(),
                        out) == 2);
  CHECK_THAT(out, Catch::Contains("b.h5: cannot merge with ") && Catch::Contains("stiffness: 2.0e8}' here, '") &&
                      Catch::Contains("stiffness: 1.0e8}' in a.h5"));
}

TEST_CASE("dataset potential measures a sized dataset's drapes each in the size its body wore", "[cli][dataset]") {
  // An outside check: the dataset's own scene (size: auto) was refused, and
  // one size named measured every other size's drape against the wrong
  // pattern (stretching 37.9 J where the simulator stored 0.096 J).
  test::TempDir dir;
  const std::filesystem::path shard = test::source_dir() / "datasets/bodyspace-thin-sized/shard-0-of-2.h5";
  const DatasetReader reader(shard);
  std::ofstream(dir / "own.yaml") << reader.layout().scene;
  std::string out;
  REQUIRE(test::run_drape("dataset potential " + shard.string() + " --scene " + (dir / "own.yaml").string() + " --split test",
                          out) == 0);
  INFO(out);
  // The simulator's own energies of the same drapes, stored with them.
  const std::vector<std::size_t> test_split = reader.indices(Split::Test);
  REQUIRE_FALSE(test_split.empty());
  double stored = 0;
  for (double e : reader.stat("energy_stretching", test_split)) stored += e / static_cast<double>(test_split.size());
  std::smatch m;
  REQUIRE(std::regex_search(out, m, std::regex("\\| stretching \\| ([0-9.e+-]+) \\|")));
  CHECK(std::stod(m[1]) == Approx(stored).epsilon(1e-3));
  // One size named for all of them is refused, naming the sample.
  std::string one = reader.layout().scene;
  one.replace(one.find("size: auto"), 10, "size: regular");
  std::ofstream(dir / "regular.yaml") << one;
  const std::vector<double> sizes = reader.stat("garment_size", test_split);
  REQUIRE(std::any_of(sizes.begin(), sizes.end(), [](double f) { return f != 0.0; }));  // some wore another size than regular (flag 0)
  CHECK(test::run_drape("dataset potential " + shard.string() + " --scene " + (dir / "regular.yaml").string() +
                            " --split test", out) == 2);
  CHECK_THAT(out, Catch::Contains("wore another garment size"));
}
