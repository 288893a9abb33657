// The human rig (issue 54): the mannequin's trunk, limbs and fat distribution
// (body_plan.cpp) with the forms that made it read as a mannequin replaced or
// added, in proportions of adult anthropometry (docs/bodies.md, "The human
// rig"): a cranium, a narrower face, jaw, nose and ears instead of an egg;
// shoulders that slope from the neck to a rounded deltoid instead of a notch
// where a stick arm meets a bowl; forearms that taper from the elbow to the
// wrist; a palm, fingers and a thumb instead of a paddle; a heel, an
// instep and toes instead of a disc; buttocks; breasts blended into the chest.
// Every added part keeps the rule of the rig: the same parts in the same order
// for every shape, so that the template's vertices can be carried part to part.
#include "body_plan.hpp"
#include "growth.hpp"

#include <drape/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::parametric {
namespace {

using V3 = Eigen::Vector3d;

// The mannequin's n-th part of a region and side (its order in body_plan.cpp).
Primitive& part_of(ImplicitBody& body, Region region, int side, int nth = 0) {
  for (Primitive& p : body.parts)
    if (p.region == region && p.side == side && nth-- == 0) return p;
  throw Error("body parametric: the mannequin rig lacks a part the human rig builds on");
}

// An orthonormal frame whose first column is `along` and second is as close to
// `towards` as it can be: ellipsoids laid along a limb.
Eigen::Matrix3d frame_along(const V3& along, const V3& towards) {
  Eigen::Matrix3d f;
  f.col(0) = along.normalized();
  f.col(1) = (towards - towards.dot(f.col(0)) * f.col(0)).normalized();
  f.col(2) = f.col(0).cross(f.col(1));
  return f;
}

// The same part moved by d (its bounds made again by its factory).
Primitive moved(const Primitive& p, const V3& d) {
  Primitive q = p.kind == Primitive::Kind::Cone ? Primitive::cone(p.a + d, p.ra, p.b + d, p.rb, p.blend)
                                                : Primitive::ellipsoid(p.a + d, p.semi, p.blend, p.frame);
  q.carries = p.carries;
  return q.in(p.region, p.side);
}

// Where the mannequin puts the left shoulder joint (x) for this shape.
double mannequin_shoulder_x(const Eigen::VectorXd& shape) {
  ImplicitBody body = plan_mannequin_body(shape);
  return part_of(body, Region::UpperArm, 1).a.x();
}

}  // namespace

ImplicitBody plan_human_body(const Eigen::VectorXd& shape) {
  ImplicitBody body = plan_mannequin_body(shape);
  const double sy = shape[kHeight] / 1.75, sr = std::sqrt(sy);
  const double m = shape[kSex], w = shape[kWeight], excess = heavy_excess(w);
  auto grow = [&](double rate, double heavy_rate, double girth) { return growth(rate, heavy_rate, girth, w, excess); };
  std::vector<Primitive> added;
  auto add = [&](Primitive p, Region region, int side = 0) { added.push_back(p.in(region, side)); };

  // Breasts: a little lower and flatter, blended into the chest over a wider
  // radius for a woman (no globes set on it).
  for (int side = 0; side < 2; ++side) {
    Primitive& breast = part_of(body, Region::Trunk, 0, 5 + side);
    breast = Primitive::ellipsoid(breast.a + V3(0, -0.012 * sy, -0.006 * sr), breast.semi.cwiseProduct(V3(1.0, 1.10, 0.92)),
                                  lerp(0.045, 0.03, m));
    breast.carries = false;  // inside a man's chest: the chest carries the vertices over them
  }
  // The upper back: shoulder blades rounding the back above the chest.
  const Primitive chest = part_of(body, Region::Trunk, 0, 3);
  add(Primitive::ellipsoid(chest.a + V3(0, 0.045 * sy, -0.03 * sr), chest.semi.cwiseProduct(V3(0.80, 0.75, 0.86)), 0.05),
      Region::Trunk);

  // Proportions measured against MakeHuman bodies of the same sex, height and
  // BMI (scripts/figures/body_proportions.py, docs/bodies.md "The human rig"): the
  // mannequin's hips are 5-14 % wider around, its calves 5-10 % and its heavy
  // ankles and necks 10-25 % narrower. The hips give some of their volume back
  // (the BMI solve puts it elsewhere); calves, ankles and neck grow more, the
  // ankles faster above the mean adiposity, as fat there does. The neck grows
  // slower than the mannequin's above it: the mannequin's own rate already
  // makes a man's neck 59 cm around at BMI 58, where clinical series of severe
  // obesity measure about 45-55 cm, and a faster one (exp(0.6 x the excess),
  // before) made the neck as wide as the head and the head a cone above it.
  Primitive& hips_part = part_of(body, Region::Trunk, 0);
  hips_part = Primitive::ellipsoid(hips_part.a, hips_part.semi.cwiseProduct(V3(0.91, 1.0, 0.91)), hips_part.blend);
  for (int side : {-1, 1}) {
    Primitive& shin = part_of(body, Region::Shin, side);
    shin = Primitive::cone(shin.a, shin.ra, shin.b, shin.rb * 1.04 * std::exp(0.6 * excess), shin.blend).in(Region::Shin, side);
    Primitive& calf = part_of(body, Region::Calf, side);
    calf = Primitive::ellipsoid(calf.a, calf.semi.cwiseProduct(V3(1.08, 1.0, 1.08)), calf.blend).in(Region::Calf, side);
  }
  Primitive& neck_part = part_of(body, Region::Neck, 0);
  const double neck_g = 1.03 * grow(0.0, -0.2, 0.0);  // on top of the mannequin's: as it is up to the mean, slower above
  neck_part = Primitive::cone(neck_part.a, neck_part.ra * neck_g, neck_part.b, neck_part.rb * neck_g, neck_part.blend).in(Region::Neck);

  // Buttocks: behind the hips ellipsoid and below its centre, in proportion to
  // it, so they follow the hips girth and a heavy woman's deeper hips.
  const Primitive hips = part_of(body, Region::Trunk, 0);
  for (int side : {-1, 1}) {
    const V3 c(side * 0.42 * hips.semi.x(), hips.a.y() - 0.045 * sy, hips.a.z() - lerp(0.46, 0.40, m) * hips.semi.z());
    add(Primitive::ellipsoid(c, V3(0.47 * hips.semi.x(), 0.090 * sy, lerp(0.64, 0.58, m) * hips.semi.z()), 0.05),
        Region::Trunk, side);
  }

  // Heavy shoulders: the mannequin pushes the arms out with the upper arm's and
  // the chest's growth (body_plan.cpp, shoulder_x) so that they never merge
  // into the trunk, which widened the human rig's shoulders with BMI far
  // faster than MakeHuman's (0.375 against 0.268 of the height for a man of
  // BMI 39; docs/bodies.md, "The human rig"). The human rig takes back the
  // push gained above the mean adiposity, each arm moved in as a whole, up to
  // 4 cm (at 1.75 m): the mean body, the template and every leaner body stay
  // as they were, and the heaviest arms keep clear of the trunk (5 cm still
  // left every corner of the space uncrossed, 6 cm crossed a 1.50 m woman of
  // BMI 65 at the armpit; tests/bodies/human_rig_test.cpp).
  if (w > kMeanWeight) {
    Eigen::VectorXd at_mean = shape;
    at_mean[kWeight] = kMeanWeight;
    const double gained = part_of(body, Region::UpperArm, 1).a.x() - mannequin_shoulder_x(at_mean);
    const double inward = std::min(std::max(0.0, gained), 0.04 * sr);
    for (Primitive& p : body.parts)
      if (p.region == Region::UpperArm || p.region == Region::Forearm || p.region == Region::Hand)
        p = moved(p, V3(-p.side * inward, 0, 0));
  }

  // The shoulder line: a capsule per side from the side of the neck down to the
  // shoulder joint (about 20 degrees), the trapezius seen from the front.
  const Primitive neck = part_of(body, Region::Neck, 0);
  for (int side : {-1, 1}) {
    const Primitive& upper = part_of(body, Region::UpperArm, side);
    const double r = 0.032 * sr * grow(0.30, 0.45, 0.5 * shape[kChest]);
    const V3 inner(side * 0.9 * neck.ra, 1.466 * sy - r, -0.030 * sy);
    const V3 outer(upper.a.x() - side * 0.025 * sr, upper.a.y() + upper.ra - r, -0.020 * sy);
    add(Primitive::cone(inner, r, outer, 0.9 * r, 0.045), Region::Trunk, side);
  }

  // Head: cranium, face, jaw and chin, nose, ears. The cranium's top is the
  // mannequin head's (1.741 of 1.75 m before the height is made exact).
  body.parts.erase(std::remove_if(body.parts.begin(), body.parts.end(),
                                  [](const Primitive& p) { return p.region == Region::Head; }),
                   body.parts.end());
  const double hg = grow(0.06, 0.10, 0);
  add(Primitive::ellipsoid({0, 1.650 * sy, -0.006 * sy}, V3(0.074 * sr * hg, 0.091 * sy, 0.097 * sr * hg), 0.025), Region::Head);
  add(Primitive::ellipsoid({0, 1.600 * sy, 0.030 * sy}, V3(0.060 * sr * hg, 0.068 * sy, 0.066 * sr * hg), 0.03), Region::Head);
  add(Primitive::ellipsoid({0, 1.550 * sy, 0.052 * sy}, V3(lerp(0.040, 0.046, m) * sr * hg, 0.026 * sy, 0.036 * sr * hg), 0.02),
      Region::Head);
  add(Primitive::ellipsoid({0, 1.606 * sy, 0.030 * sy + 0.066 * sr * hg}, V3(0.011, 0.022, 0.016) * sr, 0.012), Region::Head);
  for (int side : {-1, 1})
    add(Primitive::ellipsoid({side * (0.074 * sr * hg + 0.002), 1.622 * sy, -0.004 * sy}, V3(0.011, 0.029, 0.018) * sr, 0.008),
        Region::Head, side);

  for (int side : {-1, 1}) {
    const Primitive& upper = part_of(body, Region::UpperArm, side);
    const Primitive& fore = part_of(body, Region::Forearm, side);
    Primitive& hand = part_of(body, Region::Hand, side);
    const V3 dir = (upper.b - upper.a).normalized(), wrist = fore.b;
    // Deltoid: a cap over the shoulder joint and the top third of the upper
    // arm, on its outer side only (on the armpit's side it stays inside the
    // arm, which a thin body's arm holds close to the chest).
    const V3 lateral = -side * dir.cross(V3::UnitZ());
    add(Primitive::ellipsoid(upper.a + 0.035 * sy * dir + 0.10 * upper.ra * lateral, V3(0.070 * sy, 0.92 * upper.ra, 0.92 * upper.ra),
                             0.04, frame_along(dir, V3::UnitZ())),
        Region::UpperArm, side);
    // Forearm muscles: thickest a third of the way down, flattened front to back.
    add(Primitive::ellipsoid(fore.a + 0.30 * (fore.b - fore.a), V3(0.090 * sy, 1.10 * fore.ra, 0.96 * fore.ra), 0.03,
                             frame_along(dir, V3::UnitZ())),
        Region::Forearm, side);
    // Hand: the paddle becomes a palm with the fingers together (separate
    // fingers would need 5 mm triangles) and a thumb in front, turned towards
    // the thigh (palms face the body in the A-pose). Meshed 1.6 times finer
    // than the rest of the body (the magnifier), so the thumb comes out clean.
    const double hand_g = grow(0.12, 0.12, 0), hl = lerp(0.93, 1.0, m) * sy, hw = sr * hand_g;
    const Eigen::Matrix3d hand_frame = hand.frame;
    const V3 front = V3::UnitZ(), medial = side * dir.cross(front);
    hand = Primitive::ellipsoid(wrist + 0.050 * hl * dir, V3(0.056 * hl, 0.042 * hw, 0.020 * hw), 0.018, hand_frame)
               .in(Region::Hand, side);
    // The fingers, bent a little towards the palm: a flat block to the knuckles
    // and a narrower one to the tips.
    const V3 knuckles = wrist + 0.100 * hl * dir, bent = (dir + 0.30 * medial).normalized();
    add(Primitive::ellipsoid(knuckles + 0.018 * hl * dir + 0.002 * medial, V3(0.046 * hl, 0.040 * hw, 0.0155 * hw), 0.02,
                             frame_along(dir, front)),
        Region::Hand, side);
    add(Primitive::ellipsoid(knuckles + 0.052 * hl * bent + 0.008 * medial, V3(0.040 * hl, 0.035 * hw, 0.0135 * hw), 0.02,
                             frame_along(bent, front)),
        Region::Hand, side);
    const V3 thumb_a = wrist + 0.022 * hl * dir + 0.028 * hw * front + 0.004 * medial;
    const V3 thumb_b = thumb_a + 0.048 * hl * (0.55 * dir + 0.70 * front + 0.45 * medial).normalized();
    const V3 thumb_c = thumb_b + 0.034 * hl * (0.60 * dir + 0.55 * front + 0.50 * medial).normalized();
    add(Primitive::cone(thumb_a, 0.0130 * hw, thumb_b, 0.0110 * hw, 0.012), Region::Hand, side);
    add(Primitive::cone(thumb_b, 0.0110 * hw, thumb_c, 0.0095 * hw, 0.005), Region::Hand, side);
    body.magnifiers.push_back({wrist + 0.09 * hl * dir, 1.6, 0.10 * hl, 0.125 * hl, 0.6});
  }

  // Feet: the disc becomes the instep, with a heel behind the ankle and the
  // toes in front; 0.154 of the height long for a man, 8 % shorter for a woman.
  for (int side : {-1, 1}) {
    Primitive& foot = part_of(body, Region::Foot, side);
    const double x = foot.a.x(), fw = foot.semi.x(), len = lerp(0.92, 1.0, m) * sy;
    foot = Primitive::ellipsoid({x + side * 0.004 * sr, 0.033 * sy, 0.060 * len}, V3(0.96 * fw, 0.033 * sy, 0.085 * len), 0.025)
               .in(Region::Foot, side);
    add(Primitive::ellipsoid({x, 0.032 * sy, -0.030 * len}, V3(0.66 * fw, 0.032 * sy, 0.040 * len), 0.02), Region::Foot, side);
    add(Primitive::ellipsoid({x + side * 0.010 * sr, 0.017 * sy, 0.150 * len}, V3(1.02 * fw, 0.017 * sy, 0.048 * len), 0.02),
        Region::Foot, side);
  }

  for (Primitive& p : added) body.parts.push_back(p);
  return body;
}

}  // namespace drape::parametric
