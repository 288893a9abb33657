// body_heading and turn_to_face (geometry/body_heading.hpp).
#include <drape/errors.hpp>
#include <drape/geometry/body_heading.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace drape {

namespace {
constexpr double kDegrees = 180.0 / std::numbers::pi;
bool turned_too(const BodyHeading& h) { return std::abs(h.turn_degrees) > kTurnToleranceDegrees; }
}

BodyHeading body_heading(const Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean) {
  // The least-squares rotation (Kabsch; Eigen's Umeyama without scaling), about both centroids.
  const Eigen::Matrix4d fit = Eigen::umeyama(mean.transpose(), body.transpose(), false);
  BodyHeading out;
  out.rotation = fit.topLeftCorner<3, 3>();
  const Eigen::Vector3d up = out.rotation.col(1);
  out.lean_degrees = std::acos(std::clamp(up.y(), -1.0, 1.0)) * kDegrees;
  // The turn about +y: where the mean body's forward (+z) goes, seen from above.
  const Eigen::Vector3d forward = out.rotation.col(2);
  out.turn_degrees = std::atan2(forward.x(), forward.z()) * kDegrees;
  return out;
}

Eigen::MatrixX3d BodyMove::placed(const Eigen::MatrixX3d& given) const {
  return (((given.rowwise() - pivot) * rotation).rowwise() + pivot).rowwise() - offset;
}

Eigen::MatrixX3d BodyMove::back(const Eigen::MatrixX3d& placed) const {
  return (((placed.rowwise() + offset).rowwise() - pivot) * rotation.transpose()).rowwise() + pivot;
}

BodyMove BodyMove::then(const BodyMove& next) const {
  // placed_next(placed(x)) = (x - pivot) R R_next + (pivot - offset - pivot_next) R_next + pivot_next - offset_next.
  BodyMove out;
  out.rotation = rotation * next.rotation;
  out.pivot = pivot;
  out.offset = pivot - (pivot - offset - next.pivot) * next.rotation - next.pivot + next.offset;
  return out;
}

std::string facing_text(double turn_degrees) {
  char line[160];
  std::snprintf(line, sizeof line, "faces %.1f degrees from the way the body model's bodies face (turned about the "
                "vertical, counter-clockwise seen from above)", turn_degrees);
  return line;
}

std::string lean_refusal(const std::string& what, double lean_degrees, const Eigen::Vector3d& up) {
  Eigen::Vector3d axis = up.cross(Eigen::Vector3d::UnitY());
  // Upside down the axis is any horizontal one: about x.
  axis = axis.norm() > 1e-9 ? axis.normalized() : Eigen::Vector3d::UnitX();
  char line[520];
  std::snprintf(line, sizeof line,
                "%s leans %.1f degrees from upright (its up axis, fitted against the body model's mean body, points "
                "(%+.2f, %+.2f, %+.2f)): drape drapes bodies standing upright, Y up, and a leaning body's drape is "
                "not its upright drape turned (gravity acts across it); stand it upright (turn it %.1f degrees about "
                "(%+.2f, %+.2f, %+.2f)), which drape does by itself up to %.0f degrees",
                what.c_str(), lean_degrees, up.x(), up.y(), up.z(), lean_degrees, axis.x(), axis.y(), axis.z(),
                kLeanLimitDegrees);
  return line;
}

BodyMove turn_to_face(Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean, const std::string& what,
                      std::string* note, bool posed) {
  BodyMove move;
  BodyHeading heading = body_heading(body, mean);
  if (posed) heading.lean_degrees = 0;  // not a lean: the limbs' pose tilts the fit
  if (heading.lean_degrees > kLeanLimitDegrees) throw ConfigError(lean_refusal(what, heading.lean_degrees, heading.rotation.col(1)));
  if (std::abs(heading.turn_degrees) <= kTurnToleranceDegrees && heading.lean_degrees <= kLeanToleranceDegrees)
    return move;
  const bool leans = heading.lean_degrees > kLeanToleranceDegrees;
  if (leans) {
    move.rotation = heading.rotation;
  } else {
    // Only turned: about the vertical alone. The fitted rotation also holds
    // the tilt by which the body's build differs from the mean body's (a few
    // hundredths of a degree), which turning back would add to the body.
    const double turn = heading.turn_degrees / kDegrees;
    move.rotation << std::cos(turn), 0, std::sin(turn), 0, 1, 0, -std::sin(turn), 0, std::cos(turn);
  }
  move.pivot = body.colwise().mean();
  body = move.placed(body);
  if (note) {
    std::string said;
    char line[300];
    if (turned_too(heading)) said = facing_text(heading.turn_degrees);
    if (leans) {
      std::snprintf(line, sizeof line, "leans %.1f degrees from upright (the garment then hangs along the body as on "
                    "the body stood upright; within %.0f degrees the two barely differ)", heading.lean_degrees,
                    kLeanLimitDegrees);
      said += (said.empty() ? "" : " and ") + std::string(line);
    }
    *note = said + (leans ? turned_too(heading) ? "; it is draped stood upright, facing as they do, and the drape moved "
                                                    "back with it"
                                                  : "; it is draped stood upright and the drape tilted back with it"
                          : "; it is draped turned to face as they do and the drape turned back with it");
  }
  return move;
}

}  // namespace drape
