#include "tshirt_mesh.hpp"

#include "materials.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/laplacian.hpp>
#include <drape/geometry/polygon_mesher.hpp>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace drape::tshirt {
namespace {

struct Panel {
  geometry::PlanarMesh mesh;
  std::vector<char> on_seam;  // per point (interior points: 0)
  Outline outline;            // the boundary points' pieces
};

Panel mesh_panel(const PatternSpec& spec, bool front, double spacing) {
  Outline outline = panel_outline(spec, front, spacing);
  Panel panel{geometry::mesh_polygon(outline.loop, spacing), outline.on_seam, std::move(outline)};
  panel.on_seam.resize(panel.mesh.points.size(), 0);
  return panel;
}

// The panel's points moved onto the graded pattern `to` (same mesh): the
// boundary onto its outline (outline_point_on), the interior by the harmonic
// map with those boundary values (cotangent weights: an affine grade would
// move every point affinely). Throws when a triangle would turn over.
Polygon2 graded_points(const Panel& panel, const PatternSpec& from, const PatternSpec& to) {
  const Polygon2& p = panel.mesh.points;
  const int n = static_cast<int>(p.size()), nb = panel.mesh.num_boundary;
  if (static_cast<std::size_t>(nb) != panel.outline.piece.size())
    throw Error("tshirt: the panel's mesh does not keep its outline's points");
  Eigen::MatrixX3d flat = Eigen::MatrixX3d::Zero(n, 3);
  for (int i = 0; i < n; ++i) flat.row(i).head<2>() = p[static_cast<std::size_t>(i)].transpose();
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(panel.mesh.triangles.size()), 3);
  for (std::size_t f = 0; f < panel.mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) faces(static_cast<Eigen::Index>(f), k) = panel.mesh.triangles[f][static_cast<std::size_t>(k)];
  const Eigen::SparseMatrix<double> K = geometry::cotangent_stiffness(flat, faces);

  Eigen::MatrixX2d boundary(nb, 2);
  for (int i = 0; i < nb; ++i)
    boundary.row(i) = outline_point_on(from, to, panel.outline.piece[static_cast<std::size_t>(i)],
                                       panel.outline.along[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(i)])
                          .transpose();
  const int ni = n - nb;
  const Eigen::SparseMatrix<double> Kii = K.block(nb, nb, ni, ni), Kib = K.block(nb, 0, ni, nb);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(Kii);
  if (solver.info() != Eigen::Success) throw Error("tshirt: the grading map's system is singular");
  const Eigen::MatrixX2d interior = solver.solve(-(Kib * boundary));

  Polygon2 out(p.size());
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = i < nb ? Eigen::Vector2d(boundary.row(i)) : Eigen::Vector2d(interior.row(i - nb));
  for (const auto& t : panel.mesh.triangles) {
    const Eigen::Vector2d a = out[static_cast<std::size_t>(t[0])], b = out[static_cast<std::size_t>(t[1])],
                          c = out[static_cast<std::size_t>(t[2])];
    if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0)
      throw Error("tshirt: grading the pattern turned a triangle over");
  }
  return out;
}

// Point order by rows of the lattice (then by u): index neighbours are mesh neighbours.
std::vector<int> row_order(const Polygon2& points, double spacing) {
  const double row = spacing * std::sqrt(3.0) / 2;
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const long ra = std::lround(points[a].y() / row), rb = std::lround(points[b].y() / row);
    return ra != rb ? ra < rb : points[a].x() < points[b].x();
  });
  return order;
}

}  // namespace

TshirtResult build_tshirt(const TshirtOptions& options) {
  const PatternSpec regular;
  const PatternSpec spec = regular.graded(options.grade);

  // Lattice step for the wanted vertex count: one vertex per sqrt(3)/2 h^2 of
  // pattern area, corrected once by what the first meshing gave.
  Outline probe = panel_outline(regular, true, 0.01);
  const double area = geometry::signed_area(probe.loop) + geometry::signed_area(panel_outline(regular, false, 0.01).loop);
  double spacing = std::sqrt(area / (std::sqrt(3.0) / 2 * options.target_vertices));
  Panel front, back;
  for (int attempt = 0; attempt < 2; ++attempt) {
    front = mesh_panel(regular, true, spacing);
    back = mesh_panel(regular, false, spacing);
    int seam = 0;
    for (char c : back.on_seam) seam += c;
    const double count = static_cast<double>(front.mesh.points.size() + back.mesh.points.size() - seam);
    if (attempt == 0) spacing *= std::sqrt(count / options.target_vertices);
  }

  // Global vertices: the front panel in row order, then the back panel's own
  // (non-seam) points in row order; back seam points reuse the front's vertex.
  std::map<std::pair<double, double>, int> front_seam;
  const std::vector<int> front_order = row_order(front.mesh.points, spacing);
  std::vector<int> front_vertex(front.mesh.points.size()), back_vertex(back.mesh.points.size(), -1);
  for (std::size_t k = 0; k < front_order.size(); ++k) front_vertex[front_order[k]] = static_cast<int>(k);
  for (std::size_t i = 0; i < front.on_seam.size(); ++i)
    if (front.on_seam[i]) front_seam[{front.mesh.points[i].x(), front.mesh.points[i].y()}] = front_vertex[i];
  int next = static_cast<int>(front.mesh.points.size());
  for (int i : row_order(back.mesh.points, spacing)) {
    if (back.on_seam[i]) {
      const auto it = front_seam.find({back.mesh.points[i].x(), back.mesh.points[i].y()});
      if (it == front_seam.end()) throw Error("a back seam point has no front partner");
      back_vertex[i] = it->second;
    } else {
      back_vertex[i] = next++;
    }
  }
  const int nv = next;
  const int nff = static_cast<int>(front.mesh.triangles.size()), nfb = static_cast<int>(back.mesh.triangles.size());
  const int nuf = static_cast<int>(front.mesh.points.size());

  // Each panel's points on the size's pattern: the regular's themselves, or
  // moved onto the graded outline (the mesh stays the regular's).
  const Polygon2 front_points = options.grade == 1.0 ? front.mesh.points : graded_points(front, regular, spec);
  const Polygon2 back_points = options.grade == 1.0 ? back.mesh.points : graded_points(back, regular, spec);
  const TorsoFrame torso = fit_torso(options.torso, options.grade);

  TshirtResult result;
  result.spacing = spacing * options.grade;
  result.garment.fit_grade = options.grade;
  Mesh& mesh = result.garment.mesh;
  mesh.vertices.resize(nv, 3);
  mesh.faces.resize(nff + nfb, 3);
  mesh.uv.resize(nuf + static_cast<int>(back.mesh.points.size()), 2);
  mesh.uv_faces.resize(nff + nfb, 3);
  result.panel_of_face.resize(nff + nfb);

  // Each panel is its own UV chart in meters, seen from outside the garment:
  // the back is mirrored (u_back = -u) and laid out to the right of the front.
  const Box2 box = front_box(spec);
  const double width = box.hi.x() - box.lo.x();
  for (int i = 0; i < nuf; ++i) {
    const Eigen::Vector2d p = front_points[i];
    mesh.uv.row(i) << p.x() - box.lo.x(), p.y();
    mesh.vertices.row(front_vertex[i]) = place(spec, torso, p, +1).transpose();
  }
  for (int i = 0; i < static_cast<int>(back.mesh.points.size()); ++i) {
    const Eigen::Vector2d p = back_points[i];
    mesh.uv.row(nuf + i) << -p.x() - box.lo.x() + width + 0.05, p.y();
    if (!back.on_seam[i]) mesh.vertices.row(back_vertex[i]) = place(spec, torso, p, -1).transpose();
  }
  for (int f = 0; f < nff; ++f) {
    const auto& t = front.mesh.triangles[f];
    for (int k = 0; k < 3; ++k) mesh.faces(f, k) = front_vertex[t[k]], mesh.uv_faces(f, k) = t[k];
    result.panel_of_face[f] = 0;
  }
  // The back's triangles are counter-clockwise seen from the front, i.e. from inside: reverse them.
  for (int f = 0; f < nfb; ++f) {
    const auto& t = back.mesh.triangles[f];
    const int order[3] = {t[0], t[2], t[1]};
    for (int k = 0; k < 3; ++k) mesh.faces(nff + f, k) = back_vertex[order[k]], mesh.uv_faces(nff + f, k) = nuf + order[k];
    result.panel_of_face[nff + f] = 1;
  }
  result.min_uv_angle_deg = std::min(geometry::min_angle_degrees(front_points, front.mesh.triangles),
                                     geometry::min_angle_degrees(back_points, back.mesh.triangles));

  // Materials: the print covers the front faces whose UV centroid lies in the
  // polygon (normalised to the front panel's bounding box).
  result.garment.materials = {knit_material()};
  result.garment.face_material = Eigen::VectorXi::Constant(nff + nfb, kKnit);
  if (options.print) {
    result.garment.materials.push_back(print_material());
    for (int f = 0; f < nff; ++f) {
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (int k = 0; k < 3; ++k) c += front_points[front.mesh.triangles[f][k]] / 3;
      const Eigen::Vector2d n((c.x() - box.lo.x()) / width, (c.y() - box.lo.y()) / (box.hi.y() - box.lo.y()));
      if (geometry::point_in_polygon(options.print_polygon, n)) result.garment.face_material[f] = kPrint;
    }
    // A print asked for on no face (a polygon smaller than a triangle) was
    // simulated as plain knit without a word (an outside check).
    if ((result.garment.face_material.head(nff).array() != kPrint).all())
      throw ConfigError("print_polygon holds the centre of no face of the front panel at this resolution: draw it "
                        "larger (in the panel's [0, 1] box), or leave print out");
  }
  return result;
}

}  // namespace drape::tshirt
