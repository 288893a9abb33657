#include <drape/energy.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/garment_layers.hpp>

#include <drape/errors.hpp>
#include <drape/warnings.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/self_intersection.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <vector>

namespace drape {

namespace {
// A garment this many times the body's size (its largest extent, the height
// in A-pose) is in other units: the longest real garment (a gown, a cape)
// stays within about 1.2 body heights.
constexpr double kLargestGarmentToBody = 3.0;
// ... or this small a share of it: the smallest garment (a bow tie, a
// glove) is about a twentieth of a body's height; an outside check's shirt
// in decimetres (7 cm across, at the feet) simulated, "fell off the body",
// and was told to add friction.
constexpr double kSmallestGarmentToBody = 0.05;
// A typical garment is about half the body's size across (a shirt 0.8 m on a
// 1.75 m body, a skirt 0.5 m): the suggested unit scale brings it nearest.
constexpr double kTypicalGarmentToBody = 0.5;
}  // namespace

void check_garment_around_body(const Mesh& garment, const Mesh& body, const std::string& what) {
  if (garment.vertices.rows() == 0 || body.vertices.rows() == 0) return;
  const Eigen::RowVector3d glo = garment.vertices.colwise().minCoeff(), ghi = garment.vertices.colwise().maxCoeff();
  const Eigen::RowVector3d blo = body.vertices.colwise().minCoeff(), bhi = body.vertices.colwise().maxCoeff();
  const double garment_size = (ghi - glo).maxCoeff(), body_size = (bhi - blo).maxCoeff();
  // Room for the numbers beside `what`, which names a file of any length.
  std::vector<char> line(what.size() + 512);
  if (garment_size > kLargestGarmentToBody * body_size || garment_size < kSmallestGarmentToBody * body_size) {
    // The power of ten that brings it nearest a typical garment's size: 0.01
    // for centimetres, 0.001 for millimetres, 10 for decimetres read as metres.
    const double scale = std::pow(10.0, -std::round(std::log10(garment_size / (kTypicalGarmentToBody * body_size))));
    std::snprintf(line.data(), line.size(),
                  "%s is %.3g m across, the body %.3g m: drape reads metres, so the garment is likely in other units "
                  "(scaled by %g it would be %.3g m); it must be modelled around the body in metres",
                  what.c_str(), garment_size, body_size, scale, scale * garment_size);
    throw ConfigError(line.data());
  }
  // Apart from the body: the gap between the two boxes, 0 where they overlap.
  const Eigen::RowVector3d gap = (blo - ghi).cwiseMax(glo - bhi).cwiseMax(0.0);
  if (gap.norm() > 0.1 * body_size) {
    std::snprintf(line.data(), line.size(),
                  "%s lies %.3g m away from the body (its box spans x %.3f..%.3f, y %.3f..%.3f, z %.3f..%.3f; the "
                  "body's x %.3f..%.3f, y %.3f..%.3f, z %.3f..%.3f): it must be modelled around the body it is "
                  "dressed on, in the body model's frame (Y up, metres)",
                  what.c_str(), gap.norm(), glo.x(), ghi.x(), glo.y(), ghi.y(), glo.z(), ghi.z(), blo.x(), bhi.x(), blo.y(),
                  bhi.y(), blo.z(), bhi.z());
    throw ConfigError(line.data());
  }
  // Turned about the vertical: the widest way across of each, from the
  // horizontal second moments about its centroid.
  struct Across {
    double degrees, ratio;  // the widest way's angle from +x (-90..90), and its spread over the narrowest way's
  };
  const auto across = [](const Eigen::MatrixX3d& v) {
    const Eigen::RowVector3d c = v.colwise().mean();
    double xx = 0, zz = 0, xz = 0;
    for (Eigen::Index i = 0; i < v.rows(); ++i) {
      const double x = v(i, 0) - c.x(), z = v(i, 2) - c.z();
      xx += x * x, zz += z * z, xz += x * z;
    }
    const double mean = 0.5 * (xx + zz), half = std::sqrt(0.25 * (xx - zz) * (xx - zz) + xz * xz);
    const double wide = mean + half, narrow = std::max(mean - half, 1e-300);
    const double degrees = 0.5 * std::atan2(2.0 * xz, xx - zz) * 180.0 / std::numbers::pi;  // -90..90
    return Across{degrees, std::sqrt(wide / narrow)};
  };
  constexpr double kClearlyWider = 1.3;  // a shirt with its sleeves about 2.3, the A-pose body about 2.6
  const Across g = across(garment.vertices), b = across(body.vertices);
  const double apart = std::min(std::abs(g.degrees - b.degrees), 180.0 - std::abs(g.degrees - b.degrees));  // 0..90
  if (g.ratio > kClearlyWider && b.ratio > kClearlyWider && apart > 45.0) {
    std::snprintf(line.data(), line.size(),
                  "%s is widest across %.0f degrees from the way the body is (its widest way %.0f degrees from +x, "
                  "%.1f times its narrowest; the body's %.0f degrees, across its shoulders and arms): it is likely "
                  "turned about the vertical; drape reads a garment facing +z, as the body faces, modelled around it",
                  what.c_str(), apart, std::round(g.degrees) + 0.0, g.ratio, std::round(b.degrees) + 0.0);
    throw ConfigError(line.data());
  }
}

namespace {
// A garment's outward normal at each vertex (area-weighted; zero where the
// way out is unknown). The way out is a property of the garment alone, not
// of where it lies against the body: each piece's faces, with their normals,
// face away from the piece's centroid on the whole (a shirt's panels and
// sleeves, a skirt, each leg of trousers with its outer side), and the
// piece's normals are flipped where its faces are wound the other way. A
// piece whose faces point as much in as out (a flat patch, a piece wound
// inconsistently) gets no normals.
Eigen::MatrixX3d outward_normals(const Mesh& garment) {
  constexpr double kLeastAgreement = 0.2;  // |sum of n.(c_f - c)| over sum of |...|, below which the way out is unknown
  const Eigen::MatrixX3d& x = garment.vertices;
  const Eigen::MatrixX3i& faces = garment.faces;
  const std::vector<int> piece = garment_pieces(faces, static_cast<int>(x.rows()));
  const int pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  Eigen::MatrixX3d area_normal(faces.rows(), 3), centre(faces.rows(), 3);
  std::vector<Eigen::RowVector3d> centroid(static_cast<std::size_t>(pieces), Eigen::RowVector3d::Zero());
  std::vector<double> area(static_cast<std::size_t>(pieces), 0.0), out(area), total(area);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::RowVector3d a = x.row(faces(f, 0)), b = x.row(faces(f, 1)), c = x.row(faces(f, 2));
    area_normal.row(f) = 0.5 * (b - a).cross(c - a);
    centre.row(f) = (a + b + c) / 3.0;
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(f)]);
    const double af = area_normal.row(f).norm();
    centroid[p] += af * centre.row(f), area[p] += af;
  }
  for (int p = 0; p < pieces; ++p)
    if (area[static_cast<std::size_t>(p)] > 0) centroid[static_cast<std::size_t>(p)] /= area[static_cast<std::size_t>(p)];
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(f)]);
    const double lever = area_normal.row(f).dot(centre.row(f) - centroid[p]);
    out[p] += lever, total[p] += std::abs(lever);
  }
  Eigen::MatrixX3d normal = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(f)]);
    if (!(std::abs(out[p]) > kLeastAgreement * total[p])) continue;
    const double sign = out[p] > 0 ? 1.0 : -1.0;
    for (int k = 0; k < 3; ++k) normal.row(faces(f, k)) += sign * area_normal.row(f);
  }
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    if (const double n = normal.row(v).norm(); n > 0) normal.row(v) /= n;
  return normal;
}
}  // namespace

DressReport dress(Garment& garment, const BodyQuery& body, const DressOptions& options) {
  Eigen::MatrixX3d& x = garment.mesh.vertices;
  // Where it was cut, kept for the self-contact (Garment::cut_vertices): the first dressing's start.
  if (garment.cut_vertices.rows() != x.rows()) garment.cut_vertices = x;
  // A vertex deep inside whose cloth faces away from the way out is pushed
  // through the body (DressReport::pushed_through): more than 60 degrees apart.
  constexpr double kFacingAway = -0.5;
  const Eigen::MatrixX3d outward = outward_normals(garment.mesh);
  const Eigen::MatrixX3d start = x;
  const int nv = static_cast<int>(x.rows());
  std::vector<std::vector<int>> nb(static_cast<std::size_t>(nv));
  for (Eigen::Index f = 0; f < garment.mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) nb[garment.mesh.faces(f, k)].push_back(garment.mesh.faces(f, (k + 1) % 3)),
                                nb[garment.mesh.faces(f, (k + 1) % 3)].push_back(garment.mesh.faces(f, k));
  DressReport report;
  std::vector<char> moved(static_cast<std::size_t>(nv), 0);
  // One pass of pushing vertices out to the clearance; returns how many moved.
  auto push = [&](bool first) {
    int count = 0;
    for (int v = 0; v < nv; ++v) {
      const BodyQuery::Hit hit = body.closest(x.row(v).transpose());
      if (first && hit.signed_distance < 0) ++report.inside_before, report.deepest_before = std::max(report.deepest_before, -hit.signed_distance);
      if (first && hit.signed_distance < -kThroughDepth && outward.row(v).dot(hit.normal.transpose()) < kFacingAway) {
        report.pushed_through.push_back(v);
        report.deepest_through = std::max(report.deepest_through, -hit.signed_distance);
      }
      // The micrometre of slack keeps a vertex just placed at the clearance from
      // being pushed again forever by rounding.
      if (hit.signed_distance < options.margin - 1e-6) {
        x.row(v) = hit.point + options.margin * hit.normal;
        moved[v] = 1;
        ++count;
      }
    }
    return count;
  };
  for (int it = 0; it < options.max_iterations; ++it) {
    report.iterations = it + 1;
    if (push(it == 0) == 0) break;
    // Spread the correction: averaging displacements lets the neighbours of a
    // pushed vertex follow it instead of leaving a spike. Vertices once pushed
    // keep their displacement (smoothing them would pull them back in and the
    // rounds would oscillate), so the rounds stop once nothing new needs a push.
    Eigen::MatrixX3d d = x - start;
    for (int s = 0; s < options.smoothing_steps; ++s) {
      Eigen::MatrixX3d next = d;
      for (int v = 0; v < nv; ++v) {
        if (nb[v].empty() || moved[v]) continue;
        Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
        for (int w : nb[v]) mean += d.row(w);
        next.row(v) = 0.5 * d.row(v) + 0.5 * mean / static_cast<double>(nb[v].size());
      }
      d.swap(next);
    }
    x = start + d;
  }
  // A final push so that the result never ends inside, whatever the smoothing did.
  push(false);

  // Neighbours pushed onto different sides of a crease (an armpit, between
  // the arm and the torso) can fold the cloth through itself, and the
  // simulation cannot undo that (its self-contact leaves such a rest state
  // unguarded). Then the fold is smoothed out where it is: the vertices of
  // every edge through a face and of that face, and two rings around them,
  // move twice to the mean of their neighbours, and the vertices inside are
  // pushed out again, round after round; the round with the fewest edges
  // through faces is kept (the dressing above when none has fewer: a
  // garment that came through it untangled is left exactly as it was).
  // Edges through faces, not faces through faces: a fold one edge long (an
  // edge through a face beside its own) is seen too. (Tried first: smoothing
  // every displacement, pushed vertices' included; it left 5-13 edges of a
  // graded MakeHuman shirt's armpits through faces.)
  if (options.untangle_rounds > 0) {
    constexpr int kRings = 2, kSmoothing = 2;
    const Eigen::MatrixX3i& faces = garment.mesh.faces;
    auto crossings = geometry::self_edge_crossings(x, faces, geometry::kCrossingsCountedAtMost);
    std::size_t tangled = crossings.size();
    report.tangled_before = static_cast<int>(tangled);
    if (tangled > 0) {
      Eigen::MatrixX3d best = x;
      for (int round = 1; round <= options.untangle_rounds && !crossings.empty(); ++round) {
        std::vector<char> in(static_cast<std::size_t>(nv), 0);
        for (const auto& [edge, face] : crossings) {
          in[static_cast<std::size_t>(edge.first)] = in[static_cast<std::size_t>(edge.second)] = 1;
          for (int k = 0; k < 3; ++k) in[static_cast<std::size_t>(faces(face, k))] = 1;
        }
        for (int r = 0; r < kRings; ++r) {
          std::vector<char> grown = in;
          for (int v = 0; v < nv; ++v)
            if (in[static_cast<std::size_t>(v)])
              for (int w : nb[v]) grown[static_cast<std::size_t>(w)] = 1;
          in.swap(grown);
        }
        for (int s = 0; s < kSmoothing; ++s) {
          Eigen::MatrixX3d next = x;
          for (int v = 0; v < nv; ++v) {
            if (!in[static_cast<std::size_t>(v)] || nb[v].empty()) continue;
            Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
            for (int w : nb[v]) mean += x.row(w);
            next.row(v) = mean / static_cast<double>(nb[v].size());
          }
          x.swap(next);
        }
        for (int k = 0; k < options.max_iterations && push(false) > 0; ++k) {
        }  // until no vertex needs a push (at a crease one push can land close to the other side)
        crossings = geometry::self_edge_crossings(x, faces, geometry::kCrossingsCountedAtMost);
        if (crossings.size() < tangled) best = x, tangled = crossings.size(), report.untangle_rounds = round;
      }
      x = best;
    }
    report.tangled_after = static_cast<int>(tangled);
  }
  report.pushed = static_cast<int>(std::count(moved.begin(), moved.end(), 1));
  // A garment of several pieces: each outside the one under it (garment_layers.hpp).
  if (options.lay_pieces) report.layers = separate_layers(garment, body);
  if (report.layers.crossings > 0)
    warn("the garment's " + std::to_string(report.layers.pieces) + " pieces still pass through each other at " +
         std::to_string(report.layers.crossings) + " edge-face pairs after " + std::to_string(report.layers.moved) +
         " vertices were moved out of the piece under them (garment_layers.hpp); the cloth's self-contact leaves "
         "those places out");
  report.min_distance_after = INFINITY;
  for (int v = 0; v < nv; ++v)
    report.min_distance_after = std::min(report.min_distance_after, body.closest(x.row(v).transpose()).signed_distance);
  return report;
}

DressReport dress(Garment& garment, const Mesh& body, const DressOptions& options) {
  return dress(garment, geometry::BodySurface(body), options);
}

}  // namespace drape
