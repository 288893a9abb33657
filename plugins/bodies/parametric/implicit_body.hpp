#pragma once
// A body as an implicit surface: rounded cones (limbs) and ellipsoids (torso,
// head, hands, feet) joined one after another by a polynomial smooth minimum.
// Negative inside, zero on the skin; the gradient is exact (analytic).
#include "sampling_warp.hpp"

#include <Eigen/Core>

#include <vector>

namespace drape::parametric {

// What a part belongs to, for the skeleton (skeleton.cpp): its rings and
// hard skinning labels are found by region, so a rig may add parts freely.
enum class Region { Trunk, Neck, Head, UpperArm, Forearm, Hand, Thigh, Shin, Calf, Foot };

struct Primitive {
  enum class Kind { Ellipsoid, Cone };
  Kind kind = Kind::Ellipsoid;
  Region region = Region::Trunk;
  int side = 0;  // +1 left (x > 0), -1 right, 0 on the midline
  // Whether template vertices bind to this part (body_template.cpp): not a
  // part that lies inside the body for some shapes (a man's breasts), whose
  // vertices would be carried inside and folded by the projection back out.
  bool carries = true;
  // Ellipsoid: centre `a`, local axes (columns of `frame`), semi-axes `semi`.
  // Cone: from `a` (radius ra) to `b` (radius rb); frame columns are the axis
  // and two perpendiculars, so that a deformation can carry the offsets along.
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double ra = 0, rb = 0;
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  Eigen::Vector3d semi = Eigen::Vector3d::Ones();
  // Blend radius with everything before it (0: plain union). The first primitive's is unused.
  double blend = 0;
  // A lower bound of eval() from a sphere holding the part, which lets the union
  // skip parts that cannot change its value: see lower_bound().
  Eigen::Vector3d bound_centre = Eigen::Vector3d::Zero();
  double bound_radius = 0;
  double bound_slope = 1;  // smallest / largest semi-axis for ellipsoids
  double lower_bound(const Eigen::Vector3d& p) const;

  static Primitive ellipsoid(const Eigen::Vector3d& centre, const Eigen::Vector3d& semi, double blend,
                             const Eigen::Matrix3d& frame = Eigen::Matrix3d::Identity());
  static Primitive cone(const Eigen::Vector3d& a, double ra, const Eigen::Vector3d& b, double rb, double blend);

  // Approximate signed distance and its gradient.
  double eval(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const;
  // eval(), or +infinity (gradient untouched) when a cheap bound shows that
  // the value is at least `limit`: the union skips such a part.
  double eval_unless_beyond(const Eigen::Vector3d& p, double limit, Eigen::Vector3d* gradient) const;
  Primitive& in(Region r, int s = 0) {
    region = r;
    side = s;
    return *this;
  }

  // Maps a point near this primitive to the same place near `to` (same kind):
  // along the axis by length, across it by radius. Used to carry a template
  // vertex to a new shape.
  Eigen::Vector3d carry(const Eigen::Vector3d& p, const Primitive& to) const;
};

class ImplicitBody {
 public:
  std::vector<Primitive> parts;
  // Where the template is meshed finer (sampling_warp.hpp); none: uniform.
  Magnifiers magnifiers;

  double eval(const Eigen::Vector3d& p, Eigen::Vector3d* gradient = nullptr) const;
  // Moves `p` onto the zero level set with Newton steps along the gradient.
  Eigen::Vector3d project(Eigen::Vector3d p, int steps = 6) const;
};

}  // namespace drape::parametric
