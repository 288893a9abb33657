// mpirun -np 2 drape train: data-parallel over two processes. The weights are
// compared with one process trained in the usual way on the same global
// batches: bit for bit against 2 threads (the ranks cut every batch and add the
// parts' gradients exactly as the threads do), within float round-off against
// 1 thread. Skips with a message when drape was built without MPI or mpirun is
// absent.
#include <catch2/catch.hpp>

#include <drape/io/checkpoint.hpp>
#include <drape/io/h5.hpp>

#include <algorithm>
#include <cmath>
#include <regex>

#include "train_test_util.hpp"

using namespace drape;
namespace fs = std::filesystem;

namespace {

using Weights = std::map<std::string, std::vector<float>>;

Weights mpi_weights_of(const fs::path& file) {
  const h5::File f = h5::File::open(file);
  Weights w;
  for (const auto& name : f.datasets_below("/weights")) w[name] = f.read<float>("/weights/" + name);
  return w;
}

double max_difference(const Weights& a, const Weights& b) {
  REQUIRE(a.size() == b.size());
  double worst = 0;
  for (const auto& [name, v] : a) {
    const auto& u = b.at(name);
    REQUIRE(u.size() == v.size());
    for (std::size_t k = 0; k < v.size(); ++k) worst = std::max(worst, std::abs(double(v[k]) - double(u[k])));
  }
  return worst;
}

// Batch 5 over 11 training samples: parts of 3 and 2 samples (unequal shares),
// and a last batch of 1 sample that rank 1 sits out.
std::string mpi_train_args(const fs::path& data, const fs::path& out, const std::string& more, int batch = 5) {
  return "train " + test::baseline_graph().string() + " --data " + data.string() + " --out " + out.string() +
         " --epochs 3 --batch " + std::to_string(batch) + " --lr 3e-3 --seed 5 --quiet --k " + std::to_string(test::kTinyK) + " " + more;
}

std::string mpirun(const std::string& args) {
  return "env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 DRAPE_CACHE_DIR=" +
         test::assets_cache().string() + " mpirun --allow-run-as-root --oversubscribe -np 2 " +
         test::drape_program().string() + " " + args;
}

// Why not, when this machine cannot run the test; empty when it can.
std::string cannot_run_mpi() {
  std::string out;
  if (test::run(test::drape_command("train --help"), out) != 0 || out.find("built with MPI") == std::string::npos)
    return "drape was built without MPI (install libopenmpi-dev and reconfigure)";
  if (test::run("command -v mpirun", out) != 0) return "mpirun is not on PATH (install openmpi-bin)";
  return "";
}

// True (and a warning saying why) when this machine cannot run the MPI tests.
bool skipped_without_mpi() {
  const std::string why = cannot_run_mpi();
  if (why.empty()) return false;
  WARN("skipped: " << why);
  SUCCEED("skipped");
  return true;
}

}  // namespace

TEST_CASE("mpirun -np 2 drape train: the weights of one process on the same global batches", "[train][mpi]") {
  if (skipped_without_mpi()) return;
  test::TempDir dir;
  const fs::path data = dir / "data.h5";
  test::write_tiny_dataset(data, 14, 11, 3);
  std::string out;
  REQUIRE(test::run(mpirun(mpi_train_args(data, dir / "mpi.h5", "--threads 1")), out) == 0);
  INFO(out);
  // Rank 0 alone talks: every epoch's line once, and the ranks named.
  CHECK_THAT(out, Catch::Contains("1 thread on each of 2 ranks"));
  const std::regex epoch_line("epoch 3/3");
  CHECK(std::distance(std::sregex_iterator(out.begin(), out.end(), epoch_line), std::sregex_iterator()) == 1);
  REQUIRE(test::run(test::drape_command(mpi_train_args(data, dir / "threads2.h5", "--threads 2")), out) == 0);
  REQUIRE(test::run(test::drape_command(mpi_train_args(data, dir / "threads1.h5", "--threads 1")), out) == 0);

  const Weights mpi = mpi_weights_of(dir / "mpi.h5");
  // Two ranks of one thread add the same float terms in the same order as two threads.
  CHECK(mpi == mpi_weights_of(dir / "threads2.h5"));
  CHECK(mpi_weights_of(training_state_path(dir / "mpi.h5")) == mpi_weights_of(training_state_path(dir / "threads2.h5")));
  CHECK(read_checkpoint(dir / "mpi.h5").history.at("train_loss") == read_checkpoint(dir / "threads2.h5").history.at("train_loss"));
  CHECK(read_checkpoint(dir / "mpi.h5").history.at("val_loss") == read_checkpoint(dir / "threads2.h5").history.at("val_loss"));

  // Against one thread the batch's mean gradient is rounded differently (a
  // mean of part means instead of one mean): a relative 1e-7 per gradient,
  // which Adam turns into weight differences of about lr * 1e-7 per step, far
  // below 1e-5 after 9 steps. A mistake in the combination (a part dropped or
  // counted twice, a wrong share) turns the gradient as training on other
  // batches does, which moves weights by far more -- checked below. (A uniform
  // scale of every part would not show here, Adam normalises it away; the
  // bit-for-bit comparison with 2 threads above catches it.)
  const Weights one = mpi_weights_of(dir / "threads1.h5");
  CHECK(max_difference(mpi, one) < 1e-5);
  REQUIRE(test::run(test::drape_command(mpi_train_args(data, dir / "batch4.h5", "--threads 1", 4)), out) == 0);
  CHECK(max_difference(mpi_weights_of(dir / "batch4.h5"), one) > 1e-4);
}

TEST_CASE("mpirun -np 2 drape train resumes to the uninterrupted result and refuses another rank count", "[train][mpi]") {
  if (skipped_without_mpi()) return;
  test::TempDir dir;
  const fs::path data = dir / "data.h5", model = dir / "model.h5";
  test::write_tiny_dataset(data, 10, 8, 2);
  std::string out;
  REQUIRE(test::run(mpirun(mpi_train_args(data, dir / "whole.h5", "--threads 1")), out) == 0);
  REQUIRE(test::run(mpirun(mpi_train_args(data, model, "--threads 1 --max-epochs-this-run 1")), out) == 0);
  CHECK(std::stol(read_checkpoint(training_state_path(model)).meta.at("epoch")) == 1);
  // One process cannot continue what two ranks started: its sums round differently. Said first, whatever
  // its threads (two threads were refused as "threads 1 ... threads 2": an outside check).
  CHECK(test::run(test::drape_command(mpi_train_args(data, model, "--threads 1 --resume")), out) == 2);
  CHECK_THAT(out, Catch::Contains("ranks"));
  CHECK(test::run(test::drape_command(mpi_train_args(data, model, "--threads 2 --resume")), out) == 2);
  CHECK_THAT(out, Catch::Contains("the interrupted run had ranks 2, this one has ranks 1"));
  REQUIRE(test::run(mpirun(mpi_train_args(data, model, "--threads 1 --resume")), out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("resuming"));
  CHECK(mpi_weights_of(model) == mpi_weights_of(dir / "whole.h5"));
  CHECK(mpi_weights_of(training_state_path(model)) == mpi_weights_of(training_state_path(dir / "whole.h5")));
}

// With the seed's six losses, v2v and direction keep the ground truth's
// closest points in a cache per process; after each epoch the ranks hand each
// other what they computed. Their training must still be the two threads'
// bit for bit (a wrong point under a key would change every later loss).
TEST_CASE("mpirun -np 2 drape train with the six losses shares closest points and still matches two threads",
          "[train][mpi]") {
  if (skipped_without_mpi()) return;
  test::TempDir dir;
  const fs::path data = dir / "data.h5";
  test::write_tiny_dataset(data, 14, 11, 3);
  const std::string graph = (test::source_dir() / "graphs/drape.yaml").string();
  auto args = [&](const fs::path& out, const std::string& more) {
    return "train " + graph + " --data " + data.string() + " --out " + out.string() + " --epochs 3 --batch 5 --lr 1e-3 --seed 5 --quiet --k " +
           std::to_string(test::kTinyK) + " " + more;
  };
  std::string out;
  REQUIRE(test::run(mpirun(args(dir / "mpi.h5", "--threads 1")), out) == 0);
  INFO(out);
  REQUIRE(test::run(test::drape_command(args(dir / "threads2.h5", "--threads 2")), out) == 0);
  CHECK(mpi_weights_of(dir / "mpi.h5") == mpi_weights_of(dir / "threads2.h5"));
  CHECK(read_checkpoint(dir / "mpi.h5").history.at("train_loss") == read_checkpoint(dir / "threads2.h5").history.at("train_loss"));
  CHECK(read_checkpoint(dir / "mpi.h5").history.at("val_loss") == read_checkpoint(dir / "threads2.h5").history.at("val_loss"));
}

// Only train is MPI-parallel: generate or optimize --data started as one of several
// processes without a shard is refused before it makes anything (an outside check's mpirun
// -np 2 drape generate ran the whole job twice on one output: rank 1 died on
// its lock, an empty .partial left). The launcher's variables are set by
// hand, so this runs without mpirun.
TEST_CASE("a dataset made whole by several MPI processes is refused and a shard each runs", "[train][mpi]") {
  test::TempDir dir;
  std::ofstream(dir / "tiny.yaml") << test::tiny_simulation_scene();
  std::string out;
  const std::string generate = test::drape_program().string() + " generate " + (dir / "tiny.yaml").string() +
                               " --count 2 --seed 1 --threads 1 --out " + (dir / "d.h5").string();
  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE=2", "PMI_SIZE=3"}) {
    INFO(launcher);
    CHECK(test::run(std::string("env ") + launcher + " " + generate, out) == 2);
    CHECK_THAT(out, Catch::Contains("drape generate is not MPI-parallel (drape train is)") &&
                        Catch::Contains("give each process its own shard (--shard i/"));
    CHECK_FALSE(fs::exists(dir / "d.h5"));
    CHECK_FALSE(fs::exists(dir / "d.h5.partial"));
  }
  // One process of one (a launcher's single rank) runs as without it.
  REQUIRE(test::run("env OMPI_COMM_WORLD_SIZE=1 " + generate, out) == 0);
  CHECK(fs::exists(dir / "d.h5"));
  // A shard each (srun -n N ... --shard $SLURM_PROCID/N), --help, and any
  // other command run as one process would (an outside check found them refused).
  REQUIRE(test::run("env PMI_SIZE=2 " + generate.substr(0, generate.find(" --out")) + " --shard 1/2 --out " +
                        (dir / "s1.h5").string(), out) == 0);
  CHECK(fs::exists(dir / "s1.h5"));
  CHECK(test::run("env PMI_SIZE=2 " + test::drape_program().string() + " generate --help", out) == 0);
  CHECK(test::run("env PMI_SIZE=2 " + test::drape_program().string() + " generate -h", out) == 0);
  // Options cut short as the parser takes them ("--sh 1/2" is a shard; "--dat" is --data).
  REQUIRE(test::run("env PMI_SIZE=2 " + generate.substr(0, generate.find(" --out")) + " --sh 0/2 --out " +
                        (dir / "s0.h5").string(), out) == 0);
  CHECK(test::run("env PMI_SIZE=2 " + test::drape_program().string() + " optimize --scene x.yaml --dat d.h5 --out o.h5", out) == 2);
  CHECK_THAT(out, Catch::Contains("drape optimize is not MPI-parallel"));
  CHECK(test::run("env PMI_SIZE=2 " + test::drape_program().string() + " plugins --kind energy --brief", out) == 0);
}

// Ranks given another training (an outside check: another --batch or
// --epochs ended in MPI_ERR_TRUNCATE, a corrupted heap or a hang; another
// --seed or --data trained a model of neither; a rank that could not see
// <out>.state started afresh while rank 0 resumed, then hung): refused by
// every rank before the first step, naming what differs. A wrapper gives
// rank 1 its own arguments, as a job script might by mistake.
TEST_CASE("mpirun -np 2 drape train refuses ranks given different settings or an unshared state", "[train][mpi]") {
  if (skipped_without_mpi()) return;
  test::TempDir dir;
  const fs::path data = dir / "data.h5";
  test::write_tiny_dataset(data, 10, 8, 2);
  const fs::path wrapper = dir / "per_rank.sh";
  std::ofstream(wrapper) << "#!/bin/sh\n"
                            "if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then exec \"$@\" $RANK1; else exec \"$@\" $RANK0; fi\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  std::string out;
  const auto per_rank = [&](const std::string& args, const std::string& rank0, const std::string& rank1) {
    const std::string command = mpirun(args);
    const std::size_t program = command.find(test::drape_program().string());
    return "timeout 300 env RANK0='" + rank0 + "' RANK1='" + rank1 + "' " + command.substr(0, program) + wrapper.string() +
           " " + command.substr(program);
  };
  CHECK(test::run(per_rank(mpi_train_args(data, dir / "p.h5", "--threads 1"), "--patience 20", "--patience 21"), out) == 2);
  CHECK_THAT(out, Catch::Contains("rank 1 differs from rank 0 in --patience or --monitor"));
  CHECK_FALSE(fs::exists(dir / "p.h5"));
  // A state only rank 0 sees: rank 1's --out in a folder of its own.
  REQUIRE(test::run(mpirun(mpi_train_args(data, dir / "m.h5", "--threads 1 --max-epochs-this-run 1")), out) == 0);
  fs::create_directories(dir / "own");
  std::string resume = mpi_train_args(data, "OUT", "--threads 1 --resume");
  resume.erase(resume.find(" --out OUT"), std::string(" --out OUT").size());
  CHECK(test::run(per_rank(resume, "--out " + (dir / "m.h5").string(),
                           "--out " + (dir / "own" / "m.h5").string()),
                  out) == 2);
  CHECK_THAT(out, Catch::Contains("differs from rank 0 in the earlier run's state m.h5.state") &&
                      Catch::Contains("a file system every rank shares"));
}

TEST_CASE("an error every rank meets is printed once on one line and not followed by resume advice", "[train][mpi]") {
  // An outside check: a missing --data under mpirun printed "drape train: rank
  // drape train: rank 1 of 2: ..." (both ranks, interleaved mid-line), then
  // "stopped by SIGTERM: what was finished is kept".
  if (skipped_without_mpi()) return;
  test::TempDir dir;
  std::string out;
  const int code = test::run(mpirun(mpi_train_args(dir / "missing.h5", dir / "m.h5", "")), out);
  INFO(out);
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("drape train: rank 0 of 2: " + (dir / "missing.h5").string() + ": no such file"));
  CHECK_THAT(out, !Catch::Contains("rank 1 of 2"));
  CHECK_THAT(out, !Catch::Contains("stopped by SIG"));
  CHECK_FALSE(fs::exists(dir / "m.h5"));
}
