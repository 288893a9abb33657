// `drape model info MODEL`: what a model file holds and the domain it knows.
// `drape model domain MODEL --data DATA [--out FILE]`: records the training
// domain of DATA's training split in the model (for models trained before
// drape train recorded it), atomically, rewriting the file in the current
// format (sealed: docs/formats.md).
// `drape model set MODEL --set node.param=value... [--out FILE]`: stores graph
// parameters that leave the weights alone (e.g. post.enabled=true, the
// push-out after the network) in the model, as --set does for one run.
#include "command.hpp"

#include <drape/io/shipped_files.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/io/dataset.hpp>
#include <drape/errors.hpp>
#include <drape/io/h5.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/io/write_failure.hpp>
#include <drape/registry.hpp>
#include <drape/training/model.hpp>
#include <drape/graph.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/training/model_params.hpp>
#include <drape/scene/size_table.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

namespace fs = std::filesystem;

const char* kInfoUsage = "drape model info MODEL";
const char* kDomainUsage = "drape model domain MODEL --data DATA [--out FILE] [--force]";
const char* kSetUsage = "drape model set MODEL --set node.param=value [--set ...] [--out FILE]";

// Whether a model's graph reads a pose, from its stored text (without loading its weights).
bool graph_takes_pose(const std::string& graph_text, const std::string& where) {
  std::vector<std::string> inputs;
  for (const auto& [name, input] : parse_graph_text(graph_text, where).inputs) inputs.push_back(name);
  return reads_pose(inputs);
}

void print_domain(const ModelDomain& d, bool takes_pose = true) {
  std::printf("domain: body model '%s', %s from %s\n", d.body_model.c_str(), training_count(d).c_str(),
              d.source.empty() ? "(unknown)" : d.source.c_str());
  std::printf("  %-10s %8.3f .. %-8.3f m\n", "height", d.height.min, d.height.max);
  std::printf("  %-10s %8.2f .. %-8.2f\n", "BMI", d.bmi.min, d.bmi.max);
  for (std::size_t p = 0; p < d.params.size(); ++p) {
    if (d.param_names[p] == "height") continue;  // printed above, with its unit
    std::printf("  %-10s %8.3f .. %-8.3f%s\n", d.param_names[p].c_str(), d.params[p].min, d.params[p].max,
                d.params[p].min == d.params[p].max ? "  (fixed)" : "");
  }
  std::printf("  a body farther than %.2f cm (RMS over %zu vertices) from every training body is outside\n",
              100 * d.neighbour_limit, d.descriptor_vertices.size());
  if (d.placement.allFinite())
    std::printf("  the training bodies stood at x %.4f, z %.4f (mean of the vertices), soles at y %.4f m (each within "
                "%.1f, %.1f, %.1f mm of that); a body given elsewhere is moved there to be draped\n",
                d.placement[0], d.placement[2], d.placement[1], 1000 * d.placement_spread[0], 1000 * d.placement_spread[2],
                1000 * d.placement_spread[1]);
  else
    std::printf("  where the training bodies stood is not recorded (drape model domain adds it)\n");
  if (d.pose_names.empty()) {
    std::printf("  poses: the A-pose only (predict refuses a pose)\n");
    return;
  }
  if (!takes_pose) {  // trained on posed drapes by a graph that reads no pose
    std::printf("  poses: the A-pose only (its graph takes no pose; predict refuses a pose), though the drapes it was "
                "trained on were posed (%zu joint angles), which it could not tell apart\n",
                d.pose_names.size());
    return;
  }
  std::printf("  poses (degrees; predict --pose warns outside, --strict refuses; measures above on the bodies at rest):\n");
  for (std::size_t a = 0; a < d.pose_names.size(); ++a)
    std::printf("    %-26s %8.1f .. %-8.1f%s\n", d.pose_names[a].c_str(), d.pose[a].min, d.pose[a].max,
                d.pose[a].min == d.pose[a].max ? "  (fixed)" : "");
  // Each range is of one angle over all the training bodies: a heavy body's
  // arms meet its trunk well inside the abduction range (an outside check
  // read the box as trained for every body; BMI 62 at 26 degrees had no
  // drape to learn from).
  std::printf("  (each range is one angle's over all training bodies: not every pose inside them was trained on every "
              "body; a heavy body's arms meet its trunk at small abductions, where the training drew none: predict "
              "warns that the body passes through itself, simulate refuses it)\n");
}

// The sizes a model of drapes in each body's own size chooses from.
void print_size_chart(const std::string& text, const std::string& file) {
  const SizeTable t = SizeTable::parse(text, file + ": /meta size_chart");
  std::printf("sizes: chosen for each body by the tailor's rule (design size %s, %+.1f %% ease on the mean body)\n",
              t.design.c_str(), 100.0 * t.design_ease);
  for (const auto& [name, girth] : t.girth)
    std::printf("  %-10s %.3f m around (grade %.3f)\n", name.c_str(), girth, t.grade(name));
}

// The settings `drape train` was given (what it takes to train the model
// again, beside the dataset and graph printed above), and the model it
// started from (--init) by the path it had then.
void print_training_settings(const std::map<std::string, std::string>& meta) {
  const auto get = [&](const char* key) -> std::string {
    const auto it = meta.find(key);
    return it == meta.end() ? std::string() : it->second;
  };
  std::string line;
  const auto add = [&](const std::string& part) { line += (line.empty() ? "" : ", ") + part; };
  for (const char* key : {"seed", "batch", "threads"})
    if (!get(key).empty()) add(std::string(key) + " " + get(key));
  if (const std::string lr = get("lr"); !lr.empty()) {
    // Stored exactly (17 digits); shown short. A value that is not a number
    // (a file written by hand) is shown as it is.
    char number[32];
    char* end = nullptr;
    const double value = std::strtod(lr.c_str(), &end);
    if (end != lr.c_str() && *end == '\0') std::snprintf(number, sizeof number, "%g", value);
    else std::snprintf(number, sizeof number, "%.30s", lr.c_str());
    std::string line = std::string("lr ") + number;
    // Appended piece by piece: GCC 12 warns falsely (-Wstringop-overflow) on " " + string here.
    if (!get("schedule").empty()) line.append(" ").append(get("schedule"));
    if (!get("epochs").empty()) line.append(" over ").append(get("epochs")).append(" epochs");
    add(line);
  }
  if (!get("patience").empty()) add("patience " + get("patience"));
  if (!get("monitor_loss").empty()) add("best epoch by the validation " + get("monitor_loss") + " loss");
  if (!get("ranks").empty()) add("MPI ranks " + get("ranks"));
  if (!line.empty()) std::printf("  %-14s %s\n", "training", line.c_str());
  if (!get("init").empty())
    std::printf("  %-14s %s (the model it started from, by its path at the time)\n", "init", get("init").c_str());
}

// A push-out (TailorNet's post-processing) the model's graph applies after
// the network: what predict's drapes went through, and how to go without it.
void print_post_processing(const Registry& registry, const std::string& graph_text, const std::string& where) {
  for (const PushOutSetting& p : push_out_settings(registry, graph_text, where)) {
    if (p.enabled)
      std::printf("  %-14s %s: vertices inside the body or within %.1f mm pushed out to it%s (the network alone: "
                  "--set %s.enabled=false)\n", "push-out", p.node.c_str(), 1000 * p.epsilon,
                  p.edges ? ", edges with their midpoint within half that lifted off it" : "", p.node.c_str());
    else
      std::printf("  %-14s %s: off (--set %s.enabled=true, or drape model set, turns it on)\n", "push-out",
                  p.node.c_str(), p.node.c_str());
    if (p.enabled && p.strain_limit > 0)
      std::printf("  %-14s %s: first every edge longer than %.2f times its rest length (%s) shortened to that "
                  "(--set %s.strain_limit=0: off)\n", "strain limit", p.node.c_str(), 1.0 + p.strain_limit,
                  p.grade_connected ? "the pattern of the size the body wears" : "the template's pattern, whatever the size",
                  p.node.c_str());
    if (p.mirror_average)
      std::printf("  %-14s before %s: the network also drapes the body in its mirrored pose, and the garment is the "
                  "mean of its own and that twin's reflection (--set %s.mirror_average=false: off, one network pass)\n",
                  "mirror average", p.node.c_str(), p.node.c_str());
  }
}

int info(const std::vector<std::string>& args) {
  po::options_description opts("drape model info");
  opts.add_options()("model", po::value<std::string>()->required(), "model file");
  po::positional_options_description positional;
  positional.add("model", 1);
  po::variables_map vm;
  if (!parse(kInfoUsage, args, opts, positional, vm)) return 0;
  const fs::path file = find_input_file(vm["model"].as<std::string>());  // models/... from anywhere
  const Checkpoint c = read_checkpoint(file);
  std::printf("%s\n", file.string().c_str());
  for (const char* key : {"kind", "status", "epoch", "best_epoch", "best_loss", "dataset", "ground_truth", "train_samples", "drape_version"}) {
    const auto it = c.meta.find(key);
    if (it == c.meta.end()) continue;
    // A model trained before 2026-11-29 stored the dataset's absolute path:
    // its file name is what says which data it was (a glob pattern is shown
    // whole: its last component would cut a {a,b} alternative in half).
    const std::string value = std::string(key) == "dataset" ? dataset_name(it->second) : it->second;
    std::printf("  %-14s %s\n", key, value.c_str());
  }
  print_training_settings(c.meta);
  if (const auto assets = c.meta.find("assets"); assets != c.meta.end()) {
    const AssetsSpec spec = parse_assets_spec(assets->second, file.string() + " meta 'assets'");
    if (!spec.encoder_body.empty())
      std::printf("  %-14s %s: the encoder reads the body resampled onto that body model's template vertices "
                  "(drape train --encoder-body; docs/bodies.md, \"One encoder for both rigs\")\n",
                  "encoder body", spec.encoder_body.c_str());
  }
  print_post_processing(Registry::load_default(plugin_path(vm)), c.graph, file.string() + " (graph)");
  if (auto chart = c.meta.find("size_chart"); chart != c.meta.end()) print_size_chart(chart->second, file.string());
  if (auto domain = read_domain(file)) print_domain(*domain, graph_takes_pose(c.graph, file.string() + " (graph)"));
  else
    std::printf("domain: not recorded (a model written before drape recorded it): predict cannot tell a body outside "
                "it; add it with `drape model domain %s --data DATASET`\n",
                file.string().c_str());
  return 0;
}

int domain(const std::vector<std::string>& args) {
  po::options_description opts("drape model domain");
  opts.add_options()("model", po::value<std::string>()->required(), "model file")(
      "data", po::value<std::string>()->required(), "the dataset it was trained on (its training split is the domain)")(
      "out", po::value<std::string>(), "write here instead of replacing MODEL")(
      "force", po::bool_switch(), "record it although the model names another dataset as its training data");
  po::positional_options_description positional;
  positional.add("model", 1);
  po::variables_map vm;
  if (!parse(kDomainUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  const fs::path file = find_input_file(vm["model"].as<std::string>());
  const fs::path out = vm.count("out") ? fs::path(vm["out"].as<std::string>()) : file;
  // --data X --out X turned the dataset into a model file; any other file is not replaced either.
  refuse_output_among_inputs(out, dataset_inputs(vm["data"].as<std::string>()), "--out");
  // One writer per output (a generate running on it took its lock: this
  // wrote the model, then generate renamed its dataset over it).
  const OutputLock lock(out, "drape model domain");
  refuse_replacing_other_than_a_model(out, vm.count("out") ? "--out" : "MODEL (replaced without --out)");
  // The domain is what predict warns outside of: another shard's bodies, or a
  // posed set's pose ranges on an A-pose model, were recorded silently (an
  // outside check), and predict then warned about bodies the model never saw.
  const Checkpoint c = read_checkpoint(file);
  const std::string given = dataset_name(vm["data"].as<std::string>());
  if (const auto trained_on = c.meta.find("dataset"); trained_on != c.meta.end() && !vm["force"].as<bool>()) {
    const std::string name = dataset_name(trained_on->second);
    if (name != given)
      throw UsageError(file.string() + " was trained on " + name + " (its meta 'dataset'), not " + given +
                       ": the domain would describe bodies it never learnt from. Give the dataset it was trained on, or "
                       "--force to record this one anyway");
  }
  if (!graph_takes_pose(c.graph, file.string() + " (graph)") && !DatasetReader(vm["data"].as<std::string>()).layout().pose_angles.empty())
    throw UsageError(given + " holds posed drapes, and " + file.string() +
                     "'s graph takes no pose (an A-pose model): its domain is A-pose bodies; give an A-pose dataset");
  Registry& registry = Registry::load_default(plugin_path(vm));
  const ModelDomain d = record_model_domain(registry, file, vm["data"].as<std::string>(), out);
  std::printf("wrote %s\n", out.string().c_str());
  print_domain(d);
  return 0;
}

int set(const std::vector<std::string>& args) {
  po::options_description opts("drape model set");
  opts.add_options()("model", po::value<std::string>()->required(), "model file")(
      "set", po::value<std::vector<std::string>>(), "node.param=value: a parameter of a node without learnt weights, "
                                                    "e.g. post.enabled=true (repeatable)")(
      "out", po::value<std::string>(), "write here instead of replacing MODEL");
  po::positional_options_description positional;
  positional.add("model", 1);
  po::variables_map vm;
  if (!parse(kSetUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  if (!vm.count("set")) throw UsageError("--set node.param=value is required\nusage: " + std::string(kSetUsage));
  const fs::path file = find_input_file(vm["model"].as<std::string>());
  const fs::path out = vm.count("out") ? fs::path(vm["out"].as<std::string>()) : file;
  const OutputLock lock(out, "drape model set");  // one writer per output
  // A dataset named as --out became a model file; one named as MODEL was
  // said to be "--out" when no --out was given.
  refuse_replacing_other_than_a_model(out, vm.count("out") ? "--out" : "MODEL (replaced without --out)");
  Registry& registry = Registry::load_default(plugin_path(vm));
  for (const std::string& change : set_model_params(registry, file, parse_param_overrides(vm), out))
    std::printf("  %s\n", change.c_str());
  std::printf("wrote %s\n", out.string().c_str());
  return 0;
}

int run(const std::vector<std::string>& args) {
  const std::string usage = std::string("usage: ") + kInfoUsage + "\n       " + kDomainUsage + "\n       " + kSetUsage;
  if (args.empty()) throw UsageError("info, domain or set?\n" + usage);
  const std::string& action = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (action == "info") return info(rest);
  if (action == "domain") return domain(rest);
  if (action == "set") return set(rest);
  if (action == "--help" || action == "-h" || action == "help") {
    std::cout << usage << "\n\n  info    what a model file holds and the body domain it was trained on\n"
                          "  domain  record the domain of a dataset's training split in a model\n"
                          "  set     store parameters of graph nodes without learnt weights (e.g. post.enabled=true)\n";
    return 0;
  }
  throw UsageError("unknown action '" + action + "'" + did_you_mean(action, {"info", "domain", "set"}) + "\n" + usage);
}

const RegisterCommand registration{{"model", "what a model file holds, and the body domain it knows (info, domain, set)", run}};

}  // namespace
}  // namespace drape::cli
