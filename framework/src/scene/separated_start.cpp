// The start-state check of a barrier contact run (separated_start.hpp).
#include "separated_start.hpp"

#include <drape/errors.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/geometry/winding.hpp>

#include "garment_region.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numbers>

namespace drape::scene_detail {

namespace {
// How far (m) a start body may be shrunk along its normals, tried in turn.
constexpr std::array<double, 7> kShrinkDepths{0.0, 0.005, 0.01, 0.02, 0.03, 0.04, 0.06};
// m: clear_offset_hint counts each garment vertex's distance from the body up to this.
constexpr double kFarEnough = 0.10;
constexpr double kInsideWeight = 10.0;
// clear_offset_hint names an offset only where the garment lies at most this share as far from the body.
constexpr double kCloserShare = 0.5;

// Whether a body's winding number tells inside from outside: it needs a
// closed, consistently oriented surface (every shipped body model's). The
// faces decide, so a body and its shrunk copies share the answer.
bool encloses(const Eigen::MatrixX3i& faces, Eigen::Index num_vertices) {
  const geometry::TopologyReport topology = geometry::check_topology(faces, static_cast<int>(num_vertices));
  return topology.watertight() && topology.oriented();
}

// separation_problem, told whether the body encloses (encloses()).
std::string problem_with(const Eigen::MatrixX3d& x, const geometry::BodySurface& body, const Eigen::MatrixX3i& garment_faces,
                         bool closed) {
  // Inside by the winding number, not by the sign of the distance: a body
  // shrunk along its normals turns thin parts inside out, and there the
  // closest face's pseudo-normal points the wrong way (5-10 cm "inside" for
  // points the shrunk body does not enclose; drape/geometry/winding.hpp). On a
  // body mesh with holes the sign decides.
  std::vector<int> inside;
  Eigen::VectorXd d;
  if (closed) {
    const std::vector<int> winding = geometry::winding_numbers(x, body.vertices(), body.faces());
    for (std::size_t v = 0; v < winding.size(); ++v)
      if (winding[v] != 0) inside.push_back(static_cast<int>(v));
  } else {
    d = body.signed_distances(x);
    for (Eigen::Index v = 0; v < d.size(); ++v)
      if (!(d[v] > 0)) inside.push_back(static_cast<int>(v));
  }
  if (!inside.empty()) {
    if (d.size() == 0) d = body.signed_distances(x);  // for the message only
    double deepest = 0;
    for (int v : inside) deepest = std::max(deepest, std::abs(d[v]));
    return "the garment starts inside the body (" + describe_region(x, inside) + ", deepest " +
           std::to_string(deepest * 100) + " cm)";
  }
  const geometry::SurfaceCrossings crossings = geometry::surface_crossings(x, garment_faces, body.vertices(), body.faces());
  if (crossings.total() > 0)
    return "the garment starts crossing the body surface (" + std::to_string(crossings.garment_edges_through_body) +
           " garment edges through body faces, " + std::to_string(crossings.body_edges_through_garment) +
           " body edges through garment faces; " + describe_region(x, crossings.garment_vertices) + ")";
  return "";
}
}  // namespace

std::string separation_problem(const Eigen::MatrixX3d& x, const geometry::BodySurface& body,
                               const Eigen::MatrixX3i& garment_faces) {
  return problem_with(x, body, garment_faces, encloses(body.faces(), body.vertices().rows()));
}

void check_separated_start(const Eigen::MatrixX3d& x, const geometry::BodySurface& body, const Eigen::MatrixX3i& garment_faces,
                           bool morphs) {
  const std::string problem = separation_problem(x, body, garment_faces);
  const std::string shrink = std::to_string(static_cast<int>(100 * kShrinkDepths.back()));
  if (!problem.empty())
    throw ConfigError("simulate: " + problem + "; the barrier contact keeps surfaces apart but cannot pull them apart (" +
                      (morphs ? "a start body shrunk by up to " + shrink + " cm was tried too"
                              : "the scene's solver has morph_steps: 0, so the garment must start clear of the body "
                                "itself; a scene that morphs tries a start body shrunk by up to " + shrink + " cm") +
                      "): start from a garment clear of the body, or use the penalty contact (effect `collision`) for "
                      "this start");
}

Eigen::MatrixX3d separated_start_body(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body,
                                      const Eigen::MatrixX3i& body_faces, const Eigen::MatrixX3i& garment_faces,
                                      double* shrink) {
  const geometry::BodySurface original(body, body_faces);
  const bool closed = encloses(body_faces, body.rows());  // once: the shrunk bodies have the same faces
  for (double depth : kShrinkDepths) {
    Eigen::MatrixX3d shrunk = body - depth * original.vertex_normals();
    if (!problem_with(x, geometry::BodySurface(shrunk, body_faces), garment_faces, closed).empty()) continue;
    if (shrink) *shrink = depth;
    return shrunk;
  }
  check_separated_start(x, original, garment_faces);  // throws, naming the region
  return body;
}

std::string clear_offset_hint(const Garment& garment, const Eigen::MatrixX3d& undressed, const Eigen::MatrixX3d& body,
                              const Eigen::MatrixX3i& body_faces) {
  const geometry::BodySurface surface(body, body_faces);
  // How far the garment lies from the body, translated by t: the mean
  // distance of its vertices outside, each counted up to 10 cm (a sleeve
  // hanging off an arm does not outweigh the torso), and of those inside
  // kInsideWeight times (a shirt moved down onto its shoulders' seams is no
  // closer). A garment modelled around the body lies closest to it where it
  // was modelled.
  const auto apart_of = [&](const Eigen::MatrixX3d& points, const Eigen::RowVector3d& t) {
    const Eigen::VectorXd d = surface.signed_distances(points.rowwise() + t);
    return d.unaryExpr([](double s) { return s < 0 ? -kInsideWeight * s : std::min(s, kFarEnough); }).mean();
  };
  // Up and down only, 1 cm steps to 45 cm each way: a garment modelled for
  // a taller or shorter body, or with its floor elsewhere, is off along y.
  // (A grid over every axis found a place around the right arm for a shirt
  // moved 8-10 cm forward or aside, which the measure below prefers to the
  // torso: an outside check's finding; such moves get no hint.)
  Eigen::RowVector3d best = Eigen::RowVector3d::Zero();
  const double at_start = apart_of(undressed, best);
  double best_apart = at_start;
  for (int cm = -45; cm <= 45; ++cm) {
    const Eigen::RowVector3d t(0.0, 0.01 * cm, 0.0);
    if (const double a = apart_of(undressed, t); a < best_apart) best_apart = a, best = t;
  }
  // Said only when the garment so placed, dressed as a run's start is,
  // starts clear of the body (or of it shrunk, as a run may start).
  const auto starts_clear = [&](const Eigen::MatrixX3d& placed) {
    Garment moved = garment;
    moved.mesh.vertices = placed;
    if (placed_through(dress(moved, Mesh{body, body_faces, {}, {}}))) return false;
    try {
      separated_start_body(moved.mesh.vertices, body, body_faces, garment.mesh.faces);
    } catch (const ConfigError&) {
      return false;
    }
    return true;
  };
  const std::string modelled = "A garment is modelled around the scene body model's mean body, in metres, Y up, facing +Z "
                               "(docs/garments.md, \"`mesh`: your own garment from a file\")";
  // Said only where the garment lies much closer around the body there, and
  // not where it was modelled (displacement is not what keeps it from starting).
  if (best_apart < kCloserShare * at_start && best.norm() >= 0.015 && starts_clear(undressed.rowwise() + best)) {
    const long cm = std::lround(100 * best[1]);
    const std::string where = std::to_string(std::labs(cm)) + (cm > 0 ? " cm up" : " cm down");
    return "moved about " + where + ", the garment would lie closest around the body and start clear of it: is it "
           "placed for another body or origin? " + modelled;
  }
  // Turned: about each axis through its centroid, 5 to 45 degrees each way
  // (an outside check's shirt tilted 20 degrees about x or z, or turned 30
  // about y, was refused as crossing the body with no word of its turn).
  const Eigen::RowVector3d centre = undressed.colwise().mean();
  const auto turned = [&](int axis, int degrees) -> Eigen::MatrixX3d {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    return ((undressed.rowwise() - centre) * turn.transpose()).rowwise() + centre;
  };
  double turned_apart = at_start;
  int best_axis = -1, best_degrees = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int degrees = -45; degrees <= 45; degrees += 5)
      if (const double a = degrees == 0 ? at_start : apart_of(turned(axis, degrees), Eigen::RowVector3d::Zero()); a < turned_apart)
        turned_apart = a, best_axis = axis, best_degrees = degrees;
  if (best_axis < 0 || !(turned_apart < kCloserShare * at_start) || !starts_clear(turned(best_axis, best_degrees))) return "";
  static const char* const axes[] = {"x (the body's left-right axis: tipped forward or back)",
                                     "y (the vertical: facing elsewhere)", "z (the body's front-back axis: leaning sideways)"};
  return "turned about " + std::to_string(std::abs(best_degrees)) + " degrees " +
         (best_degrees > 0 ? "counter-clockwise" : "clockwise") + " about " + axes[best_axis] +
         " through its centre (seen from the axis' positive end), the garment would lie closest around the body and "
         "start clear of it: is it turned? " + modelled;
}

}  // namespace drape::scene_detail
