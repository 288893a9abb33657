// generate_dataset (services/dataset_generation.hpp).
#include <drape/bodies/body.hpp>
#include <drape/bodies/body_space.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/io/dataset.hpp>
#include <drape/errors.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/training/model.hpp>
#include <drape/io/output_lock.hpp>

#include "../io/dataset_internal.hpp"
#include <drape/io/parallel_samples.hpp>
#include <drape/progress.hpp>
#include <drape/training/rng.hpp>
#include <drape/services/dataset_generation.hpp>
#include <drape/services/graded_scene.hpp>
#include <drape/scene/simulation.hpp>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <cmath>
#include <atomic>
#include <fstream>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <thread>

namespace drape {
namespace {

// The 8:1:1 split of the whole set (all shards): a seeded permutation, the
// first 80% train, the next 10% validation, the rest test.
std::vector<Split> splits(std::size_t total, std::uint64_t seed) {
  const auto order = Rng(Rng::derive(seed, "split")).permutation(total);
  std::vector<Split> out(total);
  for (std::size_t k = 0; k < total; ++k)
    out[order[k]] = k < total * 8 / 10 ? Split::Train : (k < total * 9 / 10 ? Split::Val : Split::Test);
  return out;
}

// The request on its own, before any work (the same checks for every face).
void check_request(const GenerateRequest& r) {
  if (r.count == 0) throw ConfigError("count: expected at least 1 sample");
  if (r.shard.count == 0 || r.shard.index >= r.shard.count)
    throw ConfigError("shard " + std::to_string(r.shard.index) + "/" + std::to_string(r.shard.count) +
                      ": expected i/N with 0 <= i < N");
  // (A shard of no sample wrote an empty dataset sealed complete: an outside check.)
  if (r.shard.count > r.count)
    throw ConfigError("shard " + std::to_string(r.shard.index) + "/" + std::to_string(r.shard.count) + ": " +
                      std::to_string(r.shard.count) + " shards of a set of " + std::to_string(r.count) +
                      " samples leave some shards empty; give at most as many shards as --count");
  if (!(r.girths >= 0 && r.girths <= 1)) throw ConfigError("girths: expected a fraction in [0, 1]");
  for (const auto& [name, range] : {std::pair{"bmi", r.bmi}, std::pair{"height", r.height}, std::pair{"sex", r.sex}})
    if (std::isnan(range.lo) || std::isnan(range.hi)) throw ConfigError(std::string(name) + " range: not a number (NaN)");
    else if (!(range.lo <= range.hi)) throw ConfigError(std::string(name) + " range: expected lo <= hi");
  if (r.threads < 0) throw ConfigError("threads: expected 0 (all cores) or a count");
}

// The BMI range against what the scene's body model reaches; the height
// and sex ranges by solving the body at each pair of their ends (every
// height between the ends is drawn with either end of the sex range), at
// the mean body's BMI, so that a range the model cannot make is refused
// before the output is begun (an outside check: --height 0.2 was refused at
// the first sample, leaving a .partial whose resume then refused the
// corrected command).
void check_body_ranges(const GenerateRequest& r, const Simulation& sim, const Scene& scene) {
  const BodyModel& model = sim.body_model();
  const auto [bmi_lo, bmi_hi] = model.bmi_range();
  if (r.bmi.lo < bmi_lo - 1e-9 || r.bmi.hi > bmi_hi + 1e-9) {
    std::ostringstream o;
    o << "bmi " << r.bmi.lo << ":" << r.bmi.hi << " is outside what body model '" << scene.body_model << "' reaches ("
      << bmi_lo << ":" << bmi_hi << ")";
    throw ConfigError(o.str());
  }
  for (const double sex : {r.sex.lo, r.sex.hi})
    for (const double height : {r.height.lo, r.height.hi}) {
      BodyRequest request = model.mean_request();
      request.height = height, request.sex = sex;
      try {
        model.solve(request);
      } catch (const ConfigError& e) {
        std::ostringstream o;
        o << "height " << r.height.lo << ":" << r.height.hi << ", sex " << r.sex.lo << ":" << r.sex.hi << ": " << e.what();
        throw ConfigError(o.str());
      }
    }
}

std::string ranges_text(const GenerateRequest& r) {
  std::ostringstream o;
  o << "bmi " << r.bmi.lo << ":" << r.bmi.hi << ", height " << r.height.lo << ":" << r.height.hi << ", sex " << r.sex.lo
    << ":" << r.sex.hi << ", girths " << r.girths << ", seed " << r.seed << ", count " << r.count << ", shard "
    << r.shard.index << "/" << r.shard.count;
  return o.str();
}

// Where each sample's pose comes from: none (A-pose), the scene's, or drawn.
struct PoseSource {
  bool posed = false;
  bool drawn = false;
  Pose scene_pose;                // the scene's (not drawn)
  std::vector<PoseAngle> space;  // what is drawn from (drawn)
  std::string text;              // for the generator attribute
};

PoseSource pose_source(const GenerateRequest& r, const Simulation& sim, const Scene& scene) {
  PoseSource out;
  out.scene_pose = sim.target_pose();
  if (!r.draw_poses && !r.pose_ranges.empty())
    throw ConfigError("pose ranges (" + r.pose_ranges + ") are what poses are drawn from: draw poses too (--poses draw)");
  if (r.draw_poses && !out.scene_pose.empty())
    throw ConfigError(scene.pose.begin()->second.where,
                      "body `pose`: this scene drapes one pose and poses are to be drawn; draw them from the scene "
                      "without its pose, or generate in the scene's pose without drawing");
  out.drawn = r.draw_poses;
  out.posed = out.drawn || !out.scene_pose.empty();
  if (!out.posed) return out;
  const BodyModel& model = sim.body_model();
  if (!model.poseable()) {
    const std::string why = unposeable_reason(model);
    throw ConfigError("body model '" + scene.body_model + "' cannot be posed" + (why.empty() ? " (it has no skeleton)" : ": " + why));
  }
  out.space = with_sampling_ranges(model.pose_angles(), r.pose_ranges, "pose range");
  if (out.drawn) check_drawable(out.space, scene.body_model);
  out.text = out.drawn ? "poses drawn" + std::string(r.pose_ranges.empty() ? "" : " (" + sampling_ranges_text(out.space, model.pose_angles()) + ")")
                       : "pose " + format_pose(out.scene_pose);
  return out;
}

// The pose of a sample as the dataset stores it: full_pose, each angle
// rounded to float, so that the stored angles pose the body that was simulated.
Pose stored_pose(const Pose& pose, const BodyModel& model, const Eigen::MatrixX3d& unposed) {
  Pose out = full_pose(model, pose, unposed);
  for (auto& [name, degrees] : out.angles) degrees = static_cast<double>(static_cast<float>(degrees));
  return out;
}

DatasetLayout layout_of(const Scene& scene, const SceneSimulations& simulations, const GenerateRequest& request,
                        const PoseSource& poses) {
  const Simulation& sim = simulations.design();
  DatasetLayout layout;
  layout.samples = request.shard.last(request.count) - request.shard.first(request.count);
  layout.body_params = static_cast<int>(sim.body_model().mean_shape().size());
  layout.body_vertices = static_cast<int>(sim.mean_body().rows());
  layout.garment_vertices = sim.garment().mesh.num_vertices();
  layout.stats = generated_statistics(scene);
  layout.scene = scene.yaml();
  if (simulations.auto_size()) {
    layout.attributes["garment_sizes"] = "auto: each sample's size in its garment_size statistic (docs/garments.md)";
    // The tailor's rule in numbers, for a model trained on these drapes to
    // choose a body's size by (drape predict --garment-size auto).
    layout.attributes["size_chart"] = simulations.chart()->table().to_text();
  } else if (simulations.auto_grade()) {
    layout.attributes["garment_sizes"] = "grade auto: each sample's grade in its garment_grade statistic (docs/garments.md)";
    layout.attributes["size_chart"] = simulations.grades()->table().to_text();  // the grades as steps g0.50 ... g2.00
  }
  layout.template_hash = template_hash(sim.garment().mesh, sim.body_model().faces());
  layout.garment_faces = sim.garment().mesh.faces;  // for readers without drape's assets (h5py, torch)
  layout.attributes["generator"] = "drape generate: " + ranges_text(request) + (poses.posed ? "; " + poses.text : "");
  if (poses.posed)
    for (const PoseAngle& a : sim.body_model().pose_angles()) layout.pose_angles.push_back(a.name);
  layout.attributes["body_model"] = scene.body_model;
  std::string names;
  for (const auto& n : sim.body_model().shape_names()) names += (names.empty() ? "" : ",") + n;
  layout.attributes["body_param_names"] = names;
  return layout;
}

// The body of global sample `global`: its own seeded stream, so a sample is
// the same whatever the shard, thread or resumption that makes it.
BodyRequest draw_body(const GenerateRequest& r, const BodyModel& model, std::size_t global) {
  Rng rng(Rng::derive(r.seed, "sample-" + std::to_string(global)));
  BodyRequest request;
  request.bmi = rng.uniform(r.bmi.lo, r.bmi.hi);
  request.height = r.height.lo == r.height.hi ? r.height.lo : rng.uniform(r.height.lo, r.height.hi);
  request.sex = r.sex.lo == r.sex.hi ? r.sex.lo : (rng.uniform() < 0.5 ? r.sex.lo : r.sex.hi);
  // Drawn after the rest, and only with a spread, so a seed without girths
  // draws the bodies it always drew.
  if (r.girths > 0) draw_proportions(r.girths, model, rng, request);
  return request;
}

std::string sample_name(std::size_t global, const BodyRequest& request) {
  std::ostringstream who;
  who << "sample " << global << " (BMI " << request.bmi << ", height " << request.height << " m, sex " << request.sex;
  for (const auto& [name, value] : request.proportions) who << ", " << name << " " << value;  // drape body --girth
  who << "; narrow --bmi or --height)";
  return who.str();
}

DatasetSample sample_of(const SimulationResult& r, const Eigen::VectorXd& shape, const BodyRequest& request,
                        std::size_t global, Split split, double size_flag, double grade, const Pose& pose,
                        const std::vector<std::string>& angles) {
  namespace st = sample_stat;
  DatasetSample s;
  s.body_params = shape.cast<float>();
  s.pose.resize(static_cast<Eigen::Index>(angles.size()));
  for (std::size_t a = 0; a < angles.size(); ++a) s.pose[static_cast<Eigen::Index>(a)] = static_cast<float>(pose.angles.at(angles[a]));
  s.body_vertices = r.body.cast<float>();
  s.garment_vertices = r.garment.cast<float>();
  s.split = split;
  for (const auto& t : r.energies) s.stats["energy_" + t.name] = t.value;
  s.stats[st::energy_total] = r.total_energy;
  s.stats[st::penetration] = r.penetration;
  s.stats[st::crossings] = r.crossings ? r.crossings->total() : 0;
  s.stats[st::residual] = r.residual;
  s.stats[st::stationarity] = r.stationarity;
  s.stats[st::converged] = r.converged ? 1 : 0;
  s.stats[st::iterations] = r.iterations;
  s.stats[st::steps] = r.steps;
  s.stats[st::seconds] = r.seconds;
  s.stats[st::bmi] = request.bmi;
  s.stats[st::height] = request.height;
  s.stats[st::sex] = request.sex;
  s.stats[st::global_index] = static_cast<double>(global);
  s.stats[st::garment_size] = size_flag;
  s.stats[st::garment_grade] = grade;
  return s;
}

}  // namespace

std::vector<std::string> generated_statistics(const Scene& scene) {
  namespace st = sample_stat;
  std::vector<std::string> names;
  for (const auto& e : scene.effects) names.push_back("energy_" + e.name);
  for (const char* s : {st::energy_total, st::penetration, st::crossings, st::residual, st::stationarity, st::converged,
                        st::iterations, st::steps, st::seconds, st::bmi, st::height, st::sex, st::global_index,
                        st::garment_size, st::garment_grade})
    names.push_back(s);
  return names;
}

GenerateSummary generate_dataset(const Registry& registry, const Scene& scene, const GenerateRequest& request,
                                 const std::string& out, const GenerateObserver& observer) {
  check_request(request);
  // Before anything looks at the output (output_lock.hpp).
  const OutputLock lock(out, "drape generate", true);
  // size: auto -- each body wears the size its girth needs (garment_size.hpp,
  // every size built once); the dataset's template is the design size's (the
  // sizes share its topology), each sample records its size in garment_size.
  const SceneSimulations simulations(registry, scene);
  const Simulation& sim = simulations.design();
  check_body_ranges(request, sim, scene);
  const PoseSource poses = pose_source(request, sim, scene);
  // The size flag of a graph trained on several sizes (garment_size_flag).
  const double design_size = garment_size_flag(sim.scene());
  // The garment_grade of every sample of a scene without size: auto or grade: auto.
  const double design_grade = GradedScene(registry, simulations).fixed_grade();
  const std::size_t first = request.shard.first(request.count);
  const std::vector<Split> split = splits(request.count, request.seed);

  DatasetLayout layout = layout_of(scene, simulations, request, poses);
  // A finished output: this same job done before (a job array's retry) has
  // nothing to do, as train --resume on a finished run; any other is refused.
  if (const std::optional<std::size_t> done = dataset_detail::finished_by_same_request(out, layout, "generate it again")) {
    GenerateSummary summary;
    summary.samples = *done;
    summary.already_finished = true;
    return summary;
  }
  DatasetWriter writer(out, layout);
  const std::vector<std::size_t> todo = writer.missing();
  GeneratePlan plan;
  plan.out = out;
  plan.total = request.count;
  plan.first = first;
  plan.last = request.shard.last(request.count);
  plan.samples = layout.samples;
  plan.already = layout.samples - todo.size();
  plan.resumed = writer.resumed();
  int threads = request.threads;
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  plan.threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(todo.size(), 1)));
  plan.ranges = ranges_text(request);
  if (observer.on_start) observer.on_start(plan);

  ProgressBar::Options bar_options;
  bar_options.start = plan.already;  // a resumed job: the ETA counts this run's rate only
  std::ofstream discard;             // no bar: a stream that writes nothing
  discard.setstate(std::ios::badbit);
  ProgressBar bar("generate", layout.samples, observer.progress ? *observer.progress : discard, bar_options);
  std::mutex write_mutex;
  std::atomic<int> not_settled{0}, penetrating{0}, crossing{0};
  std::vector<std::size_t> crossing_itself;  // (under write_mutex)
  // The caller's poll stops the simulations under way too, not only the
  // samples not begun: a coarse drape takes 10-60 s.
  std::atomic<bool> polled_stop{false};
  struct StoppedByPoll {};
  std::function<void()> poll;
  if (observer.poll)
    poll = [&] {
      try {
        observer.poll();
      } catch (...) {
        polled_stop = true;
        throw;
      }
    };
  make_samples_in_parallel(writer, bar, todo, plan.threads, [&]() -> SampleWorker {
#ifdef _OPENMP
    omp_set_num_threads(1);  // parallel over samples, not inside one
#endif
    return [&](std::size_t local) {
      const std::size_t global = first + local;
      BodyRequest body_request = draw_body(request, sim.body_model(), global);
      const Eigen::VectorXd shape = solve_in_space(sim.body_model(), body_request);
      const Eigen::MatrixX3d body = sim.body_vertices(shape);
      const std::string who = sample_name(global, body_request);
      // The pose: drawn on its own stream (the shapes stay those of the seed
      // without poses), or the scene's; the size is chosen on the unposed body.
      Pose pose;
      Eigen::MatrixX3d target = body;
      if (poses.posed) {
        const BodyModel& model = sim.body_model();
        if (poses.drawn) {
          Rng pose_rng(Rng::derive(request.seed, "pose-" + std::to_string(global)));
          pose = stored_pose(draw_free_pose(model, shape, pose_rng, 50, &poses.space).pose, model, body);
          target = model.posed_vertices(body, pose, 1.0);  // free of self-crossing: drawn so
        } else {
          pose = stored_pose(poses.scene_pose, model, body);
          try {
            target = pose_vertices(model, scene.body_model, body, pose);
          } catch (const ConfigError& e) {
            throw ConfigError(who + ": " + e.what());
          }
        }
      }
      SizeChoice choice;
      GradeChoice grade_choice;
      const Simulation& wearing = simulations.for_body(body, who, &choice, &grade_choice);
      const double size_flag = simulations.auto_size() ? garment_size_flag(choice.size) : design_size;
      const double grade = simulations.auto_size()    ? scene.garment_grade * simulations.chart()->table().grade(choice.size)
                           : simulations.auto_grade() ? grade_choice.grade
                                                      : design_grade;
      const SimulationResult r = [&] {
        try {
          SimulationOptions options;
          if (poll) {
            options.on_step = [&](const SimulationStep&) {
              if (polled_stop) throw StoppedByPoll{};
            };
            options.on_partial_move = [&](int, int, int, double) {
              if (polled_stop) throw StoppedByPoll{};
            };
          }
          if (poses.posed) {
            options.target_pose = &pose;
            options.unposed_target = &body;
          }
          return wearing.run(target, options);
        } catch (const ConfigError& e) {  // a body the scene refuses: say which sample it is
          const std::string hint = start_fit_hint(wearing);
          throw ConfigError(who + ": " + e.what() + (hint.empty() ? "" : "; " + hint));
        }
      }();
      const DatasetSample s =
          sample_of(r, shape, body_request, global, split[global], size_flag, grade, pose, layout.pose_angles);
      if (!r.converged) ++not_settled;
      if (r.penetration > 0) ++penetrating;
      if (r.crossings && r.crossings->total() > 0) ++crossing;
      {
        const std::lock_guard<std::mutex> guard(write_mutex);
        writer.write(local, s);
        if (r.self_crossings && *r.self_crossings > 0) crossing_itself.push_back(global);
      }
      std::ostringstream status;
      status << "last: BMI " << std::fixed << std::setprecision(1) << body_request.bmi << ", " << r.iterations << " it, "
             << std::setprecision(2) << r.seconds << " s";
      bar.set_status(status.str());
      bar.advance();
    };
  }, poll);
  // A resumed run's drapes of earlier runs are counted too, read back from
  // the finished file (the garment through itself is no statistic of the
  // file): a resume after a kill named only its own ("--drop 7" where the
  // uninterrupted run said "--drop 0,3,7"; an outside check). A few
  // milliseconds a drape.
  std::size_t checked_again = 0;
  if (plan.already > 0) {
    std::vector<char> made_now(layout.samples, 0);
    for (const std::size_t local : todo) made_now[local] = 1;
    const DatasetReader finished(out);
    const Eigen::MatrixX3i& faces = finished.layout().garment_faces;
    for (std::size_t local = 0; local < layout.samples && faces.rows() > 0; ++local) {
      if (made_now[local]) continue;
      const Tensor garment = finished.garment_vertices({local});
      ++checked_again;
      if (!geometry::self_edge_crossings(garment.mat(0).cast<double>(), faces, 1).empty())
        crossing_itself.push_back(first + local);
    }
  }
  std::sort(crossing_itself.begin(), crossing_itself.end());
  GenerateSummary summary;
  summary.checked_again = checked_again;
  summary.samples = layout.samples;
  summary.not_settled = not_settled.load();
  summary.penetrating = penetrating.load();
  summary.crossing = crossing.load();
  summary.crossing_itself = std::move(crossing_itself);
  return summary;
}

}  // namespace drape
