// `drape dataset merge --out all.h5 shard0.h5 shard1.h5 ...`: joins shards
// generated in parallel (drape::merge_datasets).
// `drape dataset info data.h5`: what a dataset file holds (docs/formats.md).
// `drape dataset potential data.h5 --scene S`: its drapes' energies under a scene.
// `drape dataset slim data.h5 --out slim.h5` / `drape dataset expand slim*.h5
// --out data.h5`: without the body vertices, and back (drape::slim_dataset).
#include "command.hpp"
#include "dataset_potential.hpp"

#include <drape/bodies/body.hpp>
#include <drape/io/dataset.hpp>
#include <drape/errors.hpp>
#include <drape/training/model.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/io/write_failure.hpp>
#include <drape/progress.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/dataset_resampling.hpp>
#include <drape/services/dataset_unposing.hpp>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

namespace fs = std::filesystem;

const char* kMergeUsage = "drape dataset merge --out FILE SHARD... [--allow-incomplete] [--mixed-sizes] [--drop I,J] [--force]";
const char* kInfoUsage = "drape dataset info FILE [--scene-lines N]";
const char* kSlimUsage = "drape dataset slim FILE --out SLIM [--drop I,J] [--force]";
const char* kUnposeUsage = "drape dataset unpose FILE --out CANONICAL [--force]";
const char* kResampleUsage = "drape dataset resample FILE --onto SCENE --out RESAMPLED [--force]";
const char* kExpandUsage = "drape dataset expand --out FILE SLIM... [--allow-incomplete] [--mixed-sizes] [--force]";

void refuse_existing(const fs::path& out, const po::variables_map& vm) {
  // A finished dataset is never overwritten by accident (as DatasetWriter does).
  if (fs::exists(out) && !vm.count("force"))
    throw ConfigError(SourceLocation{out.string(), 0}, "exists; pass --force to replace it");
  refuse_replacing_a_model(out, "--out");  // --force replaces a dataset, not a model
}

constexpr const char* kDropHelp =
    "leave out the samples of these global indices (comma-separated or repeated: the global_index statistic, as drape "
    "generate names a drape in its report, e.g. one an independent check rejected); the output lists them in its "
    "attribute 'dropped'";

// The positional shards, each a file or a quoted pattern expanded as the
// readers expand it ('shards/shard-*.h5' was "no such file": an outside
// check); one that matches nothing is refused.
std::vector<fs::path> shard_files(const po::variables_map& vm) {
  std::vector<fs::path> shards;
  for (const auto& given : vm["shards"].as<std::vector<std::string>>())
    for (const fs::path& file : dataset_files(given)) shards.push_back(file);
  return shards;
}

// --drop's global indices, comma-separated or repeated.
std::vector<long> drop_list(const po::variables_map& vm) {
  std::vector<long> out;
  if (!vm.count("drop")) return out;
  for (const std::string& arg : vm["drop"].as<std::vector<std::string>>())
    for (const long g : parse_global_indices(arg, "--drop")) out.push_back(g);
  return out;
}

// The done rows of dataset files (a shard's unfinished samples are not
// copied, so they are not counted as dropped either).
std::size_t done_rows(const std::vector<fs::path>& files) {
  std::size_t n = 0;
  for (const fs::path& f : files) n += DatasetReader(f).indices().size();
  return n;
}

// " (--drop: N global indices, M rows)": the rows a drop removed, which are
// more than the indices named when a merge of the same shard twice (the
// oversampling of docs/training.md) repeats an index.
std::string dropped_text(std::size_t indices, std::size_t rows_before, std::size_t rows_after) {
  if (indices == 0) return "";
  const std::size_t rows = rows_before >= rows_after ? rows_before - rows_after : 0;
  std::string out = " (" + std::to_string(indices) + " global ind" + (indices == 1 ? "ex" : "ices") + " dropped: " +
                    std::to_string(rows) + " row" + (rows == 1 ? "" : "s");
  if (rows > indices) out += ", as an index repeats among the inputs";
  return out + ")";
}

int merge(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset merge");
  opts.add_options()("out,o", po::value<std::string>()->required(), "the merged dataset to write")(
      "shards", po::value<std::vector<std::string>>()->required(), "shard files, joined in this order")(
      "allow-incomplete", "skip the samples a shard has not finished (default: refuse such a shard)")(
      "mixed-sizes", "the shards wear different sizes of one garment (their garment_size and garment_grade statistics "
                     "tell them apart; a statistic a shard lacks is filled: its size and grade from its scene, NaN "
                     "for the rest)")(
      "drop", po::value<std::vector<std::string>>()->composing(), kDropHelp)("force", "replace --out if it exists");
  po::positional_options_description positional;
  positional.add("shards", -1);
  po::variables_map vm;
  if (!parse(kMergeUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  const fs::path out = vm["out"].as<std::string>();
  const OutputLock lock(out, "drape dataset merge");  // before anything looks at it (output_lock.hpp)
  const std::vector<fs::path> shards = shard_files(vm);
  refuse_existing(out, vm);
  const std::vector<long> drop = drop_list(vm);
  const std::size_t before = drop.empty() ? 0 : done_rows(shards);
  const std::size_t n = merge_datasets(shards, out, !vm.count("allow-incomplete"), vm.count("mixed-sizes") > 0, drop);
  std::cout << "merged " << n << " samples from " << shards.size() << " shard" << (shards.size() == 1 ? "" : "s")
            << " into " << out.string() << dropped_text(drop.size(), before, n) << "\n";
  return 0;
}

int slim(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset slim");
  opts.add_options()("file", po::value<std::string>()->required(), "a finished dataset")(
      "out,o", po::value<std::string>()->required(), "the slim copy to write")(
      "drop", po::value<std::vector<std::string>>()->composing(), kDropHelp)("force", "replace --out if it exists");
  po::positional_options_description positional;
  positional.add("file", 1);
  po::variables_map vm;
  if (!parse(kSlimUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  const fs::path in = vm["file"].as<std::string>(), out = vm["out"].as<std::string>();
  const OutputLock lock(out, "drape dataset slim");  // before anything looks at it (output_lock.hpp)
  if (!fs::exists(in)) throw ConfigError(SourceLocation{in.string(), 0}, "no such file");
  refuse_existing(out, vm);
  const std::vector<long> drop = drop_list(vm);
  const std::size_t before = drop.empty() ? 0 : done_rows({in});
  const std::size_t n = slim_dataset(in, out, drop);
  std::cout << "wrote " << out.string() << ": " << n << " samples without body vertices"
            << dropped_text(drop.size(), before, n) << ", " << fs::file_size(out) / 1024
            << " KiB (" << fs::file_size(in) / 1024 << " KiB with them)\n";
  return 0;
}

int expand(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset expand");
  opts.add_options()("out,o", po::value<std::string>()->required(), "the full dataset to write")(
      "shards", po::value<std::vector<std::string>>()->required(), "slim (or full) dataset files, joined in this order")(
      "allow-incomplete", "skip the samples a shard has not finished (default: refuse such a shard)")(
      "mixed-sizes", "the shards wear different sizes of one garment, as for merge")(
      "force", "replace --out if it exists");
  po::positional_options_description positional;
  positional.add("shards", -1);
  po::variables_map vm;
  if (!parse(kExpandUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  const fs::path out = vm["out"].as<std::string>();
  const OutputLock lock(out, "drape dataset expand");  // before anything looks at it (output_lock.hpp)
  const std::vector<fs::path> shards = shard_files(vm);
  refuse_existing(out, vm);
  // The body model of the first shard's own scene, with its parameters: the
  // one that generated the bodies (the others must agree, as in a merge).
  const DatasetLayout layout = DatasetReader(shards.front()).layout();
  const Scene scene = parse_scene(layout.scene, shards.front().string() + " (its stored scene)");
  const auto body_model = make_body_model(Registry::load_default(plugin_path(vm)), assets_spec_for(scene, 0));
  std::size_t slim_samples = 0;  // the bodies to rebuild, for the progress bar
  for (const auto& shard : shards) {
    const DatasetReader reader(shard);
    if (!reader.layout().body_vertices_stored) slim_samples += reader.indices().size();
  }
  ProgressBar bar("expand", slim_samples);
  const std::size_t n = expand_datasets(shards, out, *body_model, !vm.count("allow-incomplete"), [&] { bar.advance(); },
                                        vm.count("mixed-sizes") > 0);
  bar.finish();
  std::cout << "wrote " << out.string() << ": " << n << " samples, their bodies rebuilt by body model '" << scene.body_model
            << "' from the stored shape parameters\n";
  return 0;
}

int unpose(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset unpose");
  opts.add_options()("file", po::value<std::string>()->required(), "a posed dataset (drape generate --poses draw)")(
      "out,o", po::value<std::string>()->required(), "the dataset of its drapes in each body's rest pose")(
      "force", "replace --out if it exists");
  po::positional_options_description positional;
  positional.add("file", 1);
  po::variables_map vm;
  if (!parse(kUnposeUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  const fs::path in = vm["file"].as<std::string>(), out = vm["out"].as<std::string>();
  const OutputLock lock(out, "drape dataset unpose");
  refuse_output_among_inputs(out, dataset_files(in), "--out");  // --force removed the input before reading it
  refuse_existing(out, vm);
  if (fs::exists(out)) fs::remove(out);
  ProgressBar bar("unpose", DatasetReader(in).indices().size());
  const std::size_t n = unpose_dataset(Registry::load_default(plugin_path(vm)), in, out, [&] { bar.advance(); });
  bar.finish();
  std::cout << "wrote " << out.string() << ": " << n << " drapes and bodies in each body's rest pose (joint angles in "
            << "the statistics pose_<name>)\n";
  return 0;
}

int resample(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset resample");
  opts.add_options()("file", po::value<std::string>()->required(), "an A-pose dataset (slim or full), or a glob pattern of shards")(
      "onto", po::value<std::string>()->required(),
      "a scene whose template body the bodies are carried onto (the same garment), e.g. the mannequin's "
      "graphs/scenes/tshirt_coarse_sized.yaml for the human rig's drapes")(
      "out,o", po::value<std::string>()->required(), "the dataset of the resampled bodies (full)")(
      "force", "replace --out if it exists");
  po::positional_options_description positional;
  positional.add("file", 1);
  po::variables_map vm;
  if (!parse(kResampleUsage, args, opts, positional, vm)) return 0;
  check_hdf5_outputs(vm, {"out"});
  const fs::path in = vm["file"].as<std::string>(), out = vm["out"].as<std::string>();
  const fs::path onto = find_input_file(vm["onto"].as<std::string>());  // graphs/scenes/... from any folder
  const OutputLock lock(out, "drape dataset resample");
  refuse_output_among_inputs(out, dataset_files(in), "--out");  // --force removed the input before reading it
  refuse_existing(out, vm);
  if (fs::exists(out)) fs::remove(out);
  ProgressBar bar("resample", DatasetReader(in).indices().size());
  const ResampleSummary s = resample_dataset(Registry::load_default(plugin_path(vm)), in, onto, out, [&] { bar.advance(); });
  bar.finish();
  std::cout << "wrote " << out.string() << ": " << s.samples << " drapes, each body of " << s.source_vertices
            << " vertices read at the " << s.target_vertices << " vertices of " << onto.filename().string()
            << "'s template body (those lie " << s.median_distance * 1000 << " mm from the source template's surface at "
            << "the median, " << s.p90_distance * 1000 << " mm at 90 %, " << s.max_distance * 1000 << " mm at most)\n";
  return 0;
}

// "name: 12 recorded, mean 0.5, min 0, max 1" over the done samples.
std::string stat_summary(const DatasetReader& reader, const std::string& name, const std::vector<std::size_t>& done) {
  const std::vector<double> values = reader.stat(name, done);
  std::size_t recorded = 0;
  double sum = 0, lo = INFINITY, hi = -INFINITY;
  for (double v : values) {
    if (!std::isfinite(v)) continue;  // NaN: not recorded for that sample
    ++recorded;
    sum += v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  std::ostringstream s;
  s << name << ": " << recorded << " of " << done.size() << " recorded";
  if (recorded) s << ", mean " << sum / static_cast<double>(recorded) << ", min " << lo << ", max " << hi;
  return s.str();
}

int info(const std::vector<std::string>& args) {
  po::options_description opts("drape dataset info");
  opts.add_options()("file", po::value<std::string>()->required(), "dataset file (finished or .partial)")(
      "scene-lines", po::value<int>()->default_value(8), "lines of the scene YAML to show");
  po::positional_options_description positional;
  positional.add("file", 1);
  po::variables_map vm;
  if (!parse(kInfoUsage, args, opts, positional, vm)) return 0;
  if (vm["scene-lines"].as<int>() < 0)
    throw UsageError("--scene-lines " + std::to_string(vm["scene-lines"].as<int>()) + ": expected 0 or more lines");
  const fs::path path = vm["file"].as<std::string>();
  const DatasetReader reader(path);  // a file or a glob pattern ("no such file" / "no dataset file matches")
  const DatasetLayout& layout = reader.layout();
  const std::vector<std::size_t> done = reader.indices();
  const bool complete = done.size() == layout.samples;
  std::string slim_note;  // how the bodies a slim file left out are rebuilt, and whether checked
  if (!layout.body_vertices_stored) {
    const std::size_t witnessed = reader.witnessed_files();
    slim_note = " (not stored: a slim dataset, rebuilt as they are read" +
                std::string(witnessed == reader.files().size() ? ", each checked against the witness of the simulated body"
                            : witnessed == 0 ? "; no witness of the simulated bodies (slimmed before 2026-12-01): unchecked"
                                             : "; " + std::to_string(witnessed) + " of " + std::to_string(reader.files().size()) +
                                                   " files keep a witness of the simulated bodies, the others are unchecked") +
                ")";
  }
  if (reader.files().size() > 1)
    std::cout << path.string() << ": " << reader.files().size() << " files read as one, " << reader.files().front().string()
              << " ... " << reader.files().back().string() << "\n";
  std::cout << path.string() << ": drape dataset, " << (complete ? "complete" : "incomplete") << "\n"
            << "  samples   " << layout.samples << ", done " << done.size() << "\n"
            << "  sizes     body params P = " << layout.body_params << ", body vertices Nb = " << layout.body_vertices
            << slim_note
            << ", garment vertices Ng = " << layout.garment_vertices << ", faces "
            << (layout.garment_faces.rows() ? std::to_string(layout.garment_faces.rows()) : "not stored") << "\n"
            << "  poses     "
            << (layout.pose_angles.empty() ? std::string("none: the bodies are in the body model's A-pose")
                                           : std::to_string(layout.pose_angles.size()) +
                                                 " joint angles per body, degrees (/bodies/pose; docs/poses.md)" +
                                                 (reader.mixed_poses() ? "; the A-pose files' bodies at their rest angles"
                                                                       : ""))
            << "\n"
            << "  splits    train " << reader.indices(Split::Train).size() << ", val " << reader.indices(Split::Val).size()
            << ", test " << reader.indices(Split::Test).size() << " (done samples)\n"
            << "  stats     " << layout.stats.size() << " per sample" << (layout.stats.empty() ? "" : ", over the done samples:")
            << "\n";
  for (const auto& name : layout.stats) std::cout << "    " << stat_summary(reader, name, done) << "\n";
  std::cout << "  template  " << layout.template_hash << "\n"
            << "  created   " << layout.created << " by drape " << layout.drape_version << "\n";
  for (const auto& [name, value] : layout.attributes) {
    std::string one_line;  // multi-line values (merged_from: one shard per line) on one line
    for (char c : value) one_line += c == '\n' ? std::string(", ") : std::string(1, c);
    std::cout << "  " << name << ": " << one_line << "\n";
  }
  std::istringstream scene(layout.scene);
  std::vector<std::string> lines;
  for (std::string line; std::getline(scene, line);) lines.push_back(line);
  const std::size_t shown = std::min(lines.size(), static_cast<std::size_t>(vm["scene-lines"].as<int>()));
  std::cout << "  scene     " << lines.size() << " line" << (lines.size() == 1 ? "" : "s") << (shown ? ":" : "") << "\n";
  for (std::size_t i = 0; i < shown; ++i) std::cout << "    | " << lines[i] << "\n";
  if (shown < lines.size()) std::cout << "    | ... (" << lines.size() - shown << " more)\n";
  return 0;
}

int run(const std::vector<std::string>& args) {
  const std::string usage =
      std::string("usage: ") + kMergeUsage + "\n       " + kInfoUsage + "\n       " + kPotentialUsage + "\n       " +
      kSlimUsage + "\n       " + kExpandUsage + "\n       " + kUnposeUsage + "\n       " + kResampleUsage;
  if (args.empty()) throw UsageError("merge or info?\n" + usage);
  const std::string& action = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (action == "merge") return merge(rest);
  if (action == "info") return info(rest);
  if (action == "potential") return dataset_potential(rest);
  if (action == "slim") return slim(rest);
  if (action == "expand") return expand(rest);
  if (action == "unpose") return unpose(rest);
  if (action == "resample") return resample(rest);
  if (action == "--help" || action == "-h" || action == "help") {
    std::cout << usage << "\n\n  merge  join shards generated in parallel into one dataset\n"
                          "  info   sizes, splits, stats and scene of a dataset file\n"
                          "  potential  every effect's energy, L_p and p of the stored drapes under a scene\n"
                          "  slim   a copy without the body vertices (rebuilt from the shape parameters by expand)\n"
                          "  expand join slim datasets into one full dataset, the bodies rebuilt by the scene's body model\n"
                          "  unpose a posed dataset's drapes and bodies in each body's rest pose (docs/poses.md)\n"
                          "  resample  the bodies carried onto another body model's template vertices (docs/bodies.md)\n";
    return 0;
  }
  throw UsageError("unknown action '" + action + "'" + did_you_mean(action, {"merge", "info", "potential", "slim", "expand", "unpose", "resample"}) + "\n" + usage);
}

const RegisterCommand registration{{"dataset", "merge dataset shards, show what a dataset file holds, its drapes' potential under a scene, or slim and expand it", run}};

}  // namespace
}  // namespace drape::cli
