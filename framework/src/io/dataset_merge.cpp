// merge_datasets: shard files concatenated into one finished dataset.
#include "dataset_internal.hpp"

#include <drape/io/atomic_file.hpp>
#include <drape/bodies/body.hpp>
#include <drape/training/model.hpp>
#include <drape/scene/scene.hpp>
#include <drape/warnings.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace fs = std::filesystem;

namespace drape {

using namespace dataset_detail;

namespace {

// A resolved scene (Scene::yaml()) without what differs between shards of
// one experiment in several garment sizes: the garment's size and grade and
// the description. --mixed-sizes compared nothing of the scenes, and a shard
// draped without friction merged with one draped with it, labelled as the
// first (an outside check).
std::string scene_beyond_size(const std::string& yaml) {
  YAML::Node scene;
  try {
    scene = YAML::Load(yaml);
  } catch (const YAML::Exception&) {
    return yaml;  // compared as text
  }
  if (!scene.IsMap()) return yaml;
  scene.remove("description");
  if (YAML::Node garment = scene["garment"]; garment && garment.IsMap()) {
    garment.remove("grade");
    if (YAML::Node params = garment["params"]; params && params.IsMap()) params.remove("size");
  }
  YAML::Emitter out;
  out << scene;
  return out.c_str();
}

constexpr const char* kGarmentSize = "garment_size";

// The size flag of a shard made before drape generate recorded garment_size:
// every sample of it has the garment of its stored (resolved) scene.
double garment_size_from_scene(const fs::path& shard, const std::string& scene_text) {
  const Scene scene = parse_scene(scene_text, shard.string() + " (its stored scene)");
  try {
    return garment_size_flag(scene);
  } catch (const ConfigError& e) {
    throw ConfigError(shard.string() + ": " + e.what());
  }
}

constexpr const char* kGarmentGrade = "garment_grade";

// The garment_grade of a shard made before drape generate recorded it: its
// scene's grade, when every sample wears the design size (size flag 0).
double garment_grade_from_scene(const fs::path& shard, const h5::File& file, const DatasetLayout& layout) {
  const bool design = layout.has_stat(kGarmentSize) ? [&] {
    for (double f : file.read<double>(stat_path(kGarmentSize)))
      if (f != 0.0) return false;
    return true;
  }() : garment_size_from_scene(shard, layout.scene) == 0.0;
  if (!design)
    throw ConfigError(shard.string() + ": has no garment_grade statistic and its samples wear another size than the "
                      "design size (made before drape generate recorded it): generate it again");
  return parse_scene(layout.scene, shard.string() + " (its stored scene)").garment_grade;
}

// With --mixed-sizes, what a shard lacks of the other shards' statistics, as
// a value for all its rows: its size flag and grade from its scene, and NaN
// ("not measured") for the rest, e.g. the energy of an effect its scene did
// not have.
std::map<std::string, double> missing_stat_fills(const fs::path& shard, const h5::File& file, const DatasetLayout& layout,
                                                 const std::vector<std::string>& all_stats) {
  std::map<std::string, double> fills;
  for (const std::string& name : all_stats) {
    if (layout.has_stat(name)) continue;
    fills[name] = name == kGarmentSize    ? garment_size_from_scene(shard, layout.scene)
                  : name == kGarmentGrade ? garment_grade_from_scene(shard, file, layout)
                                          : std::numeric_limits<double>::quiet_NaN();
  }
  return fills;
}

// What the output gets of the body vertices: none (slim), or each shard's
// own, or, for a slim shard, the body model's rebuild from the parameters.
struct BodyVertices {
  bool write = true;
  const BodyModel* rebuild = nullptr;  // used for shards that left them out
  std::function<void()> rebuilt;       // after each rebuilt body, when set
};

// Copies `count` rows starting at `from` in `in` to row `to` of `out`, for
// every array; a statistic the shard lacks gets its value in `fills`.
void copy_rows(const h5::File& in, bool in_has_bodies, bool in_has_witness, h5::File& out, const DatasetLayout& layout, std::size_t from,
               std::size_t to, std::size_t count, const std::map<std::string, double>& fills, const BodyVertices& bodies) {
  auto copy = [&](const std::string& dataset, std::size_t row_size, auto tag) {
    using T = decltype(tag);
    std::vector<T> rows(count * row_size);
    in.read_rows(dataset, from, count, rows.data());
    out.write_rows(dataset, to, count, rows.data());
  };
  const std::size_t p = static_cast<std::size_t>(layout.body_params);
  std::vector<float> params(count * p), poses(count * layout.pose_angles.size());
  in.read_rows(kParams, from, count, params.data());
  out.write_rows(kParams, to, count, params.data());
  if (!layout.pose_angles.empty()) {
    in.read_rows(kPose, from, count, poses.data());
    out.write_rows(kPose, to, count, poses.data());
  }
  const std::size_t body_size = static_cast<std::size_t>(layout.body_vertices) * 3;
  const std::size_t witness_size = witness_blocks(layout.body_vertices) * 4;
  if (bodies.write && in_has_bodies) {
    copy(kBodyVertices, body_size, float{});
  } else if (bodies.write) {
    const std::vector<float> rows = rebuilt_bodies(*bodies.rebuild, params, count, p, layout.pose_angles, poses, bodies.rebuilt);
    if (in_has_witness) {  // the rebuilt bodies must be the simulated ones
      std::vector<double> witness(count * witness_size);
      in.read_rows(kBodyWitness, from, count, witness.data());
      for (std::size_t r = 0; r < count; ++r)
        if (const std::string refused = not_the_simulated_body(in.path().string(), from + r, rows.data() + r * body_size,
                                                               layout.body_vertices, witness.data() + r * witness_size);
            !refused.empty())
          throw ConfigError(refused);
    }
    out.write_rows(kBodyVertices, to, count, rows.data());
  } else if (in_has_bodies) {  // slim: the witness of the bodies left out
    std::vector<float> rows(count * body_size);
    in.read_rows(kBodyVertices, from, count, rows.data());
    std::vector<double> witness(count * witness_size);
    for (std::size_t r = 0; r < count; ++r)
      body_witness(rows.data() + r * body_size, layout.body_vertices, witness.data() + r * witness_size);
    out.write_rows(kBodyWitness, to, count, witness.data());
  }
  copy(kGarmentVertices, static_cast<std::size_t>(layout.garment_vertices) * 3, float{});
  copy(kSplit, 1, std::int8_t{});
  for (const auto& name : layout.stats) {
    if (const auto f = fills.find(name); f != fills.end()) {
      const std::vector<double> fill(count, f->second);
      out.write_rows(stat_path(name), to, count, fill.data());
    } else {
      copy(stat_path(name), 1, double{});
    }
  }
  const std::vector<std::uint8_t> done(count, 1);
  out.write_rows(kDone, to, count, done.data());
}

// A row's state in `done` as the join reads it: the file's 0 and 1, and a
// done row --drop names, which counts as done and is not copied.
constexpr std::uint8_t kRowDone = 1, kRowDropped = 2;

constexpr const char* kGlobalIndex = "global_index";
constexpr const char* kDropped = "dropped";

// The global indices in a file's `dropped` attribute (those an earlier merge
// or slim left out); none when it has none.
std::vector<long> dropped_before(const DatasetLayout& layout, const fs::path& file) {
  const auto text = layout.attributes.find(kDropped);
  if (text == layout.attributes.end() || text->second.find_first_not_of(" \t") == std::string::npos) return {};
  return parse_global_indices(text->second, file.string() + ": attribute 'dropped'");
}

// Per shard, which rows `drop` names by the generator's global index (the
// global_index statistic, as drape generate names a drape in its report):
// a shard without the statistic cannot be told which, and an index no shard
// holds is a typo, not a silent no-op.
std::vector<std::vector<char>> rows_to_drop(const std::vector<h5::File>& files, const std::vector<DatasetLayout>& layouts,
                                            const std::vector<fs::path>& shards, const std::vector<long>& drop) {
  std::vector<std::vector<char>> out(files.size());
  if (drop.empty()) return out;
  std::vector<char> found(drop.size(), 0);
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (!layouts[k].has_stat(kGlobalIndex))
      throw ConfigError(shards[k].string() + ": has no global_index statistic (made before drape generate recorded it), so "
                        "--drop cannot tell its samples apart; leave --drop out for it");
    const std::vector<double> global = files[k].read<double>(stat_path(kGlobalIndex));
    out[k].assign(global.size(), 0);
    for (std::size_t r = 0; r < global.size(); ++r)
      for (std::size_t d = 0; d < drop.size(); ++d)
        if (global[r] == static_cast<double>(drop[d])) out[k][r] = 1, found[d] = 1;
  }
  for (std::size_t d = 0; d < drop.size(); ++d)
    if (!found[d])
      throw ConfigError("--drop " + std::to_string(drop[d]) + ": no sample of the " +
                        (files.size() == 1 ? "file " + shards.front().string() : std::to_string(files.size()) + " files") +
                        " has that global index (the global_index statistic: drape dataset info lists its range)");
  return out;
}

// The run a file's drapes come from (its generator attribute without the
// shards, with the scene and template it was made in: sizes of one garment
// are made by one command each) and which of its shards the file holds:
// generate's "shard i/N", or a merge's "shards i,j of N" (a slim or
// expanded copy's "shard i of N"); an empty run for a file without one
// (made before the attribute, or a merge of several runs).
struct RunShard {
  std::string run;       // the generator without the shards, as said
  std::string identity;  // run, scene and template: what makes two files one run
  std::vector<long> indices;
  long count = -1;
  std::string shards() const {  // "shard 1/2", "shards 0,1 of 2"
    if (indices.size() == 1) return "shard " + std::to_string(indices.front()) + "/" + std::to_string(count);
    std::string list;
    for (const long i : indices) list += (list.empty() ? "" : ",") + std::to_string(i);
    return "shards " + list + " of " + std::to_string(count);
  }
};
RunShard run_of(const DatasetLayout& layout) {
  RunShard out;
  const auto generator = layout.attributes.find("generator");
  if (generator == layout.attributes.end() || generator->second.find(" + ") != std::string::npos) return out;
  static const std::regex shard(", shards? ([0-9,]+)(?:/| of )(\\d+)");
  std::smatch m;
  if (!std::regex_search(generator->second, m, shard)) return out;
  std::stringstream list(m[1].str());
  for (std::string item; std::getline(list, item, ',');)
    if (!item.empty()) out.indices.push_back(std::stol(item));
  if (out.indices.empty()) return out;
  out.run = m.prefix().str() + m.suffix().str();
  out.identity = out.run + "\n" + layout.template_hash + "\n" + layout.scene;
  out.count = std::stol(m[2]);
  return out;
}

// One run's drapes merged twice (a file given twice, or two files of the
// same shard of one run) are said: oversampling is a use (the same file
// merged twice), but merging one full run with a copy of it, or a shard
// twice by mistake, gave every drape twice without a word (an outside
// check). One run's shards not all given are said too (the merged set lacks
// their samples); shards of different runs merge quietly (their global
// indices repeat).
void check_runs(const std::vector<fs::path>& shards, const std::vector<DatasetLayout>& layouts) {
  for (std::size_t a = 0; a < shards.size(); ++a)
    for (std::size_t b = a + 1; b < shards.size(); ++b)
      if (std::error_code ec; fs::equivalent(shards[a], shards[b], ec))
        warn(shards[b].string() + " is given twice (also as " + shards[a].string() +
             "): its drapes are merged twice, each counting twice (oversampling)");
  std::map<std::string, std::map<long, std::size_t>> runs;  // run identity -> shard index -> input
  std::map<std::string, RunShard> named;
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const RunShard r = run_of(layouts[k]);
    if (r.run.empty()) continue;
    std::set<std::size_t> again;  // earlier inputs holding one of this file's shards
    for (const long index : r.indices) {
      const auto [at, fresh] = runs[r.identity].emplace(index, k);
      if (!fresh && at->second != k && !fs::equivalent(shards[k], shards[at->second])) again.insert(at->second);
    }
    for (const std::size_t earlier : again)
      warn(shards[k].string() + " (" + r.shards() + ") holds drapes of the same run as " + shards[earlier].string() +
           " (" + run_of(layouts[earlier]).shards() + "; " + r.run + "): the same drapes are merged twice, each counting twice");
    named[r.identity] = r;
  }
  // (One file alone is copied, slimmed or expanded, not merged: nothing is lacking.)
  for (const auto& [identity, given] : runs)
    if (shards.size() > 1 && static_cast<long>(given.size()) < named[identity].count) {
      std::string which;
      for (const auto& [index, input] : given) which += (which.empty() ? "" : ", ") + std::to_string(index);
      warn("merging shard" + std::string(given.size() > 1 ? "s " : " ") + which + " of the " +
           std::to_string(named[identity].count) + " of one run (" + named[identity].run +
           "): the merged set lacks the other shards' samples");
    }
}

std::size_t join_shards(const std::vector<fs::path>& shards, const fs::path& out, bool require_complete, bool mixed_sizes,
                        const BodyVertices& bodies, const std::vector<long>& drop) {
  if (shards.empty()) throw ConfigError("merge: no shard files given");
  std::vector<h5::File> files;
  std::vector<std::vector<std::uint8_t>> done;
  DatasetLayout merged;
  std::size_t total = 0;
  std::string templates;
  std::vector<std::map<std::string, double>> fills;  // per shard: the statistics it lacks (--mixed-sizes)
  std::vector<bool> has_bodies;                       // per shard: false for a slim one
  std::vector<bool> has_witness;                      // per shard: a slim one that keeps the witness of its bodies
  std::vector<DatasetLayout> layouts;
  std::vector<std::string> all_stats;  // with --mixed-sizes: every shard's, and the size flag and grade
  for (const auto& shard : shards) {
    if (fs::exists(out) && fs::equivalent(shard, out))
      throw ConfigError("--out " + out.string() + " is also an input (" + shard.string() + "): the job would write over what it reads");
    files.push_back(h5::File::open(shard));
    layouts.push_back(read_layout(files.back()));
    for (const std::string& name : layouts.back().stats) all_stats.push_back(name);
  }
  check_runs(shards, layouts);
  if (mixed_sizes) {
    // The size flag always; the grade when a shard has it (shards made before
    // it existed merge among themselves as before).
    const bool any_grade = std::find(all_stats.begin(), all_stats.end(), kGarmentGrade) != all_stats.end();
    all_stats.push_back(kGarmentSize);
    if (any_grade) all_stats.push_back(kGarmentGrade);
    std::sort(all_stats.begin(), all_stats.end());
    all_stats.erase(std::unique(all_stats.begin(), all_stats.end()), all_stats.end());
  }
  const std::vector<std::vector<char>> dropped = rows_to_drop(files, layouts, shards, drop);
  std::vector<long> dropped_all = drop;  // what the output records: these, and what its shards' merges dropped
  std::optional<SizeTable> size_chart;  // the size charts of the shards that have one, joined
  std::string weights_seen;                 // optimize --data's model_weights, of the first shard recording them
  fs::path weights_from;
  std::vector<std::string> unweighed;       // shards recording none
  for (std::size_t k = 0; k < shards.size(); ++k) {
    const fs::path& shard = shards[k];
    DatasetLayout layout = layouts[k];
    has_bodies.push_back(layout.body_vertices_stored);
    if (bodies.write && !layout.body_vertices_stored && !bodies.rebuild)
      throw ConfigError(shard.string() + ": a slim dataset (no body vertices); join slim shards with `drape dataset expand`");
    if (!layout.body_vertices_stored && bodies.rebuild) dataset_body_model(bodies.rebuild, layout, shard.string());
    has_witness.push_back(!layout.body_vertices_stored && files[k].exists(kBodyWitness));
    if (has_witness.back()) check_witness_shape(files[k], layout);
    layout.body_vertices_stored = bodies.write;  // compared across shards as the output will hold them
    done.push_back(files[k].read<std::uint8_t>(kDone));
    // (A row --drop names counts as done for require_complete, and is not copied.)
    const std::size_t n_done = static_cast<std::size_t>(std::count(done.back().begin(), done.back().end(), kRowDone));
    if (!dropped[k].empty())
      for (std::size_t r = 0; r < done.back().size(); ++r)
        if (dropped[k][r] && done.back()[r] == kRowDone) done.back()[r] = kRowDropped;
    const std::size_t n = static_cast<std::size_t>(std::count(done.back().begin(), done.back().end(), kRowDone));
    for (const long g : dropped_before(layout, shard)) dropped_all.push_back(g);
    fills.emplace_back();
    if (mixed_sizes) {
      fills.back() = missing_stat_fills(shard, files[k], layout, all_stats);
      layout.stats = all_stats;
    }
    // Every path joins the charts, not only --mixed-sizes: shards of one
    // `size: auto` scene made before and after sizes were added differ in
    // their chart alone, and the first shard's would leave the later sizes out
    // of the merged (or expanded) file.
    join_size_chart(size_chart, layout, shard.string());
    templates += (templates.empty() ? "" : ",") + layout.template_hash;
    if (require_complete && n_done != layout.samples)
      throw ConfigError(shard.string() + ": only " + std::to_string(n_done) + " of " + std::to_string(layout.samples) +
                        " samples are done; finish generating it first");
    // Drapes optimised by other weights (a model retrained between two
    // shards' runs) are two experiments in one file: merged without a word
    // until an outside check (optimize --data records model_weights). Each
    // shard against the first that records them (a file made before the
    // fingerprints, first in the list, let every other through).
    if (const auto w = layout.attributes.find("model_weights"); w != layout.attributes.end() && !w->second.empty()) {
      if (weights_seen.empty()) {
        weights_seen = w->second, weights_from = shard;
      } else if (w->second != weights_seen) {
        throw ConfigError(shard.string() + ": cannot merge with " + weights_from.string() +
                          ": its drapes were optimised by other model weights (fingerprint " + w->second + ", " +
                          weights_from.filename().string() + "'s " + weights_seen + ")");
      }
    } else {
      unweighed.push_back(shard.filename().string());
    }
    if (k == 0) {
      merged = layout;
    } else {
      DatasetLayout same = layout;
      same.samples = merged.samples;  // shards may differ in length, nothing else
      if (mixed_sizes) {             // ... and in the garment's size
        if (scene_beyond_size(layout.scene) != scene_beyond_size(merged.scene))
          throw ConfigError(shard.string() + ": cannot merge with " + shards.front().string() +
                            ": their scenes differ in more than the garment's size (--mixed-sizes joins sizes of one "
                            "scene; the effects, materials, body or solver differ):\n" + shards.front().filename().string() +
                            ":\n" + merged.scene + "\n" + shard.filename().string() + ":\n" + layout.scene);
        same.scene = merged.scene;
        same.template_hash = merged.template_hash;
        same.attributes = merged.attributes;
      }
      // Each value said with its file (the message named this shard first and
      // gave the first shard's value as "in the file": an outside check).
      const std::string difference = layout_difference(same, merged, "here", "in " + shards.front().filename().string());
      const bool other_garment = same.scene != merged.scene || same.template_hash != merged.template_hash;
      if (!difference.empty())
        throw ConfigError(shard.string() + ": cannot merge with " + shards.front().string() + ": " + difference +
                          (other_garment && !mixed_sizes ? " (another scene or garment template; shards of different "
                                                           "garment sizes merge with --mixed-sizes)"
                                                         : ""));
    }
    total += n;
  }
  merged.samples = total;
  merged.created = now_utc();
  std::string names;
  for (const auto& shard : shards) {
    if (!names.empty()) names += '\n';
    names += shard.filename().string();
  }
  merged.attributes["merged_from"] = names;
  // The weights are the set's only when every file records the same.
  if (!weights_seen.empty() && unweighed.empty()) merged.attributes["model_weights"] = weights_seen;
  else merged.attributes.erase("model_weights");
  if (!weights_seen.empty() && !unweighed.empty()) {
    std::string list;
    for (const std::string& name : unweighed) list += (list.empty() ? "" : ", ") + name;
    warn("merge: " + list + " record no model weights (optimised before drape recorded them), " +
         weights_from.filename().string() + " does: whether they were optimised by the same model cannot be told");
  }
  // Each shard's own source drapes' fingerprint (optimize --data) says
  // nothing of a set of several: left out (one file slimmed or expanded
  // keeps its own, which a rerun of its request is checked against).
  if (shards.size() > 1) merged.attributes.erase("source_drapes");
  // How the samples were made: the one run's settings with the shards it
  // holds ("..., shards 0,1 of 2"), or every run's (it named the first
  // shard's alone); no longer "shard i/N", which merges read as one shard.
  {
    std::map<std::string, std::vector<long>> held;  // run -> shard indices
    std::map<std::string, long> counts;
    std::vector<std::string> others;  // generators without a shard
    for (const DatasetLayout& layout : layouts) {
      const RunShard r = run_of(layout);
      if (!r.run.empty()) held[r.run].insert(held[r.run].end(), r.indices.begin(), r.indices.end()), counts[r.run] = r.count;
      else if (const auto g = layout.attributes.find("generator"); g != layout.attributes.end()) others.push_back(g->second);
    }
    std::vector<std::string> texts;
    for (auto& [run, indices] : held) {
      std::sort(indices.begin(), indices.end());
      indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
      std::string list;
      for (const long i : indices) list += (list.empty() ? "" : ",") + std::to_string(i);
      texts.push_back(run + ", shard" + (indices.size() > 1 ? "s " : " ") + list + " of " + std::to_string(counts[run]));
    }
    std::sort(others.begin(), others.end());
    others.erase(std::unique(others.begin(), others.end()), others.end());
    texts.insert(texts.end(), others.begin(), others.end());
    std::string generator;
    for (const std::string& t : texts) generator += (generator.empty() ? "" : " + ") + t;
    if (!generator.empty()) merged.attributes["generator"] = generator;
  }
  if (mixed_sizes) merged.attributes["templates"] = templates;
  if (size_chart) merged.attributes["size_chart"] = size_chart->to_text();
  std::sort(dropped_all.begin(), dropped_all.end());
  dropped_all.erase(std::unique(dropped_all.begin(), dropped_all.end()), dropped_all.end());
  if (!dropped_all.empty()) merged.attributes[kDropped] = global_index_list(dropped_all);
  else merged.attributes.erase(kDropped);

  write_atomically(out, [&](const fs::path& tmp) {
    h5::File result = h5::File::create(tmp);
    create_layout(result, merged);
    if (!bodies.write)
      result.create<double>(kBodyWitness, {total, witness_blocks(merged.body_vertices), 4}, {.preallocate = true});
    std::size_t to = 0;
    for (std::size_t s = 0; s < files.size(); ++s) {
      const auto& d = done[s];
      // Runs of consecutive done samples, in blocks that keep memory bounded.
      constexpr std::size_t kBlock = 64;
      std::size_t i = 0;
      while (i < d.size()) {
        if (d[i] != kRowDone) {  // not done, or dropped
          ++i;
          continue;
        }
        std::size_t run = 1;
        while (i + run < d.size() && d[i + run] == kRowDone && run < kBlock) ++run;
        copy_rows(files[s], has_bodies[s], has_witness[s], result, merged, i, to, run, fills[s], bodies);
        i += run;
        to += run;
      }
    }
    result.flush(true);
    result.close();
  });
  return total;
}

}  // namespace

std::vector<long> parse_global_indices(const std::string& text, const std::string& what) {
  // Nothing to drop is a shell variable never set (`--drop "$BAD"`): it
  // dropped nothing without a word (an outside check).
  if (text.find_first_not_of(" \t") == std::string::npos)
    throw ConfigError(what + " is empty (a shell variable never set?): give global indices, e.g. 3,17");
  std::vector<long> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) {
    std::size_t used = 0;
    long g = -1;
    try {
      g = std::stol(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || g < 0)
      throw ConfigError(what + ": '" + item + "' is not a global index (a whole number >= 0) in '" + text + "'");
    out.push_back(g);
  }
  return out;
}

std::string global_index_list(const std::vector<long>& indices) {
  std::string list;
  for (const long g : indices) list += (list.empty() ? "" : ",") + std::to_string(g);
  return list;
}

std::size_t merge_datasets(const std::vector<fs::path>& shards, const fs::path& out, bool require_complete,
                           bool mixed_sizes, const std::vector<long>& drop) {
  return join_shards(shards, out, require_complete, mixed_sizes, BodyVertices{}, drop);
}

std::size_t slim_dataset(const fs::path& in, const fs::path& out, const std::vector<long>& drop) {
  {
    const h5::File file = h5::File::open(in);
    const DatasetLayout layout = read_layout(file);
    if (!layout.body_vertices_stored) throw ConfigError(in.string() + ": is a slim dataset already");
    // A slim file rebuilds each body from its shape parameters with the
    // scene's body model; a resampled set's bodies are the source bodies read
    // at another template's vertices, which no shape makes: its slim copy was
    // written, exit 0, and refused by every reader after (an outside check).
    if (layout.attributes.count("resampled_from"))
      throw ConfigError(in.string() + ": its bodies were resampled onto another template (`drape dataset resample`), so "
                        "its body model cannot rebuild them from their shape parameters: it stays whole; slim the "
                        "source set instead");
  }
  return join_shards({in}, out, true, false, BodyVertices{.write = false, .rebuild = nullptr, .rebuilt = {}}, drop);
}

std::size_t expand_datasets(const std::vector<fs::path>& shards, const fs::path& out, const BodyModel& body_model,
                            bool require_complete, const std::function<void()>& rebuilt, bool mixed_sizes) {
  return join_shards(shards, out, require_complete, mixed_sizes, BodyVertices{.write = true, .rebuild = &body_model, .rebuilt = rebuilt},
               std::vector<long>{});
}

}  // namespace drape
