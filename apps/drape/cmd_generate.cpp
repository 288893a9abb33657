// `drape generate`: a dataset of simulated drapes (the seed's ground truth) --
// bodies drawn uniformly in BMI (and height), each draped by the scene's
// simulation, in parallel over samples, resumable after a kill, shardable
// across a cluster job array (merge with `drape dataset merge`).
#include "command.hpp"
#include "sample_ranges.hpp"

#include <drape/io/dataset.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/registry.hpp>
#include <drape/services/dataset_generation.hpp>

#include <cstdio>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape generate");
  opts.add_options()("scene", po::value<std::string>()->default_value("graphs/scenes/tshirt.yaml"), "scene file")(
      "count", po::value<long>(), "samples in the whole set (all shards)")(
      "bmi", po::value<std::string>()->default_value("10:65"), "BMI range lo:hi (uniform) or a value")(
      "height", po::value<std::string>()->default_value("1.75"), "height range lo:hi in m, or a value")(
      "sex", po::value<std::string>()->default_value("1"), "0, 1, a blend between, or 0:1 for female or male at random per sample")(
      "girths", po::value<double>()->default_value(0.0),
      "spread of the body's girths (chest, waist, belly, hips, arms, thighs) as a fraction of the body model's range, "
      "each drawn uniformly; 0 keeps the mean build (docs/bodies.md)")(
      "poses", po::value<std::string>()->default_value("scene"),
      "scene: every body in the scene's pose (its A-pose when it has none); draw: each body in a pose drawn from the "
      "body model's pose space, free of self-intersection by rejection (docs/poses.md); the joint angles are stored")(
      "pose-range", po::value<std::string>()->default_value(""),
      "with --poses draw: sampling ranges replacing the pose space's, e.g. shoulder_abduction=60:90,spine_twist=30:45 "
      "(degrees; a name without left_/right_ sets both sides)")(
      "seed", po::value<std::uint64_t>()->default_value(0), "seed of the bodies, the poses and the split")(
      "out", po::value<std::string>(), "dataset file (HDF5) to write")(
      "shard", po::value<std::string>()->default_value("0/1"), "make only shard i of N (a contiguous part), e.g. 3/16")(
      "threads", po::value<int>()->default_value(0), "samples simulated at once (0: all cores)");
  po::positional_options_description pos;
  pos.add("scene", 1);
  po::variables_map vm;
  const std::string usage =
      "drape generate [SCENE.yaml] --count N --bmi 10:65 --seed S --out data.h5 [--poses draw] [--shard i/N] [--threads T]";
  if (!parse(usage, args, opts, pos, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  // (a long, so that -1 is refused instead of wrapping to 2^64 - 1 samples)
  if (!vm.count("count") || vm["count"].as<long>() < 1) throw UsageError("--count N (N >= 1) is required");
  if (!vm.count("out")) throw UsageError("--out FILE is required");
  GenerateRequest request;
  request.count = static_cast<std::size_t>(vm["count"].as<long>());
  request.shard = parse_shard(vm["shard"].as<std::string>());
  request.bmi = parse_range("bmi", vm["bmi"].as<std::string>());
  request.height = parse_range("height", vm["height"].as<std::string>());
  request.sex = parse_range("sex", vm["sex"].as<std::string>());
  // A range draws one of its two ends per sample (female or male, with equal
  // odds): --sex 0.3:0.6 gave only 0.3 and 0.6, never a value between (an
  // outside check); the body model's sexes between 0 and 1 are blends.
  if (request.sex.lo != request.sex.hi && !(request.sex.lo == 0.0 && request.sex.hi == 1.0))
    throw UsageError("--sex " + vm["sex"].as<std::string>() +
                     ": a range draws female (0) or male (1) with equal odds, so it is 0:1; one value (a blend, say 0.5) "
                     "gives every sample that sex");
  request.girths = vm["girths"].as<double>();  // generate_dataset checks the values
  request.seed = vm["seed"].as<std::uint64_t>();
  const std::string poses = vm["poses"].as<std::string>();
  if (poses != "scene" && poses != "draw") throw UsageError("--poses " + poses + ": expected scene or draw");
  request.draw_poses = poses == "draw";
  request.pose_ranges = vm["pose-range"].as<std::string>();
  if (!vm["pose-range"].defaulted() && request.pose_ranges.find_first_not_of(" \t") == std::string::npos)
    throw UsageError("--pose-range is empty (a shell variable never set?): give name=lo:hi, e.g. shoulder_abduction=60:90");
  request.threads = vm["threads"].as<int>();
  const std::string out = vm["out"].as<std::string>();

  Registry& registry = Registry::load_default(plugin_path(vm));
  GenerateObserver observer;
  observer.progress = &std::cerr;
  observer.on_start = [](const GeneratePlan& p) {
    std::printf("generating %zu samples (%zu..%zu of %zu) into %s%s, %d at a time; %s\n", p.samples, p.first, p.last - 1,
                p.total, p.out.c_str(), p.resumed ? (" (resuming: " + std::to_string(p.already) + " done)").c_str() : "",
                p.threads, p.ranges.c_str());
    std::fflush(stdout);
  };
  const GenerateSummary done = generate_dataset(registry, load_scene(find_input_file(vm["scene"].as<std::string>())), request, out, observer);
  if (done.already_finished) {
    std::printf("nothing to do: %s is finished (%zu samples), made by this same request\n", out.c_str(), done.samples);
    return 0;
  }
  std::printf("wrote %s: %zu samples; this run's: %d not settled, %d with a vertex inside the body, %d with crossing "
              "surfaces; %zu crossing themselves%s\n",
              out.c_str(), done.samples, done.not_settled, done.penetrating, done.crossing, done.crossing_itself.size(),
              done.checked_again > 0 ? (" (with the " + std::to_string(done.checked_again) +
                                        " drapes of earlier runs, read back from the file)").c_str()
                                     : "");
  if (!done.crossing_itself.empty()) {
    // Named, so that they can be looked at or left out (scripts/check_dataset_drapes.py counts them independently).
    const std::string list = global_index_list({done.crossing_itself.begin(), done.crossing_itself.end()});
    std::printf("garments crossing themselves: sample %s (global index); `drape dataset slim %s --out SLIM --drop %s` "
                "leaves them out\n",
                list.c_str(), shell_word(out).c_str(), list.c_str());
  }
  return 0;
}

const RegisterCommand registered{{"generate", "simulate a dataset of drapes over random bodies (resumable, shardable)", run}};

}  // namespace
}  // namespace drape::cli
