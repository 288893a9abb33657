// `drape train GRAPH.yaml --data data.h5 --out model.h5`: train a graph on a
// dataset (drape/training/trainer.hpp), resumable with --resume after a kill.
#include "command.hpp"
#include "mpi_ranks.hpp"

#include <drape/io/dataset.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/io/write_failure.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/services/model_training.hpp>

#include <drape/errors.hpp>
#include <drape/training/trainer.hpp>

#include <chrono>
#include <exception>
#include <iostream>
#include <thread>

#include <unistd.h>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// A test hook kept out of --help: stop after N epochs as a kill would, so
// tests can resume deterministically. Removed from the arguments here.
long take_hidden_epoch_limit(std::vector<std::string>& args) {
  const std::string flag = "--max-epochs-this-run";
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string value;
    if (args[i] == flag && i + 1 < args.size()) {
      value = args[i + 1];
      args.erase(args.begin() + static_cast<long>(i), args.begin() + static_cast<long>(i) + 2);
    } else if (args[i].rfind(flag + "=", 0) == 0) {
      value = args[i].substr(flag.size() + 1);
      args.erase(args.begin() + static_cast<long>(i));
    } else {
      continue;
    }
    try {
      const long n = std::stol(value);
      if (n > 0) return n;
    } catch (const std::exception&) {
    }
    throw UsageError(flag + " wants a positive number, got '" + value + "'");
  }
  return 0;
}

int run(const std::vector<std::string>& given) {
  std::vector<std::string> args = given;
  TrainOptions o;
  o.max_epochs_this_run = take_hidden_epoch_limit(args);
  po::options_description opts("drape train");
  opts.add_options()("graph", po::value<std::string>(), "graph YAML (graphs/examples/*.yaml)")(
      "data", po::value<std::string>(), "dataset from drape generate")(
      "out", po::value<std::string>(), "model file to write (HDF5); the resumable state goes to <out>.state")(
      "epochs", po::value<long>()->default_value(100), "epochs (passes over the training split)")(
      "batch", po::value<int>()->default_value(8), "samples per step")(
      "lr", po::value<double>()->default_value(1e-3), "Adam's learning rate")(
      "weight-decay", po::value<double>()->default_value(0.0),
      "AdamW's decoupled weight decay: each step scales every weight by (1 - lr * this); 0: plain Adam")(
      "schedule", po::value<std::string>()->default_value("constant"), "learning rate over epochs: constant | cosine")(
      "fraction", po::value<double>()->default_value(1.0), "train on this fraction of the training split (the seed's 4k model: 0.25)")(
      "patience", po::value<int>()->default_value(20), "stop after this many epochs without a better validation loss")(
      "monitor", po::value<std::string>(), "a loss of the graph by its name (e.g. v2v): its unweighted validation value, "
                                           "not the weighted total, chooses the best epoch and stops early")(
      "seed", po::value<std::uint64_t>()->default_value(0), "seed of the initial weights and the shuffles")(
      "threads", po::value<int>()->default_value(0), "threads, each on a part of every batch (0: all cores, or 1 per "
                                                     "rank under mpirun); results depend on it, so give it to reproduce "
                                                     "a run elsewhere")(
      "k", po::value<int>()->default_value(1000), "eigenvectors in the template assets (eigen_k; 1000 as in drape assets, which shares the cache)")(
      "init", po::value<std::string>(), "start from the weights of this model file (same graph weights: fine-tune a "
                                        "model, e.g. the shipped one, on new drapes) instead of random ones")(
      "init-widen", po::bool_switch(), "with --init, a graph that appends input features (a concat after the old "
                                       "ones, e.g. graphs/sizes/drape_grade.yaml's grade): weights with more input rows "
                                       "keep the file's rows and start the new ones at zero, so training starts from "
                                       "that model")(
      "init-partial", po::bool_switch(), "with --init, as --init-widen, and a weight of another shape in the file keeps "
                                         "its initialisation (listed): a model of the same garment on another body "
                                         "model's template, e.g. the mannequin's model to start the human rig's")(
      "encoder-body", po::value<std::string>(),
      "a body model whose vertices the encoder reads (the graph's resample_body node carries the dataset's bodies onto "
      "its mean body's vertices), e.g. parametric for the human rig's drapes, so that the mannequin's model starts it "
      "with its encoder as it was (docs/bodies.md, \"One encoder for both rigs\"); its template vertices' count "
      "replaces the body's for the encoder")(
      "resume", po::bool_switch(), "continue an interrupted training from <out>.state (starts afresh when there is none)")(
      "force", po::bool_switch(), "start over, deleting <out> and <out>.state")(
      "quiet,q", po::bool_switch(), "no progress bar");
  po::positional_options_description pos;
  pos.add("graph", 1);
  po::variables_map vm;
  const std::string usage =
      "drape train GRAPH.yaml --data data.h5 --out model.h5 [--epochs N] [--batch B] [--lr X] [--weight-decay W] [--seed S] [--threads T] "
      "[--init model.h5 [--init-widen | --init-partial]] [--monitor LOSS] [--resume]" +
      std::string(built_with_mpi() ? "\n       mpirun -np N drape train ... (built with MPI: N ranks, each on a part of every batch)"
                                   : "\n       (built without MPI: one process)");
  if (!parse(usage, args, opts, pos, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  if (!vm.count("graph")) throw UsageError("a graph file is required, e.g. graphs/examples/mlp_baseline.yaml");
  if (!vm.count("data")) throw UsageError("--data FILE is required (a dataset from drape generate)");
  if (!vm.count("out")) throw UsageError("--out FILE is required (the model file to write)");
  if (vm["resume"].as<bool>() && vm["force"].as<bool>()) throw UsageError("--resume and --force exclude each other");
  o.graph = find_input_file(vm["graph"].as<std::string>());  // graphs/... from anywhere
  o.data = vm["data"].as<std::string>();
  o.out = vm["out"].as<std::string>();
  // --data X --out X --force wrote a model over the dataset after an epoch.
  refuse_output_among_inputs(o.out, dataset_inputs(o.data), "--out");
  o.epochs = vm["epochs"].as<long>();
  o.batch = vm["batch"].as<int>();
  o.lr = vm["lr"].as<double>();
  o.weight_decay = vm["weight-decay"].as<double>();
  o.schedule = vm["schedule"].as<std::string>();
  o.patience = vm["patience"].as<int>();
  if (vm.count("monitor")) o.monitor = vm["monitor"].as<std::string>();
  o.train_fraction = vm["fraction"].as<double>();
  o.seed = vm["seed"].as<std::uint64_t>();
  // Under mpirun the ranks share the cores (mpirun binds each to its own).
  const std::unique_ptr<Ranks> ranks = mpi_ranks_if_launched();
  o.ranks = ranks.get();
  o.threads = vm["threads"].as<int>();
  if (o.threads == 0)
    o.threads = ranks ? 1 : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.eigen_k = vm["k"].as<int>();
  if (vm.count("init")) o.init = find_input_file(vm["init"].as<std::string>());
  o.init_widen = vm["init-widen"].as<bool>();
  o.init_partial = vm["init-partial"].as<bool>();
  if (vm.count("encoder-body")) o.encoder_body = vm["encoder-body"].as<std::string>();
  o.resume = vm["resume"].as<bool>();
  o.force = vm["force"].as<bool>();
  o.log = &std::cout;
  if (!vm["quiet"].as<bool>()) o.progress = &std::cerr;

  Registry& registry = Registry::load_default(plugin_path(vm));
  TrainedModel trained;  // rank 0 takes the output's lock, trains, records the domain (services/model_training.hpp)
  try {
    trained = train_model(registry, o);
  } catch (const std::exception& e) {
    if (!ranks || ranks->size() == 1) throw;
    // An error every rank meets (a missing --data) was printed by each, the
    // lines interleaved mid-word, and a rank that aborted first had mpirun
    // stop rank 0 with SIGTERM, whose lock then said "what was finished is
    // kept". The other ranks wait a moment: rank 0's abort ends them before
    // they repeat its error, and an error of their own still shows.
    if (ranks->rank() != 0) std::this_thread::sleep_for(std::chrono::seconds(2));
    const std::string line = "drape train: rank " + std::to_string(ranks->rank()) + " of " + std::to_string(ranks->size()) +
                             ": " + e.what() + "\n";
    std::cerr << std::flush;
    [[maybe_unused]] const ssize_t written = ::write(2, line.data(), line.size());  // one write: not interleaved
    // The other ranks may be waiting for this one in a collective: end them all.
    abort_all_ranks(dynamic_cast<const ConfigError*>(&e) || dynamic_cast<const UsageError*>(&e) ? 2 : 1);
  }
  if (ranks && ranks->rank() != 0) return 0;
  const TrainReport& r = trained.report;
  const ModelDomain& domain = *trained.domain;  // the bodies it learnt from (model_domain.hpp)
  std::cout << "recorded the model's domain: " << training_count(domain) << ", BMI " << domain.bmi.min << "-"
            << domain.bmi.max << ", height " << domain.height.min << "-" << domain.height.max << " m\n";
  std::cout << "wrote " << o.out.string() << ": best epoch " << r.best_epoch << " (loss " << r.best_loss << ") of "
            << r.epochs_done << "; ";
  if (r.early_stopped)
    std::cout << "stopped early";
  else if (r.finished)
    std::cout << "all epochs done";
  else
    std::cout << "interrupted after " << r.epochs_this_run << " epochs of this run: resume with the same command and --resume";
  std::cout << " (" << r.seconds << " s)\n";
  return 0;
}

const RegisterCommand registered{{"train", "train a graph on a dataset (Adam, data-parallel, resumable)", run}};

}  // namespace
}  // namespace drape::cli
