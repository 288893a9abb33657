// scripts/cluster/: the Slurm job array scripts run by hand, each task with
// the array variables Slurm would set, then the merge; the merged datasets are
// bit for bit what one drape generate / drape optimize job makes. submit.sh is
// run against a stand-in sbatch that records what it was asked to queue.
#include <catch2/catch.hpp>

#include <chrono>

#include <drape/io/dataset.hpp>

#include <fstream>
#include <sstream>

#include "train_test_util.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

std::string script(const std::string& name) { return (test::source_dir() / "scripts/cluster" / name).string(); }

// One task of an array, as Slurm would start it.
std::string task(const std::string& env, int id, int count, const std::string& name) {
  return "env DRAPE=" + test::drape_program().string() + " DRAPE_CACHE_DIR=" + test::assets_cache().string() +
         " SLURM_ARRAY_TASK_ID=" + std::to_string(id) + " SLURM_ARRAY_TASK_COUNT=" + std::to_string(count) +
         " SLURM_CPUS_PER_TASK=1 " + env + " bash " + script(name);
}

void same_samples(const fs::path& a_file, const fs::path& b_file) {
  const DatasetReader a(a_file), b(b_file);
  REQUIRE(a.indices().size() == b.indices().size());
  CHECK(a.splits() == b.splits());
  CHECK((a.garment_vertices(a.indices()).flat() - b.garment_vertices(b.indices()).flat()).cwiseAbs().maxCoeff() == 0.0f);
  CHECK((a.body_vertices(a.indices()).flat() - b.body_vertices(b.indices()).flat()).cwiseAbs().maxCoeff() == 0.0f);
}

}  // namespace

TEST_CASE("cluster scripts: a generate array of 3 tasks and its merge make the set one job makes", "[cluster]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string env = "SCENE=" + (dir / "tiny.yaml").string() + " COUNT=5 BMI=15:50 SEED=4 OUT=" + (dir / "all.h5").string();
  std::string out;
  for (int id = 0; id < 3; ++id) {
    REQUIRE(test::run(task(env, id, 3, "generate.sbatch"), out) == 0);
    INFO(out);
  }
  CHECK(fs::exists(dir / "all.h5.shards/shard-2-of-3.h5"));
  // A requeued task whose shard is finished leaves it alone; the array run
  // again with another seed into the same OUT is refused, saying how the
  // shard was made (the script skipped any shard that existed, and an
  // outside check's rerun merged seed 3's shards with seed 4's).
  REQUIRE(test::run(task(env, 1, 3, "generate.sbatch"), out) == 0);
  CHECK_THAT(out, Catch::Contains("nothing to do: ") && Catch::Contains("made by this same request"));
  const std::string reseeded = std::string(env).replace(env.find("SEED=4"), 6, "SEED=5");
  CHECK(test::run(task(reseeded, 1, 3, "generate.sbatch"), out) == 2);
  CHECK_THAT(out, Catch::Contains("already exists, a finished dataset made otherwise ("));
  REQUIRE(test::run("env DRAPE=" + test::drape_program().string() + " SHARDS=3 " + env + " bash " + script("merge.sbatch"), out) == 0);
  INFO(out);
  REQUIRE(test::run(test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() +
                        " --count 5 --bmi 15:50 --seed 4 --threads 2 --out " + (dir / "one.h5").string(),
                    out) == 0);
  same_samples(dir / "all.h5", dir / "one.h5");
  // The merge queued again: nothing to do. A shard newer than the merged set
  // (a rerun of the array into the same OUT): the old set is refused, not
  // kept ("nothing to merge", exit 0, the old seed's set: an outside check).
  const std::string merge = "env DRAPE=" + test::drape_program().string() + " SHARDS=3 " + env + " bash " + script("merge.sbatch");
  REQUIRE(test::run(merge, out) == 0);
  CHECK_THAT(out, Catch::Contains("nothing to merge"));
  fs::last_write_time(dir / "all.h5.shards/shard-1-of-3.h5", fs::last_write_time(dir / "all.h5") + std::chrono::seconds(5));
  CHECK(test::run(merge + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("all.h5 is older than") && Catch::Contains("shard-1-of-3.h5"));
  // Outside an array the script says what it needs.
  CHECK(test::run("env " + env + " bash " + script("generate.sbatch"), out) != 0);
  CHECK_THAT(out, Catch::Contains("sbatch --array"));
  // A SHARDS that is not the array's: its shards are not there, said so
  // (with OUT merged before it was "nothing to merge", exit 0), and one that
  // is no count is named (bash's "abc: unbound variable").
  const std::string four = std::string(merge).replace(merge.find("SHARDS=3"), 8, "SHARDS=4");
  CHECK(test::run(four + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("no shard ") && Catch::Contains("shard-0-of-4.h5") && Catch::Contains("SHARDS=4 must be"));
  const std::string letters = std::string(merge).replace(merge.find("SHARDS=3"), 8, "SHARDS=abc");
  CHECK(test::run(letters + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("SHARDS='abc': expected the number of tasks"));
  CHECK(test::run(task(env + " SHARDS=0", 0, 3, "generate.sbatch") + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("SHARDS='0': expected the number of tasks"));
  CHECK(test::run(task(env + " POSES=random", 0, 3, "generate.sbatch") + " 2>&1", out) == 2);
  CHECK_THAT(out, Catch::Contains("POSES='random': expected scene or draw"));
}

TEST_CASE("cluster scripts: POSES=draw makes a posed set as drape generate --poses draw does", "[cluster]") {
  // generate.sbatch had no way to pass --poses draw: with the pose-space
  // scene it wrote an A-pose set, exit 0, and POSES=draw was ignored (an
  // outside check).
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  const std::string env = "SCENE=" + (dir / "tiny.yaml").string() + " COUNT=2 BMI=20:30 SEED=4 POSES=draw " +
                          "POSE_RANGE=shoulder_abduction=50:60 OUT=" + (dir / "posed.h5").string();
  std::string out;
  REQUIRE(test::run(task(env, 0, 1, "generate.sbatch"), out) == 0);
  INFO(out);
  REQUIRE(test::run("env DRAPE=" + test::drape_program().string() + " SHARDS=1 " + env + " bash " + script("merge.sbatch"), out) == 0);
  REQUIRE(test::run(test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() +
                        " --count 2 --bmi 20:30 --seed 4 --poses draw --pose-range shoulder_abduction=50:60 --threads 2 --out " +
                        (dir / "one.h5").string(),
                    out) == 0);
  same_samples(dir / "posed.h5", dir / "one.h5");
  const DatasetReader posed(dir / "posed.h5");
  REQUIRE_FALSE(posed.layout().pose_angles.empty());
  CHECK((posed.poses(posed.indices()).flat() - DatasetReader(dir / "one.h5").poses(posed.indices()).flat()).cwiseAbs().maxCoeff() == 0.0f);
}

TEST_CASE("cluster scripts: an optimize array of 2 tasks and its merge make the set one job makes", "[cluster]") {
  test::TempDir dir;
  const fs::path data = dir / "data.h5", model = dir / "model.h5";
  test::write_tiny_dataset(data, 7, 5, 1);
  auto o = test::tiny_training(data, model);
  o.epochs = 1;
  train(test::plugins(), o);
  std::ofstream(dir / "scene.yaml") << "body: {model: parametric}\n"
                                       "garment: {template: tshirt, params: {resolution: 300}}\n"
                                       "effects:\n  gravity: {}\n  stretching: {}\n  bending: {}\n"
                                       "  collision: {stiffness: 1.0e8, margin: 0.004}\n";
  const std::string settings = "MODEL=" + model.string() + " DATA=" + data.string() + " SCENE=" + (dir / "scene.yaml").string() +
                               " SPLIT=train ITERS=2 LR=1e-3";
  std::string out;
  for (int id = 0; id < 2; ++id) {
    REQUIRE(test::run(task(settings + " OUT=" + (dir / "opt.h5").string(), id, 2, "optimize.sbatch"), out) == 0);
    INFO(out);
  }
  // Requeued: nothing to do; with other iterations: refused.
  REQUIRE(test::run(task(settings + " OUT=" + (dir / "opt.h5").string(), 0, 2, "optimize.sbatch"), out) == 0);
  CHECK_THAT(out, Catch::Contains("nothing to do: "));
  const std::string more = std::string(settings).replace(settings.find("ITERS=2"), 7, "ITERS=3");
  CHECK(test::run(task(more + " OUT=" + (dir / "opt.h5").string(), 0, 2, "optimize.sbatch"), out) == 2);
  CHECK_THAT(out, Catch::Contains("made otherwise (") && Catch::Contains("3 iterations"));
  REQUIRE(test::run("env DRAPE=" + test::drape_program().string() + " SHARDS=2 OUT=" + (dir / "opt.h5").string() + " bash " +
                        script("merge.sbatch"),
                    out) == 0);
  REQUIRE(test::run(test::drape_command("optimize --model " + model.string() + " --scene " + (dir / "scene.yaml").string() +
                                        " --data " + data.string() + " --split train --iters 2 --lr 1e-3 --threads 2 --out " +
                                        (dir / "one.h5").string()),
                    out) == 0);
  same_samples(dir / "opt.h5", dir / "one.h5");
  CHECK(DatasetReader(dir / "opt.h5").stat("source_index", DatasetReader(dir / "opt.h5").indices()) ==
        DatasetReader(dir / "one.h5").stat("source_index", DatasetReader(dir / "one.h5").indices()));
}

TEST_CASE("cluster scripts: submit.sh queues the array and a merge that waits for it", "[cluster]") {
  test::TempDir dir;
  // A stand-in sbatch: records its arguments and the settings it would pass, answers a job id.
  std::ofstream(dir / "sbatch") << "#!/bin/bash\necho \"$* OUT=$OUT\" >> " << (dir / "calls").string()
                                << "\nn=$(wc -l < " << (dir / "calls").string() << ")\necho $((41 + n))\n";
  fs::permissions(dir / "sbatch", fs::perms::owner_all);
  std::string out;
  REQUIRE(test::run("env PATH=" + dir.path().string() + ":$PATH OUT=/scratch/x.h5 COUNT=100 bash " + script("submit.sh") +
                        " generate 4",
                    out) == 0);
  INFO(out);
  std::ifstream calls(dir / "calls");
  std::string first, second;
  std::getline(calls, first);
  std::getline(calls, second);
  CHECK_THAT(first, Catch::Contains("--array=0-3") && Catch::Contains("SHARDS=4") && Catch::EndsWith("generate.sbatch OUT=/scratch/x.h5"));
  CHECK_THAT(second, Catch::Contains("--dependency=afterok:42") && Catch::Contains("merge.sbatch"));
  CHECK_THAT(out, Catch::Contains("array job 42") && Catch::Contains("merge job 43"));
  CHECK(test::run("env PATH=" + dir.path().string() + ":$PATH OUT=/scratch/x.h5 bash " + script("submit.sh") + " train 4", out) == 2);
  // What the stage's tasks need is checked before anything is queued (a
  // missing COUNT was queued, and every task of the array failed).
  fs::remove(dir / "calls");
  CHECK(test::run("env -u COUNT PATH=" + dir.path().string() + ":$PATH OUT=/scratch/x.h5 bash " + script("submit.sh") +
                      " generate 4 2>&1",
                  out) != 0);
  CHECK_THAT(out, Catch::Contains("COUNT (samples in the whole set) is required for generate"));
  CHECK(test::run("env -u DATA -u SCENE PATH=" + dir.path().string() + ":$PATH OUT=/scratch/x.h5 bash " +
                      script("submit.sh") + " optimize 4 2>&1",
                  out) != 0);
  CHECK_THAT(out, Catch::Contains("DATA (the dataset to optimise) is required for optimize"));
  CHECK_FALSE(fs::exists(dir / "calls"));  // nothing queued
}
