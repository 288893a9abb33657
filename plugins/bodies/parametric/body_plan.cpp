// Proportions are those of an adult of 1.75 m (lengths scale with height, radii
// with its square root so that a given `weight` means about the same BMI at any
// height). `weight` is a global adiposity: each girth grows as exp(rate * weight
// + own girth parameter), with rates that make trunk, hips, thighs and upper
// arms grow much more than head, hands and feet. Above the mean adiposity the
// rates change (docs/bodies.md, "Heavy bodies: where the fat goes"): a woman's
// fat goes less into the width of her hips, thighs, chest and shoulders and
// more into her buttocks, the depth of her waist and a sagging belly; for both
// sexes more goes into neck, knees, calves and ankles, which hardly grew.
// Joints move outwards with the girths around them so that arms and thighs
// never merge into the trunk or each other: the body keeps the topology of a
// sphere over the whole range.
#include "body_plan.hpp"
#include "growth.hpp"

#include <drape/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape::parametric {
namespace {

using V3 = Eigen::Vector3d;

}  // namespace

const std::vector<ShapeSpec>& shape_specs() {
  static const std::vector<ShapeSpec> specs = {
      {"height", 1.75, 1.40, 2.10, "standing height in m (mesh y extent, exact)"},
      {"sex", 0.5, 0.0, 1.0, "0 female ... 1 male"},
      {"weight", kMeanWeight, -1.0, 1.5, "global adiposity; every girth grows with it"},
      {"chest", 0.0, -0.5, 0.5, "chest girth, log factor on top of weight"},
      {"waist", 0.0, -0.5, 0.5, "waist girth, log factor"},
      {"belly", 0.0, -0.5, 0.5, "belly girth and protrusion, log factor"},
      {"hips", 0.0, -0.5, 0.5, "hip and buttock girth, log factor"},
      {"arms", 0.0, -0.5, 0.5, "upper and lower arm girth, log factor"},
      {"thighs", 0.0, -0.5, 0.5, "thigh girth, log factor"},
  };
  return specs;
}

Eigen::VectorXd mean_shape_vector() {
  Eigen::VectorXd s(kNumShape);
  for (int i = 0; i < kNumShape; ++i) s[i] = shape_specs()[static_cast<std::size_t>(i)].mean;
  return s;
}

void check_shape(const Eigen::VectorXd& shape) {
  if (shape.size() != kNumShape)
    throw ConfigError("body parametric: shape vector has " + std::to_string(shape.size()) + " entries, expected " +
                      std::to_string(kNumShape));
  for (int i = 0; i < kNumShape; ++i) {
    const ShapeSpec& s = shape_specs()[static_cast<std::size_t>(i)];
    if (!(shape[i] >= s.min && shape[i] <= s.max)) {
      std::ostringstream m;
      m.precision(10);
      m << "body parametric: shape parameter '" << s.name << "' = " << shape[i] << " is outside [" << s.min << ", "
        << s.max << "]";
      throw ConfigError(m.str());
    }
  }
}

ImplicitBody plan_body(const Eigen::VectorXd& shape, Rig rig) {
  return rig == Rig::Human ? plan_human_body(shape) : plan_mannequin_body(shape);
}

ImplicitBody plan_mannequin_body(const Eigen::VectorXd& shape) {
  const double sy = shape[kHeight] / 1.75, sr = std::sqrt(sy);
  const double m = shape[kSex], w = shape[kWeight];
  // A girth factor: exp(rate * w + girth) up to the mean adiposity (the rates
  // the body was first built with), growing at `heavy_rate` above it.
  const double excess = heavy_excess(w);
  auto grow = [&](double rate, double heavy_rate, double girth) { return growth(rate, heavy_rate, girth, w, excess); };

  ImplicitBody body;
  auto& parts = body.parts;
  auto ellipsoid = [&](V3 c, V3 s, double k) -> Primitive& { return parts.emplace_back(Primitive::ellipsoid(c, s, k)); };

  // Trunk: hips, belly, waist, chest, shoulders; x = width, z = depth. A heavy
  // woman's trunk grows in depth more than in width (belly, buttocks), and
  // belly, waist and hips also grow in height (the belly sagging) with wider
  // blends, so that it keeps one smooth profile instead of stacked rings. A heavy
  // man's trunk keeps its first rates: its hips must still hold a waistband
  // under a grown belly (tests/barrier/barrier_morph_test.cpp), which every
  // smoother or slimmer-hipped variant tried let slide off.
  const double hips_rate = lerp(0.80, 0.62, m);
  const double hips_gx = grow(hips_rate, lerp(0.30, 0.62, m), shape[kHips]);
  const double hips_gz = grow(hips_rate, lerp(0.85, 0.62, m), shape[kHips]);
  const double female = 1 - m;  // the share of the female pattern
  const V3 hips_s(lerp(0.172, 0.162, m) * sr * hips_gx, 0.125 * sy * grow(0, 0.35 * female, 0),
                  lerp(0.112, 0.104, m) * sr * hips_gz);
  ellipsoid({0, 0.93 * sy, -0.012 * sy - 0.25 * (hips_s.z() - 0.108 * sr)}, hips_s, 0);
  const double blend_g = grow(0, 0.5 * female, 0);
  const double belly_gx = grow(lerp(0.72, 0.80, m), lerp(0.55, 0.80, m), shape[kBelly]);
  const double belly_gz = grow(lerp(0.80, 0.92, m), lerp(0.75, 0.92, m), shape[kBelly]);
  const V3 belly_s(0.150 * sr * belly_gx, 0.140 * sy * grow(0, 0.2 * female, 0), 0.100 * sr * belly_gz);
  const double sag = 0.7 * (belly_s.y() - 0.140 * sy);  // most of its growth in height is downwards
  ellipsoid({0, 1.03 * sy - sag, 0.006 * sy + 0.4 * (belly_s.z() - 0.100 * sr)}, belly_s, 0.08 * blend_g);
  const double waist_gx = grow(0.72, lerp(0.60, 0.72, m), shape[kWaist]);
  const double waist_gz = grow(0.72, lerp(0.85, 0.72, m), shape[kWaist]);
  ellipsoid({0, 1.14 * sy, -0.004 * sy},
            V3(lerp(0.132, 0.142, m) * sr * waist_gx, 0.11 * sy * grow(0, 0.3 * female, 0),
               lerp(0.094, 0.098, m) * sr * waist_gz),
            0.06 * blend_g);
  // A woman's chest widens less than before: its width pushes the arms out (see
  // shoulder_x), so heavy shoulders widened as fast as the chest.
  const double chest_gx = grow(0.58, lerp(0.40, 0.58, m), shape[kChest]);
  const double chest_gz = grow(0.58, lerp(0.75, 0.58, m), shape[kChest]);
  const V3 chest_s(lerp(0.150, 0.168, m) * sr * chest_gx, 0.15 * sy, lerp(0.100, 0.110, m) * sr * chest_gz);
  ellipsoid({0, 1.28 * sy, 0}, chest_s, 0.06 * blend_g);
  const V3 shoulder_s(lerp(0.168, 0.192, m) * sr * grow(0.30, lerp(0.20, 0.30, m), 0.5 * shape[kChest]), 0.075 * sy,
                      0.085 * sr * grow(0.30, lerp(0.45, 0.30, m), 0.5 * shape[kChest]));
  ellipsoid({0, 1.395 * sy, -0.018 * sy}, shoulder_s, 0.05);
  // Breasts: fully inside the chest for sex = 1, so the part list never changes.
  // Faster growth would crease them against a heavy belly into slivers.
  const double breast_g = grow(0.58, 0.65, shape[kChest]);
  for (int side : {-1, 1}) {
    const V3 s = V3(0.058, 0.052, 0.045) * sr * breast_g;
    const double front = chest_s.z() * 0.78 + lerp(0.018, -0.05, m) * sr;
    ellipsoid({side * 0.085 * sr * chest_gx, 1.255 * sy, front}, s, 0.03);
  }

  // Neck and head (the nose marks the front, +Z). Heavy necks thicken; heads barely.
  const double neck_r = lerp(0.052, 0.060, m) * sr * grow(0.35, 0.65, 0);
  parts.push_back(Primitive::cone({0, 1.40 * sy, -0.025 * sy}, neck_r, {0, 1.56 * sy, -0.008 * sy}, neck_r * 0.92, 0.035).in(Region::Neck));
  const double head_g = grow(0.06, 0.10, 0);
  ellipsoid({0, 1.635 * sy, 0.008 * sy}, V3(0.076 * sr * head_g, 0.106 * sy, 0.096 * sr * head_g), 0.025).in(Region::Head);
  ellipsoid({0, 1.625 * sy, 0.008 * sy + 0.096 * sr * head_g}, V3(0.014, 0.024, 0.022) * sr, 0.012).in(Region::Head);

  // Arms in A-pose, about 47 degrees below horizontal (45 for heavy bodies,
  // whose arms stand further out; 50 for thin ones). Wrists and hands stay slim.
  const double arm_g = grow(0.52, lerp(0.45, 0.52, m), shape[kArms]), fore_g = grow(0.38, 0.40, 0.7 * shape[kArms]);
  const double upper_r0 = lerp(0.047, 0.053, m) * sr, upper_r = upper_r0 * arm_g;
  const double angle = std::clamp(47.0 - 3.0 * w, 45.0, 50.0) * M_PI / 180.0;
  const double shoulder_x = lerp(0.168, 0.188, m) * sr + 1.2 * std::max(0.0, upper_r - upper_r0) +
                            0.8 * std::max(0.0, chest_s.x() - lerp(0.150, 0.168, m) * sr);
  for (int side : {-1, 1}) {
    const V3 dir(side * std::cos(angle), -std::sin(angle), 0);
    const V3 shoulder(side * shoulder_x, 1.415 * sy, -0.015 * sy);
    const V3 elbow = shoulder + 0.295 * sy * dir, wrist = elbow + 0.255 * sy * dir;
    parts.push_back(Primitive::cone(shoulder, upper_r, elbow, lerp(0.036, 0.040, m) * sr * arm_g, 0.05).in(Region::UpperArm, side));
    parts.push_back(Primitive::cone(elbow, lerp(0.036, 0.040, m) * sr * fore_g, wrist,
                                    lerp(0.025, 0.028, m) * sr * grow(0.25, 0.15, 0.4 * shape[kArms]), 0.02)
                        .in(Region::Forearm, side));
    // Hand: flat side towards the thigh; axes along the arm, across (front), palm normal.
    Eigen::Matrix3d frame;
    frame.col(0) = dir;
    frame.col(1) = V3::UnitZ();
    frame.col(2) = dir.cross(V3::UnitZ());
    const double hand_g = grow(0.12, 0.12, 0);
    parts.push_back(Primitive::ellipsoid(wrist + 0.085 * sy * dir,
                                         V3(0.092 * sy, 0.046 * sr * hand_g, 0.025 * sr * hand_g), 0.018, frame)
                        .in(Region::Hand, side));
  }

  // Legs: the thighs start far enough apart that their inner sides never touch.
  // Round thighs set the hip width seen from the front, so a heavy woman's grow
  // slower than they did (the volume goes to her buttocks and belly); knees,
  // calves and ankles grow faster for both sexes.
  const double thigh_g = grow(lerp(0.80, 0.68, m), lerp(0.50, 0.68, m), shape[kThighs]);
  const double thigh_r = lerp(0.090, 0.085, m) * sr * thigh_g;
  const double knee_r = 0.052 * sr * grow(0.45, 0.55, 0.5 * shape[kThighs]);
  const double hip_x = std::max(0.085 * sr, thigh_r + 0.024 * sr);
  for (int side : {-1, 1}) {
    const V3 hip(side * hip_x, 0.90 * sy, -0.005 * sy);
    const V3 knee(side * (hip_x + 0.022 * sr), 0.49 * sy, 0.004 * sy);
    const V3 ankle(side * (hip_x + 0.030 * sr), 0.085 * sy, -0.012 * sy);
    parts.push_back(Primitive::cone(hip, thigh_r, knee, knee_r, 0.04).in(Region::Thigh, side));
    const double calf_g = grow(0.45, 0.65, 0.3 * shape[kThighs]);
    parts.push_back(Primitive::cone(knee, knee_r * 0.95, ankle, 0.032 * sr * grow(0.2, 0.55, 0), 0.02).in(Region::Shin, side));
    ellipsoid(knee + 0.33 * (ankle - knee) + V3(0, 0, -0.018 * sr), V3(0.048 * calf_g, 0.10, 0.050 * calf_g) * sr, 0.03)
        .in(Region::Calf, side);
    const double foot_g = grow(0.08, 0.12, 0);
    ellipsoid({ankle.x(), 0.040 * sy, 0.050 * sy}, V3(0.045 * sr * foot_g, 0.040 * sy, 0.128 * sy), 0.025).in(Region::Foot, side);
  }
  return body;
}

}  // namespace drape::parametric
