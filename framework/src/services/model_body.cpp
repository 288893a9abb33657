// model_body_batch and prepare_bodies (services/model_body.hpp).
#include <drape/bodies/posed_body.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/errors.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/services/model_body.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <cstdio>
#include <limits>

namespace drape {
namespace {

// A batch of several bodies says which one a notice is about.
std::string about(const SampleBatch& batch, int i) { return batch.size() > 1 ? "body " + std::to_string(i) + ": " : ""; }

// Where a body placed by its model's anchor stands, for a placement note.
std::string anchored_where(const Model& model) {
  return model.file().filename().string() + "'s training bodies stood (where its body model makes them)";
}

// The shape is what the network knows; where the body stands and which way
// it faces are only a rigid move. Draped where, and as, the training bodies
// stood, the garment then moves back with the body: the same drape as for
// the body placed right. The turn needs only the model's mean body; the
// place, the domain's record of where the training bodies stood.
BodyMove place(const Model& model, const ModelDomain* domain, const BodyAnchor* anchor, bool posed, SampleBatch& batch,
               int i, std::vector<Notice>& notices) {
  Eigen::MatrixX3d body = batch.body.mat(i).cast<double>();
  const std::string who = batch.size() > 1 ? "body " + std::to_string(i) : "the body";
  const Eigen::Vector3d unknown = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  std::string turned;
  const BodyMove move = place_given_body(body, model.assets().body.vertices, anchor, domain ? domain->placement : unknown,
                                         domain ? domain->placement_spread : unknown, posed, who, &turned);
  if (!turned.empty()) notices.push_back({Notice::Level::note, who + " " + turned});
  if (!move.offset.isZero(0.0)) {
    char where[200];
    if (anchor)
      std::snprintf(where, sizeof where, "%s", anchored_where(model).c_str());
    else
      std::snprintf(where, sizeof where, "%s's training bodies stood (centred in x and z, soles at y = %.3f)",
                    model.file().filename().string().c_str(), domain->placement[1]);
    notices.push_back({Notice::Level::note, who + " " + placement_note(move.offset.transpose(), where)});
  }
  if (!move.is_identity()) batch.body.mat(i) = body.cast<float>();
  return move;
}

void check_domain(const Model& model, const ModelDomain& domain, const SampleBatch& batch, int i, bool strict,
                  const std::string& strict_option, std::vector<Notice>& notices) {
  const std::string name = model.file().filename().string();
  const Eigen::MatrixX3d body = batch.body.mat(i).cast<double>();
  Eigen::VectorXd params;
  if (batch.body_params.size() > 0) params = batch.body_params.mat(i).row(0).transpose().cast<double>();
  const std::vector<std::string> outside =
      domain_violations(domain, body, model.assets().body.faces, params.size() ? &params : nullptr);
  if (outside.empty()) return;
  if (strict) {
    std::string all;
    for (const std::string& why : outside) all += (all.empty() ? "" : "; ") + why;
    throw ConfigError(strict_option + ": " + about(batch, i) + "the body is outside the model's training domain (" + all + ")");
  }
  for (const std::string& why : outside)
    notices.push_back({Notice::Level::warning, about(batch, i) + "the body is outside what " + name + " was trained on: " + why});
  notices.push_back({Notice::Level::warning, about(batch, i) + "the prediction may be wrong without showing it (" +
                                                 strict_option + " refuses such a body)"});
}

void warn_posed(const Model& model, const SampleBatch& batch, int i, const std::string& turned, bool strict,
                const std::string& strict_option, std::vector<Notice>& notices) {
  const std::string text = about(batch, i) + "the body looks posed: " + turned + "; " +
                           (model.file().empty() ? std::string("this model") : model.file().filename().string()) +
                           " drapes the A-pose only, so the drape is for another body: a model of posed drapes reads the "
                           "pose off the mesh (docs/poses.md, \"A body given posed\")";
  if (strict) throw ConfigError(strict_option + ": " + text);
  notices.push_back({Notice::Level::warning, text});
}

void note_fit(const Model& model, double garment_loop, const SampleBatch& batch, int i, std::vector<Notice>& notices) {
  const double ease = garment_ease(garment_loop, batch.body.mat(i).cast<double>(), model.assets().body.faces);
  if (!(ease < kMinimumEase)) return;  // fits, or not measurable (NaN)
  char line[400];
  std::snprintf(line, sizeof line,
                "the model's garment is %.1f %% smaller around than this body's chest or belly (the tailor's "
                "rule of docs/garments.md); simulated, a garment that small rides up over the belly or is stretched "
                "onto the body, and the model predicts it so. A larger size fits (drape simulate with size: auto)",
                -100.0 * ease);
  notices.push_back({Notice::Level::note, about(batch, i) + line});
}

}  // namespace

std::optional<double> requested_garment_grade(const Model& model, const std::optional<std::string>& size,
                                              const std::optional<double>& grade) {
  if (grade && size) throw ConfigError("give the garment's size or its grade, not both");
  if (grade) {
    const double g = *grade;
    if (!(g >= kModelMinGrade && g <= kModelMaxGrade))
      throw ConfigError("garment grade " + std::to_string(g) + " is outside " + std::to_string(kModelMinGrade).substr(0, 3) +
                        "-" + std::to_string(kModelMaxGrade).substr(0, 3) + " (the garment's girth over its design size's)");
    return g;
  }
  if (!size || *size == "auto") return std::nullopt;
  const std::optional<SizeTable> chart = model_size_chart(model);
  if (!chart)
    throw ConfigError("this model records no size chart to name sizes by: give the garment's grade as a number");
  return chart->grade(*size);
}

namespace {

// The tailor's rule on body i of a batch, measured where bodies stand in a
// scene (soles at y = 0, centred in x and z): the tape follows bands at
// heights above the soles, and a body given standing elsewhere is the same body.
SizeChoice rule_for(const SizeTable& chart, const Model& model, const SampleBatch& batch, int i) {
  Eigen::MatrixX3d body = batch.body.mat(i).cast<double>();
  Eigen::RowVector3d stand = body.colwise().mean();
  stand.y() = body.col(1).minCoeff();
  body.rowwise() -= stand;
  return chart.choose(body_girth(body, model.assets().body.faces));
}

// A size chosen by the rule is a size step from the design ease at most
// (about 10 points); more than this is a body outside the chart.
constexpr double kLooseEase = 0.15;

// The size the tailor's rule gives each body of a batch that has no grade yet.
void choose_sizes_by_chart(const SizeTable& chart, const Model& model, SampleBatch& batch, bool strict,
                  const std::string& strict_option, std::vector<Notice>& notices) {
  const int n = batch.size();
  batch.garment_grade = Tensor(n, 1, 1);
  for (int i = 0; i < n; ++i) {
    SizeChoice choice = rule_for(chart, model, batch, i);
    if (choice.size.empty()) {
      const std::string why = about(batch, i) + "no size of the garment fits this body (" + choice.summary() + ")";
      if (strict) throw ConfigError(strict_option + ": " + why);
      choice.size = chart.girth.back().first;
      notices.push_back({Notice::Level::warning, why + "; predicted in the largest, " + choice.size});
    } else {
      char line[200];
      std::snprintf(line, sizeof line, "size %s by the tailor's rule (body girth %.2f m, ease %+.1f %%; --garment-size "
                                       "names another)", choice.size.c_str(), choice.body_girth, 100.0 * choice.ease(choice.size));
      notices.push_back({Notice::Level::note, about(batch, i) + line});
      // The smallest size of the chart, much looser than designed: a body
      // thinner than the chart reaches (in a chart that starts at small a
      // BMI 11 body stood at +64 % ease, a box; the 3xsmall leaves the
      // thinnest corner of the body space at +28 %).
      const double loose = choice.ease(choice.size) - choice.design_ease;
      if (choice.size == chart.girth.front().first && loose > kLooseEase) {
        std::snprintf(line, sizeof line, "%s is the smallest size %s knows, and this body is thinner than it is cut "
                                         "for: %.0f points more ease than designed (%+.1f %%), so it stands off the body",
                      choice.size.c_str(), model.file().filename().string().c_str(), 100.0 * loose,
                      100.0 * choice.design_ease);
        notices.push_back({Notice::Level::note, about(batch, i) + line});
      }
    }
    batch.garment_grade(i, 0, 0) = static_cast<float>(chart.grade(choice.size));
  }
}

// A mesh of the right vertex count whose faces join other vertices than the
// model's body does: its vertices are in another order (a tool that
// re-indexed them, another mesh of the same size), and every vertex would be
// read as another part of the body. A tool may split quads the other way, so
// nine in ten of its edges being the model's is enough.
// The other diagonal of each pair of the model's triangles that share an
// edge (the edge a quad split the other way has), sorted and unique.
std::vector<std::array<int, 2>> flipped_diagonals(const Eigen::MatrixX3i& faces) {
  std::vector<std::array<int, 3>> sides;  // (edge's lower end, its upper end, the corner opposite it)
  sides.reserve(static_cast<std::size_t>(3 * faces.rows()));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      sides.push_back({std::min(a, b), std::max(a, b), faces(f, (k + 2) % 3)});
    }
  std::sort(sides.begin(), sides.end());
  std::vector<std::array<int, 2>> out;
  for (std::size_t i = 0; i + 1 < sides.size(); ++i)
    if (sides[i][0] == sides[i + 1][0] && sides[i][1] == sides[i + 1][1] && sides[i][2] != sides[i + 1][2])
      out.push_back({std::min(sides[i][2], sides[i + 1][2]), std::max(sides[i][2], sides[i + 1][2])});
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void require_model_topology(const Eigen::MatrixX3i& faces, const Eigen::MatrixX3i& model_faces, const std::string& what) {
  // (edge_list gives each mesh's edges sorted and unique.)
  const std::vector<std::array<int, 2>> model_edges = geometry::edge_list(model_faces);
  const std::vector<std::array<int, 2>> edges = geometry::edge_list(faces);
  std::vector<std::array<int, 2>> common;
  std::set_intersection(edges.begin(), edges.end(), model_edges.begin(), model_edges.end(), std::back_inserter(common));
  std::size_t shared = common.size();
  // A quad mesh of the model's vertices (its triangles' pairs joined), split
  // into triangles by the reader, has a diagonal of each quad the model may
  // not have: a whole quad mesh shared 66 % of its edges and was refused (an
  // outside check). Such diagonals count as the model's; a mesh of other
  // vertex order meets them as rarely as the model's own edges.
  if (static_cast<double>(shared) < 0.9 * static_cast<double>(edges.size())) {
    std::vector<std::array<int, 2>> rest, flips;
    std::set_difference(edges.begin(), edges.end(), common.begin(), common.end(), std::back_inserter(rest));
    const std::vector<std::array<int, 2>> diagonals = flipped_diagonals(model_faces);
    std::set_intersection(rest.begin(), rest.end(), diagonals.begin(), diagonals.end(), std::back_inserter(flips));
    shared += flips.size();
  }
  const double share = edges.empty() ? 0.0 : static_cast<double>(shared) / static_cast<double>(edges.size());
  if (share < 0.9)
    throw ConfigError(what + ": its faces are not the body model's: " + std::to_string(static_cast<int>(100 * share)) +
                      " % of its edges join vertices the model's body joins (or a quad of its triangles does): its vertices "
                      "are in another order, or it is another mesh; give a mesh in the model's vertex order (drape body --out writes one)");
}

// A body whose vertices are in another order than the model's, read through
// the model's faces, has edges that jump across the body: two vertices
// swapped (the 9-in-10 edge rule above lets a pair pass, and a file of
// points has no faces to test) put a spike where each went, a shuffled file
// a tangle of edges a metre long. The model's own bodies stretch an edge of
// the mean body by at most 4.7 times: measured over 300 bodies of the human
// rig of BMI 10-65 and height 1.4-2.1 m, half of them posed (2.7-2.8 times
// for the median body). Two vertices swapped within a few of the mesh's
// rings stay under the limit, and change the drape as little.
constexpr double kLongestEdgeStretch = 10.0;

void require_model_vertex_order(const Eigen::MatrixX3d& vertices, const ModelBodyEdges& mean, const std::string& what) {
  // (Squared lengths against the squared limit: no root or division per
  // edge, as the Python module checks every body of every call.)
  const double limit2 = kLongestEdgeStretch * kLongestEdgeStretch;
  bool any = false;
  for (std::size_t e = 0; e < mean.edges.size() && !any; ++e) {
    const auto [a, b] = mean.edges[e];
    any = (vertices.row(a) - vertices.row(b)).squaredNorm() > limit2 * mean.lengths[e] * mean.lengths[e];
  }
  if (!any) return;
  double worst = 0;
  std::size_t at = 0;
  for (std::size_t e = 0; e < mean.edges.size(); ++e) {
    const auto [a, b] = mean.edges[e];
    const double stretch = (vertices.row(a) - vertices.row(b)).norm() / mean.lengths[e];
    if (stretch > worst) worst = stretch, at = e;
  }
  const auto [a, b] = mean.edges[at];
  char line[480];
  std::snprintf(line, sizeof line,
                "%s: its vertices are not in the body model's order: read through the model's faces, the edge "
                "between vertices %d and %d is %.2f m long, %.0f times the model's mean body's (more than %.0f; the "
                "bodies of its shape and pose space stretch an edge under 5 times): vertices swapped or re-indexed, "
                "vertices moved far from their neighbours (noise, a scan's), or another mesh; give a mesh in the model's vertex order (drape body --out writes one)",
                what.c_str(), a, b, (vertices.row(a) - vertices.row(b)).norm(), worst, kLongestEdgeStretch);
  throw ConfigError(line);
}

}  // namespace

ModelBodyEdges model_body_edges(const Model& model) {
  return model_body_edges(model.assets().body.vertices, model.assets().body.faces);
}

ModelBodyEdges model_body_edges(const Eigen::MatrixX3d& mean, const Eigen::MatrixX3i& model_faces) {
  ModelBodyEdges out;
  for (const auto& edge : geometry::edge_list(model_faces)) {
    const double length = (mean.row(edge[0]) - mean.row(edge[1])).norm();
    if (length > 0) out.edges.push_back(edge), out.lengths.push_back(length);  // (a stretch of nothing measures nothing)
  }
  return out;
}

namespace {

void require_outward(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& model_faces, const std::string& what) {
  if (geometry::mesh_volume(vertices, model_faces) < 0)
    throw ConfigError(what + ": its surface, taken with the model's faces, turns inwards (negative "
                      "volume): the body is mirrored or inside out; give it as the body model makes it");
}

}  // namespace

void require_model_body_vertices(const Eigen::MatrixX3d& vertices, const Model& model, const std::string& what,
                                 const ModelBodyEdges* edges) {
  if (edges) require_model_vertex_order(vertices, *edges, what);
  else require_model_vertex_order(vertices, model_body_edges(model), what);
  require_outward(vertices, model.assets().body.faces, what);
}

void require_body_model_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i* faces, const Eigen::MatrixX3d& mean,
                             const Eigen::MatrixX3i& model_faces, const std::string& what) {
  if (faces && faces->rows() > 0) require_model_topology(*faces, model_faces, what);
  require_model_vertex_order(vertices, model_body_edges(mean, model_faces), what);
  require_outward(vertices, model_faces, what);
}

SampleBatch model_body_batch(const Model& model, const ModelBodyInput& input) {
  if (input.vertices.has_value() == input.request.has_value())
    throw ConfigError("a body: give either its vertices or a request for the model's body plugin");
  SampleBatch batch;
  if (input.vertices) {
    Mesh given;
    given.vertices = *input.vertices;
    require_vertex_count(given, model.assets().body.num_vertices(), input.name,
                         "the model's body model '" + model.assets_spec().body_model + "' has that many");
    if (input.faces && input.faces->rows() > 0)
      require_model_topology(*input.faces, model.assets().body.faces, "body " + input.name);
    check_body_units(given.vertices, "body " + input.name);
    require_model_body_vertices(given.vertices, model, "body " + input.name);
    if (model.needs_body_params())
      throw ConfigError("this model's graph takes the body parameters (input body_params), which a mesh does not "
                        "give: use --bmi");
    batch.body = Tensor(1, given.num_vertices(), 3);
    batch.body.mat(0) = given.vertices.cast<float>();
  } else {
    batch = model.body_for(*input.request);
  }
  // A model trained on several garment sizes takes the size as an input (garment_size_flag).
  if (model.needs_input("garment_size")) {
    if (!input.garment_size)
      throw ConfigError("this model was trained on several garment sizes (input garment_size): give --garment-size, one of " +
                        garment_size_choices());
    batch.garment_size = Tensor(1, 1, 1);
    batch.garment_size(0, 0, 0) = garment_size_flag(*input.garment_size);
  }
  if (model.needs_input("garment_grade")) {
    const std::optional<double> grade = requested_garment_grade(model, input.garment_size, input.garment_grade);
    if (grade) batch.garment_grade = Tensor(1, 1, 1, static_cast<float>(*grade));  // else prepare() chooses
  } else if (input.garment_grade || (input.garment_size && !model.needs_input("garment_size"))) {
    throw ConfigError("this model was trained on one garment size and takes none; leave the garment size out");
  }
  return batch;
}

bool model_takes_pose(const Model& model) {
  return reads_pose(model.graph().input_names());
}

void pose_model_batch(const Model& model, SampleBatch& batch, const Pose& pose) {
  pose_model_batch(model, batch, std::vector<Pose>(static_cast<std::size_t>(batch.size()), pose));
}

void pose_model_batch(const Model& model, SampleBatch& batch, const std::vector<Pose>& poses) {
  if (poses.size() != static_cast<std::size_t>(batch.size()))
    throw Error("pose_model_batch: " + std::to_string(poses.size()) + " poses for " + std::to_string(batch.size()) + " bodies");
  if (!model_takes_pose(model)) {
    if (std::all_of(poses.begin(), poses.end(), [](const Pose& p) { return p.empty(); })) return;
    throw ConfigError("this model drapes bodies in the A-pose only (its graph takes no pose): a posed body would get a "
                      "wrong drape; use a model trained on posed drapes (docs/poses.md), or drape simulate --pose");
  }
  const BodyModel& body_model = model.body_model();
  for (const Pose& pose : poses) check_pose(pose, body_model.pose_angles(), "pose");
  const int n = batch.size();
  SampleBatch posed;
  for (int i = 0; i < n; ++i) {
    const SampleBatch one = posed_body_batch(body_model, batch.body.mat(i).cast<double>(), poses[static_cast<std::size_t>(i)]);
    if (i == 0) {
      posed.body = Tensor(n, one.body.rows(), 3);
      posed.unposed_body = Tensor(n, one.unposed_body.rows(), 3);
      posed.joint_transforms = Tensor(n, one.joint_transforms.rows(), 12);
      posed.pose = Tensor(n, 1, one.pose.cols());
    }
    posed.body.mat(i) = one.body.mat(0);
    posed.unposed_body.mat(i) = one.unposed_body.mat(0);
    posed.joint_transforms.mat(i) = one.joint_transforms.mat(0);
    posed.pose.mat(i) = one.pose.mat(0);
  }
  batch.body = std::move(posed.body);
  batch.unposed_body = std::move(posed.unposed_body);
  batch.joint_transforms = std::move(posed.joint_transforms);
  batch.pose = std::move(posed.pose);
}

// A body mesh given posed: its pose read off it, the mesh unposed and placed
// (unpose_given_body, given_body.hpp); the notes of where it stood and of the
// pose read.
BodyMove BodyPreparation::unpose_given(SampleBatch& batch, int i, Pose& pose, bool& at_rest, bool pose_given,
                                       std::vector<Notice>& notices) const {
  const std::string who = batch.size() > 1 ? "body " + std::to_string(i) : "the body";
  const Eigen::Vector3d unknown = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::MatrixX3d body = batch.body.mat(i).cast<double>();
  const GivenPosedBody given = unpose_given_body(body, model_.body_model(), model_.assets().body.vertices, &given_.anchor(),
                                                 domain_ ? domain_->placement : unknown,
                                                 domain_ ? domain_->placement_spread : unknown, who);
  if (!given.outside.empty()) throw ConfigError(given.outside);  // (its lean and pose are misread too)
  if (!given.leaning.empty()) throw ConfigError(given.leaning);  // draped upright and turned back, it would hang across gravity
  batch.body.mat(i) = body.cast<float>();
  pose = given.fit.pose;
  at_rest = given.at_rest;
  if (!given.turned.empty())
    notices.push_back({Notice::Level::note, who + " " + given.turned});
  else if (given.moved.offset.norm() > kPosedPlacementTolerance)
    notices.push_back({Notice::Level::note, who + " " + placement_note(given.moved.offset.transpose(), anchored_where(model_))});
  // (A mesh at rest given with a pose is the documented call: Python turned
  // this note into a DrapeWarning on every such predict.)
  if (!(pose_given && at_rest)) notices.push_back({Notice::Level::note, about(batch, i) + given.pose_note});
  if (!given.warning.empty()) notices.push_back({Notice::Level::warning, about(batch, i) + given.warning});
  return given.moved;
}

std::vector<Notice> BodyPreparation::pose(SampleBatch& batch, const Pose& pose, bool strict,
                                          const std::string& strict_option, const PreparedBodies* prepared,
                                          bool check, bool refuse_crossing) const {
  std::vector<Pose> poses(static_cast<std::size_t>(batch.size()), pose);
  if (prepared)
    for (std::size_t i = 0; i < prepared->given_poses.size() && i < poses.size(); ++i) {
      if (prepared->given_poses[i].empty()) continue;
      // A mesh read at rest given with a pose: the pose given (on the mesh unposed).
      if (!pose.empty() && i < prepared->given_at_rest.size() && prepared->given_at_rest[i]) continue;
      if (!pose.empty())
        throw ConfigError(about(batch, static_cast<int>(i)) + "the body mesh is given posed and a pose is given too: give "
                          "the posed mesh alone (its pose is read off it), or the body at rest with the pose");
      poses[i] = prepared->given_poses[i];
    }
  pose_model_batch(model_, batch, poses);
  if (!model_takes_pose(model_)) return {};
  std::vector<Notice> notices;
  if (domain_ && !domain_->pose_names.empty()) {
    const std::vector<PoseAngle> angles = model_.body_model().pose_angles();
    for (int i = 0; i < batch.size(); ++i) {
      const Pose full = batch_pose(batch, i, angles);  // the angles the body is draped in, those at rest included
      std::string lines;
      for (const std::string& v : pose_violations(*domain_, full)) lines += (lines.empty() ? "" : "; ") + v;
      if (lines.empty()) continue;
      const std::string text = "the pose lies outside the model's training poses: " + lines;
      if (strict) throw ConfigError(strict_option + ": " + text);
      notices.push_back({Notice::Level::warning, text + " (the drape there is a guess; drape simulate --pose makes it)"});
    }
  }
  // A pose in which the body passes through itself (heavy arms hanging into
  // the trunk) has no drape there: drape body and simulate refuse it; the
  // network still answers, so predict warns, naming the bones and angles,
  // and --strict refuses (a crossing the body has at rest is not the pose's).
  // A body given posed is tested as it is given, against its own mesh
  // unposed: a user's mesh with the thighs through each other was draped
  // without a word, where the pose read off it was refused by drape body
  // (an outside check).
  for (int i = 0; check && i < batch.size(); ++i) {
    const auto u = static_cast<std::size_t>(i);
    const Pose& asked = poses[u];
    // Said of the mesh when its pose was read off it; of the pose when one
    // was given (with --bmi, or with a mesh read at rest: a BMI 60 body given
    // as a mesh with shoulder_abduction=25 once passed --strict unchecked).
    const bool read_off_mesh = prepared && u < prepared->given_poses.size() && !prepared->given_poses[u].empty() &&
                               !(!pose.empty() && u < prepared->given_at_rest.size() && prepared->given_at_rest[u]);
    if (asked.empty()) continue;
    const Eigen::MatrixX3d unposed = batch.unposed_body.mat(i).cast<double>(), posed = batch.body.mat(i).cast<double>();
    const std::string crossed = describe_pose_crossings(model_.body_model(), unposed, asked, posed);
    if (crossed.empty()) continue;
    const std::string text = about(batch, i) + (read_off_mesh ? "the body mesh given passes through itself: "
                                                              : "this pose makes the body pass through itself: ") +
                             crossed;
    if (refuse_crossing)
      throw ConfigError(text + "; the contact cannot keep the cloth off a body with no inside, so it is not optimised "
                               "(drape body and simulate refuse this pose too)");
    if (strict) throw ConfigError(strict_option + ": " + text);
    notices.push_back({Notice::Level::warning, text + " (the drape there is for a body with no inside; drape body and "
                                                      "simulate refuse this pose)"});
  }
  return notices;
}

std::optional<SizeTable> model_size_chart(const Model& model) {
  const auto& meta = model.checkpoint().meta;
  const auto chart = meta.find("size_chart");
  if (chart == meta.end()) return std::nullopt;
  return SizeTable::parse(chart->second, model.file().filename().string() + "'s size_chart");
}

namespace {

// A size (or grade) the user named, on body i. A model of sizes learnt each
// body in the size the tailor's rule gives it and in the design size (the
// datasets: docs/garments.md, "A model that knows the sizes"); another size
// on this body is outside what it was trained on, as a body outside its
// domain is (a 3xsmall asked for on a BMI 40 body came out 19 % inside the
// body, without a word). A garment smaller around than the body is noted as
// for a one-size model.
void check_requested_size(const SizeTable& chart, const Model& model, const SampleBatch& batch, int i, bool strict,
                          const std::string& strict_option, std::vector<Notice>& notices) {
  const double grade = batch.garment_grade(batch.garment_grade.batch() == 1 ? 0 : i, 0, 0);
  const SizeChoice rule = rule_for(chart, model, batch, i);
  auto same = [](double a, double b) { return std::abs(a - b) < 1e-3; };  // grades 0.1 apart, stored as floats
  if (!rule.size.empty() && same(grade, chart.grade(rule.size))) return;
  std::string named;
  for (const auto& [size, girth] : chart.girth)
    if (same(grade, chart.grade(size))) named = size;
  char what[80];
  if (named.empty())
    std::snprintf(what, sizeof what, "grade %.3f", grade);
  else
    std::snprintf(what, sizeof what, "%s (grade %.3f)", named.c_str(), grade);
  const double ease = grade * rule.garment_girth(chart.design) / rule.body_girth - 1.0;
  if (!same(grade, 1.0)) {
    char line[600];
    std::snprintf(line, sizeof line,
                  "%s is not a size %s learnt on this body: it learnt each body in the size the tailor's rule gives "
                  "it (here %s, ease %+.1f %%) and in the %s; its ease here is %+.1f %%, and the prediction may be "
                  "wrong without showing it",
                  what, model.file().filename().string().c_str(), rule.size.empty() ? "none fits" : rule.size.c_str(),
                  rule.size.empty() ? 0.0 : 100.0 * rule.ease(rule.size), chart.design.c_str(), 100.0 * ease);
    if (strict) throw ConfigError(strict_option + ": " + about(batch, i) + line);
    notices.push_back({Notice::Level::warning, about(batch, i) + line + " (" + strict_option + " refuses it)"});
    return;
  }
  if (ease < kMinimumEase) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "in %s the garment is %.1f %% smaller around than this body's chest or belly (the tailor's rule "
                  "of docs/garments.md gives it %s); simulated, a garment that small rides up over the belly or is "
                  "stretched onto the body, and the model predicts it so",
                  what, -100.0 * ease, rule.size.empty() ? "no size" : rule.size.c_str());
    notices.push_back({Notice::Level::note, about(batch, i) + line});
  }
}

}  // namespace

BodyPreparation::BodyPreparation(const Model& model, std::optional<ModelDomain> domain)
    : model_(model), domain_(std::move(domain)), garment_loop_(std::numeric_limits<double>::quiet_NaN()),
      given_(model.body_model()) {
  if (model.needs_input("garment_grade")) size_chart_ = model_size_chart(model);
  // A model of several sizes takes the size from its user or chooses it: no fit to note.
  if (!model.needs_input("garment_size") && !model.needs_input("garment_grade")) {
    const Assets& a = model.assets();
    garment_loop_ = garment_girth(a.garment->mesh.vertices, a.garment->mesh.faces, a.body.vertices);
  }
}

void BodyPreparation::choose_sizes(SampleBatch& batch, bool strict, const std::string& strict_option,
                                   std::vector<Notice>& notices) const {
  if (!model_.needs_input("garment_grade") || !batch.garment_grade.empty()) return;
  if (!size_chart_)
    throw ConfigError("this model takes the garment's grade and records no size chart to choose one by: give the grade "
                      "(drape predict --garment-grade 1.2, in Python predict(..., garment_size=1.2); 1 is the garment as designed)");
  choose_sizes_by_chart(*size_chart_, model_, batch, strict, strict_option, notices);
}

std::vector<Notice> BodyPreparation::choose_sizes(SampleBatch& batch) const {
  std::vector<Notice> notices;
  choose_sizes(batch, false, "", notices);
  return notices;
}

double BodyPreparation::most_turned(const SampleBatch& batch, int i) const {
  double most = 0;
  for (const LimbTurn& t : given_.limbs().turns(model_.assets().body.vertices, batch.body.mat(i).cast<double>()))
    most = std::max(most, t.degrees);
  return most;
}

PreparedBodies BodyPreparation::prepare(SampleBatch& batch, bool strict, const std::string& strict_option,
                                        bool measure, bool given_meshes, bool pose_given) const {
  PreparedBodies out;
  out.moved_by.assign(static_cast<std::size_t>(batch.size()), BodyMove{});
  // A grade already in the batch was asked for (choose_sizes fills the others by the rule).
  const bool size_asked_for = size_chart_ && !batch.garment_grade.empty();
  out.given_poses.assign(static_cast<std::size_t>(batch.size()), Pose{});
  out.given_at_rest.assign(static_cast<std::size_t>(batch.size()), 0);
  if (measure && !domain_ && !model_.file().empty()) {  // an untrained model in memory has no file to record one in
    const std::string name = model_.file().filename().string();
    if (strict)
      throw ConfigError(strict_option + ": " + model_.file().string() + " records no training domain to check the body against");
    out.notices.push_back({Notice::Level::note, name + " records no training domain, so a body outside it cannot be "
                                                       "told (drape model domain adds it)"});
  }
  // A body given posed to a model of posed drapes is unposed (and placed)
  // first: the size is chosen, and the domain checked, on the body at rest
  // (a raised arm is no girth).
  // The others are placed (turned to face, stood upright, moved) before
  // anything is measured too: a body upside down is refused as leaning, not
  // as having no torso to measure.
  std::vector<std::string> posed(static_cast<std::size_t>(batch.size()));
  for (int i = 0; i < batch.size(); ++i) {
    const auto at = static_cast<std::size_t>(i);
    // A model of posed drapes reads the pose off every mesh given: a pose
    // too mild for the limbs' turns to tell from a build (a spine bent 10
    // degrees, the knees 10: turns of 10 degrees, as a thin body's thighs
    // have at rest) was draped as if at rest, 15 mm from its drape on
    // average (its pose read costs about a second). With a pose given, only
    // a mesh whose bones turn past kMildLimbDegrees is read (a posed one is
    // refused in pose(): two poses for one body).
    if (given_meshes && model_takes_pose(model_) && (!pose_given || most_turned(batch, i) > kMildLimbDegrees)) {
      bool at_rest = false;
      out.moved_by[at] = unpose_given(batch, i, out.given_poses[at], at_rest, pose_given, out.notices);
      out.given_at_rest[at] = at_rest;
      continue;
    }
    // A body given as a mesh is taken at rest (the A-pose); one given posed
    // gets a drape for another body: told (posed_in_words), and --strict refuses it.
    // (Without measure, the limbs' turns alone: a mild pose's read is a fit of about a second.)
    if (given_meshes) posed[at] = posed_in_words(batch.body.mat(i).cast<double>(), model_.body_model(), given_, measure);
    if (!posed[at].empty()) warn_posed(model_, batch, i, posed[at], strict, strict_option, out.notices);
    out.moved_by[at] = place(model_, domain_ ? &*domain_ : nullptr, given_meshes ? &given_.anchor() : nullptr,
                             !posed[at].empty(), batch, i, out.notices);
  }
  choose_sizes(batch, strict, strict_option, out.notices);
  for (int i = 0; i < batch.size(); ++i) {
    if (domain_ && measure) check_domain(model_, *domain_, batch, i, strict, strict_option, out.notices);
    if (measure && std::isfinite(garment_loop_)) note_fit(model_, garment_loop_, batch, i, out.notices);
    if (measure && size_asked_for) check_requested_size(*size_chart_, model_, batch, i, strict, strict_option, out.notices);
  }
  return out;
}

}  // namespace drape
