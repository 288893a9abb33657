// `drape experiment`: a miniature experiment with every kind of row runs end to
// end, writes its table as Markdown and CSV next to the seed's numbers, reuses
// its datasets and outputs when run again, and refuses bad files clearly.
#include <catch2/catch.hpp>

#include <drape/io/dataset.hpp>
#include <drape/experiment/experiment.hpp>
#include <drape/io/checkpoint.hpp>

#include <chrono>
#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string tiny_experiment() {
  const std::string graph = (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string();
  const std::string tailornet = (test::source_dir() / "graphs/baselines/tailornet_no_anchor.yaml").string();
  return "name: tiny\n"
         "title: a miniature of every kind of row\n"
         "datasets:\n"
         "  shirts: {scene: tiny.yaml, count: 10, bmi: \"15:40\", seed: 2}\n"
         "training: {epochs: 2, batch: 4, lr: 1.0e-3, schedule: constant, patience: 5, seed: 0, monitor: l2}\n"
         "columns: [ME, p, L_p, L_st, e2e_h, infer]\n"
         "rows:\n"
         "  - {name: Simulation, simulation: shirts, seed: {L_p: 1.0e-4, p: 0.0}}\n"
         "  - {name: half, train: " + graph + ", fraction: 0.5, physics: tiny.yaml, seed: {ME: 0.33}}\n"
         "  - {name: half-opt, optimize: half, scene: tiny.yaml, iterations: 3}\n"
         "  - {name: half-retrain, train: " + graph + ", on_optimized: half, scene: tiny.yaml, iterations: 3}\n"
         "  - {name: tn, train: " + tailornet + "}\n"
         "  - {name: tn-post, evaluate: tn, set: {post.enabled: 'true', post.epsilon: 0.003}}\n";
}

// tiny.yaml and exp.yaml in `dir`: one dataset of 10 tiny drapes and one
// row training the MLP baseline on it for `epochs` (its outputs in runs/<name>/).
void write_one_row_experiment(const fs::path& dir, const std::string& name, int epochs) {
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::ofstream(dir / "exp.yaml") << "name: " << name << "\n"
                                  << "datasets:\n"
                                     "  shirts: {scene: tiny.yaml, count: 10, bmi: \"15:40\", seed: 2}\n"
                                  << "training: {epochs: " << epochs
                                  << ", batch: 4, lr: 1.0e-3, schedule: constant, patience: 5, seed: 0}\n"
                                     "columns: [ME]\n"
                                     "rows:\n"
                                     "  - {name: mlp, train: "
                                  << (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string() << "}\n";
}

std::string read(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("experiment: every kind of row runs, the table is written, and a second run reuses everything", "[experiment]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::ofstream(dir / "tiny_experiment.yaml") << tiny_experiment();
  const std::string command = "cd " + dir.path().string() + " && " + test::drape_program().string() +
                              " experiment tiny_experiment.yaml --threads 2";
  std::string out;
  REQUIRE(test::run(command, out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("$ drape generate"));
  CHECK_THAT(out, Catch::Contains("--fraction 0.5"));
  CHECK_THAT(out, Catch::Contains("--monitor l2"));  // every training row's best epoch by its L2 loss
  CHECK_THAT(out, Catch::Contains("--split train,val --iters 3"));
  const fs::path work = dir / "runs/tiny";
  const std::string md = read(work / "table.md"), csv = read(work / "table.csv");
  CHECK_THAT(md, Catch::Contains("| half |"));
  CHECK_THAT(md, Catch::Contains("/ 0.33 |"));  // the seed's number next to ours
  // The seed's energies are in units it does not state: given apart, not beside ours.
  CHECK_THAT(md, Catch::Contains("| L_p (J) * |"));
  CHECK_THAT(md, Catch::Contains("* The seed's L_p (Simulation 1.00e-04) does not compare with ours"));
  CHECK_THAT(md, !Catch::Contains("/ 1.00e-04"));
  CHECK_THAT(csv, Catch::StartsWith("row,ME,ME_seed,p,p_seed,L_p,L_p_seed,L_st,L_st_seed,e2e_h,e2e_h_seed,infer,infer_seed"));
  // Four rows, each with the values that apply to it.
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    INFO(line);
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    REQUIRE(f.size() >= 13);
    const bool network = f[0] == "half" || f[0] == "half-retrain" || f[0] == "tn" || f[0] == "tn-post";
    CHECK(f[1].empty() == !network);   // ME only for networks
    CHECK_FALSE(f[3].empty());         // p for every row
    CHECK(f[5].empty() == (f[0] == "half-retrain" || f[0] == "tn" || f[0] == "tn-post"));  // L_p: physics asked for, optimised, simulated
    if (f[0] == "tn-post") CHECK(std::stod(f[3]) == 0.0);  // pushed out: no vertex inside the body
    CHECK_FALSE(f[11].empty());        // inference time
    if (!f[5].empty()) CHECK(std::isfinite(std::stod(f[5])));
  }
  CHECK(rows == 6);
  CHECK_THAT(out, Catch::Contains("--set post.enabled=true --set post.epsilon=0.003"));
  // The retraining learnt from the optimised train+val drapes of 'half'.
  const DatasetReader optimized(work / "half.optimized-3.h5");
  CHECK(optimized.indices().size() == 9);  // 8 train + 1 val of 10
  CHECK(optimized.indices("test").empty());

  // Again: nothing is generated, trained or optimised; the same table comes out.
  std::string again;
  REQUIRE(test::run(command, again) == 0);
  INFO(again);
  CHECK_THAT(again, !Catch::Contains("$ drape generate"));
  CHECK_THAT(again, !Catch::Contains("$ drape train"));
  CHECK_THAT(again, !Catch::Contains("$ drape optimize"));
  CHECK_THAT(again, Catch::Contains("reusing"));
  CHECK(read(work / "table.csv") == csv);
  CHECK_THAT(md, Catch::Contains("shirts = tiny.yaml, 10 bodies, BMI 15:40, seed 2;"));

  // The same dataset given by hand: the heading names the file and its split
  // (8 / 1 / 1 of 10), not the experiment file's recipe.
  fs::path generated;
  for (const auto& entry : fs::directory_iterator(dir / "runs/data"))
    if (entry.path().extension() == ".h5") generated = entry.path();
  REQUIRE_FALSE(generated.empty());
  std::string given;
  // A misspelt key is refused before any work, with the keys there are.
  std::string typo;
  CHECK(test::run(command + " --data shrits=" + generated.string(), typo) == 2);
  CHECK_THAT(typo, Catch::Contains("no dataset 'shrits'; did you mean 'shirts'?"));
  REQUIRE(test::run(command + " --data shirts=" + generated.string(), given) == 0);
  INFO(given);
  const std::string given_md = read(work / "table.md");
  CHECK_THAT(given_md, Catch::Contains("--data shirts=" + generated.filename().string() + "`"));
  CHECK_THAT(given_md, Catch::Contains("shirts = " + generated.filename().string() +
                                       " (given), 10 samples: 8 train, 1 val, 1 test;"));
  CHECK_THAT(given_md, !Catch::Contains("BMI 15:40"));
}

TEST_CASE("experiment files: errors name the file, the line and the key", "[experiment]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  auto error_of = [&](const std::string& text) {
    std::ofstream(dir / "e.yaml") << text;
    return test::message_of([&] { parse_experiment_file(dir / "e.yaml"); });
  };
  const std::string head = "name: e\ndatasets:\n  shirts: {scene: tiny.yaml, count: 10}\ncolumns: [ME]\n";
  CHECK_THAT(error_of(head + "rows:\n  - {name: a, train: nowhere.yaml}\n"), Catch::Contains("e.yaml:6") && Catch::Contains("no file"));
  CHECK_THAT(error_of(head + "rows:\n  - {name: a, train: tiny.yml}\n"), Catch::Contains("did you mean 'tiny.yaml'"));
  CHECK_THAT(error_of(head + "rows:\n  - {name: a, simulation: shrits}\n"),
             Catch::Contains("e.yaml:6") && Catch::Contains("did you mean 'shirts'"));
  CHECK_THAT(error_of(head + "rows:\n  - {name: a, simulation: shirts, fraktion: 1}\n"),
             Catch::Contains("unknown key 'fraktion'") && Catch::Contains("fraction"));
  CHECK_THAT(error_of(head + "rows:\n  - {name: a, optimize: b, scene: tiny.yaml}\n"),
             Catch::Contains("no earlier training row 'b'"));
  CHECK_THAT(error_of("name: e\ndatasets:\n  shirts: {scene: tiny.yaml, count: 10}\ncolumns: [MEE]\nrows: []\n"),
             Catch::Contains("e.yaml:4") && Catch::Contains("did you mean 'ME'"));
  CHECK_THAT(error_of(head + "rows:\n  - {name: a, simulation: shirts, seed: {p: 1}}\n"),
             Catch::Contains("p is not among the columns"));
  CHECK_THAT(error_of("name: e\ndatasets: {shirts: {scene: tiny.yaml, count: 10}}\ncolumns: [ME\n"),
             Catch::Contains("malformed YAML"));
}

TEST_CASE("experiment: a set of a node or parameter the row's graph lacks and a reversed BMI range fail before any work", "[experiment]") {
  // They failed only after every row before them had run (an outside check),
  // and the BMI range as generate's "--bmi", an option never typed.
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string graph = (test::source_dir() / "graphs/baselines/tailornet_no_anchor.yaml").string();
  const auto run = [&](const std::string& bmi, const std::string& set) {
    std::ofstream(dir / "e.yaml") << "name: e\ndatasets:\n  shirts: {scene: tiny.yaml, count: 10, bmi: \"" << bmi
                                  << "\"}\ncolumns: [ME]\nrows:\n  - {name: TN, train: " << graph
                                  << "}\n  - {name: TN-post, evaluate: TN, set: {" << set << ": \"true\"}}\n";
    std::string out;
    const int code = test::run(test::drape_program().string() + " experiment " + (dir / "e.yaml").string() + " --dry-run --work " +
                                   (dir / "w").string(), out);
    return std::make_pair(code, out);
  };
  auto [code, out] = run("20:40", "postt.enabled");
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("e.yaml:7: row 'TN-post' set 'postt.enabled'") && Catch::Contains("has no node 'postt'") &&
                      Catch::Contains("did you mean 'post'"));
  std::tie(code, out) = run("20:40", "post.enabeld");
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("node 'post' (push_out) has no parameter 'enabeld'; did you mean 'enabled'"));
  std::tie(code, out) = run("40:20", "post.enabled");
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("e.yaml:3") && Catch::Contains(".bmi '40:20': expected a BMI or a range lo:hi"));
  // Right, a dry run plans it.
  std::tie(code, out) = run("20:40", "post.enabled");
  CHECK(code == 0);
  CHECK_FALSE(std::filesystem::exists(dir / "w" / "table.md"));
}

TEST_CASE("experiment: a row whose graph file was edited is trained again", "[experiment]") {
  // An outside check edited a row's graph after its run: the next run stopped
  // with "cannot resume: the interrupted run trained another graph ... (or
  // --force)", an option drape experiment does not have.
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string graph = read(test::source_dir() / "graphs/examples/mlp_baseline.yaml");
  std::ofstream(dir / "mine.yaml") << graph;
  std::ofstream(dir / "exp.yaml") << "name: edited\n"
                                     "datasets:\n"
                                     "  shirts: {scene: tiny.yaml, count: 10, bmi: \"15:40\", seed: 2}\n"
                                     "training: {epochs: 1, batch: 4, lr: 1.0e-3, schedule: constant, patience: 5, seed: 0}\n"
                                     "columns: [ME]\n"
                                     "rows:\n"
                                     "  - {name: mine, train: mine.yaml}\n";
  const std::string command = "cd " + dir.path().string() + " && " + test::drape_program().string() + " experiment exp.yaml --threads 2";
  std::string out;
  REQUIRE(test::run(command, out) == 0);
  // Unchanged: reused.
  REQUIRE(test::run(command, out) == 0);
  CHECK_THAT(out, Catch::Contains("trained already") && !Catch::Contains("$ drape train"));
  // Edited: trained again, on the new graph.
  const std::size_t at = graph.find("edge: 0.1");
  REQUIRE(at != std::string::npos);
  graph.replace(at, 9, "edge: 0.2");
  std::ofstream(dir / "mine.yaml") << graph;
  REQUIRE(test::run(command, out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("mine.yaml was edited since it was trained: trained again") && Catch::Contains("--force"));
  CHECK_THAT(read_checkpoint(dir / "runs/edited/mine.h5").graph, Catch::Contains("weight: 0.2"));
}

TEST_CASE("experiment: a row whose training settings changed is trained again with them", "[experiment]") {
  // An outside check changed the lr (and the batch, seed, patience) of a
  // finished row: every row said "trained already" while the table's heading
  // named the new lr, and the model recorded the old one.
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const auto write = [&](const std::string& training) {
    std::ofstream(dir / "exp.yaml") << "name: settings\n"
                                       "datasets:\n"
                                       "  shirts: {scene: tiny.yaml, count: 10, bmi: \"15:40\", seed: 2}\n"
                                       "training: {" << training << "}\n"
                                       "columns: [ME]\n"
                                       "rows:\n"
                                       "  - {name: mlp, train: "
                                    << (test::source_dir() / "graphs/examples/mlp_baseline.yaml").string() << "}\n";
  };
  const std::string in_dir = "cd " + dir.path().string() + " && " + test::drape_program().string() + " experiment exp.yaml";
  const std::string command = in_dir + " --threads 2";
  const fs::path model = dir / "runs/settings/mlp.h5";
  std::string out;
  write("epochs: 1, batch: 4, lr: 1.0e-3, schedule: constant, patience: 5, seed: 0");
  REQUIRE(test::run(command, out) == 0);
  CHECK(std::stod(read_checkpoint(model).meta.at("lr")) == 0.001);
  write("epochs: 1, batch: 4, lr: 5.0e-3, schedule: constant, patience: 5, seed: 0");
  REQUIRE(test::run(command, out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("trained with lr 0.001 where the row now gives 0.005: trained again") &&
                      Catch::Contains("--force") && !Catch::Contains("trained already"));
  CHECK(std::stod(read_checkpoint(model).meta.at("lr")) == 0.005);
  write("epochs: 1, batch: 2, lr: 5.0e-3, schedule: constant, patience: 5, seed: 3");
  REQUIRE(test::run(command, out) == 0);
  CHECK_THAT(out, Catch::Contains("trained with batch 4 where the row now gives 2, seed 0 where the row now gives 3"));
  CHECK(read_checkpoint(model).meta.at("batch") == "2");
  // The same settings again: reused, whatever --threads.
  REQUIRE(test::run(in_dir + " --threads 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("trained already") && !Catch::Contains("$ drape train"));
}

TEST_CASE("experiment: a monitor no loss of a row's graph and a misspelt plugin fail on a dry run at their lines", "[experiment]") {
  // Both passed --dry-run; the monitor failed when its row began, after the
  // rows before it had trained, without the file or line (an outside check).
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string graph = read(test::source_dir() / "graphs/examples/mlp_baseline.yaml");
  std::ofstream(dir / "mine.yaml") << graph;
  const auto dry_run = [&](const std::string& monitor) {
    std::ofstream(dir / "e.yaml") << "name: e\ndatasets:\n  shirts: {scene: tiny.yaml, count: 10}\ncolumns: [ME]\n"
                                     "training: {epochs: 1, monitor: "
                                  << monitor << "}\nrows:\n  - {name: first, train: mine.yaml}\n";
    std::string out;
    const int code = test::run("cd " + dir.path().string() + " && " + test::drape_program().string() +
                                   " experiment e.yaml --dry-run --work w", out);
    return std::make_pair(code, out);
  };
  auto [code, out] = dry_run("l22");
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("e.yaml:5") && Catch::Contains("monitor 'l22' is no loss of") &&
                      Catch::Contains("did you mean 'l2'"));
  std::tie(code, out) = dry_run("l2");
  CHECK(code == 0);
  const std::size_t at = graph.find("type: mlp");
  REQUIRE(at != std::string::npos);
  graph.replace(at, 9, "type: mpl");
  std::ofstream(dir / "mine.yaml") << graph;
  std::tie(code, out) = dry_run("l2");
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("mine.yaml:") && Catch::Contains("row 'first'") &&
                      Catch::Contains("unknown plugin type 'mpl'") && Catch::Contains("did you mean 'mlp'"));
}

TEST_CASE("experiment: a row trained on other data than given now is trained again", "[experiment]") {
  // An outside check ran an experiment again with another --data in the same
  // work folder: "trained already" (the shipped datasets are older than any
  // model, and only file times were compared), and the table kept the old
  // data's metrics under the new data's name. Outputs now record what they
  // were made from, by content.
  test::TempDir dir;
  write_one_row_experiment(dir.path(), "data", 1);
  const std::string in_dir = "cd " + dir.path().string() + " && " + test::drape_program().string();
  const std::string command = in_dir + " experiment exp.yaml --threads 2";
  std::string out;
  REQUIRE(test::run(command, out) == 0);
  REQUIRE(test::run(command, out) == 0);
  CHECK_THAT(out, Catch::Contains("trained already"));
  const std::string first_eval = read(dir / "runs/data/mlp.eval.json");
  // Other drapes of the same size, made before the model (older, as a shipped dataset is).
  REQUIRE(test::run(in_dir + " generate tiny.yaml --count 10 --bmi 15:40 --seed 3 --threads 2 --out other.h5", out) == 0);
  fs::last_write_time(dir / "other.h5", fs::last_write_time(dir / "runs/data/mlp.h5") - std::chrono::hours(24));
  REQUIRE(test::run(command + " --data shirts=other.h5", out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("trained on other data than other.h5: trained again") && Catch::Contains("--force"));
  CHECK(read(dir / "runs/data/mlp.eval.json") != first_eval);
  // The same data again: reused.
  REQUIRE(test::run(command + " --data shirts=other.h5", out) == 0);
  CHECK_THAT(out, Catch::Contains("trained already") && !Catch::Contains("$ drape eval"));
  // A dry run with the first data stamps nothing: the real run after it
  // evaluates again (the old report was stamped as current and reused).
  const std::string second_eval = read(dir / "runs/data/mlp.eval.json");
  REQUIRE(test::run(command + " --dry-run", out) == 0);
  REQUIRE(test::run(command, out) == 0);
  CHECK_THAT(out, Catch::Contains("$ drape eval"));
  CHECK(read(dir / "runs/data/mlp.eval.json") == first_eval);
  CHECK(second_eval != first_eval);
}

TEST_CASE("experiment: an interrupted training on other data is trained again", "[experiment]") {
  // An outside check killed a run that was training a row again on new
  // data, then ran the experiment with the old data: the old stamp was still
  // there, and the half-trained model of the new data was resumed, then
  // refused with "--force to start over", which drape experiment lacks.
  test::TempDir dir;
  write_one_row_experiment(dir.path(), "killed", 2);
  const std::string in_dir = "cd " + dir.path().string() + " && " + test::drape_program().string();
  std::string out;
  REQUIRE(test::run(in_dir + " experiment exp.yaml --threads 2", out) == 0);
  // The row's own train command, as the run printed it, on other data and cut after an epoch.
  const auto at = out.find("$ drape train ");
  REQUIRE(at != std::string::npos);
  std::string train = out.substr(at + 8, out.find('\n', at) - at - 8);
  const auto data_at = train.find("--data ") + 7;
  train.replace(data_at, train.find(' ', data_at) - data_at, "other.h5");
  REQUIRE(test::run(in_dir + " generate tiny.yaml --count 10 --bmi 15:40 --seed 3 --threads 2 --out other.h5", out) == 0);
  fs::remove(dir / "runs/killed/mlp.h5.inputs");  // as the killed retraining left it
  train.replace(train.find(" --resume"), 9, " --force");
  REQUIRE(test::run(in_dir + " " + train + " --max-epochs-this-run 1", out) == 0);
  CHECK_THAT(out, Catch::Contains("interrupted after 1 epochs"));
  REQUIRE(test::run(in_dir + " experiment exp.yaml --threads 2", out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("its earlier training cannot be resumed (") && Catch::Contains("trained again"));
  CHECK(fs::exists(dir / "runs/killed/mlp.h5.inputs"));
  REQUIRE(test::run(in_dir + " experiment exp.yaml --threads 2", out) == 0);
  CHECK_THAT(out, Catch::Contains("trained already"));
}
