// A garment from a mesh file (plugin kind "garment", name "mesh"): a user's
// own garment, modelled around the scene body model's mean shape, in any
// format drape reads (OBJ, PLY, glTF/GLB), vertex order kept.
//
// Material space -- what the cloth's rest lengths and angles are measured in:
//   uv    the file's per-corner UVs, a sewing pattern, times uv_scale
//         (metres per UV unit): the T-shirt's convention, and ArcSim's.
//   rest  the rest 3D shape itself, as HOOD does: each triangle laid flat as
//         it is in the file (its own corners, so the pattern needs no seams);
//         for garments whose UVs are a texture atlas, not a pattern.
// Material regions: an OBJ's `usemtl` groups or a glTF's materials, by name,
// or one region "cloth";
// each is the knit unless the scene's materials say otherwise.
// Bad input is refused with one line naming the file and the element.
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/materials/materials.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/bodies/body.hpp>
#include <drape/plugin.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <functional>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>

namespace {

using namespace drape;

struct MeshGarmentOptions {
  std::string file;
  std::string material_space = "uv";
  double uv_scale = 1.0;
  bool weld = false;
  double weld_distance = 1e-6;
};

std::string where(const MeshGarmentOptions& o) { return "garment mesh '" + o.file + "'"; }

// A vertex or face as the messages name it: drape counts from 0, an OBJ's
// lines from 1 (an outside check read "face 1907" as the 1,907th f line).
// A face is a triangle of the file's polygons in order, as the reader splits them.
std::string vertex_name(int v) { return "vertex " + std::to_string(v) + " (from 0: the file's vertex " + std::to_string(v + 1) + ")"; }
std::string face_name(int f) {
  return "face " + std::to_string(f) + " (from 0: the file's triangle " + std::to_string(f + 1) + ", its polygons split in order)";
}

// Vertices closer than `distance` to an earlier one: the seams of a garment
// exported with split vertices. Returns, per vertex, the vertex it merges into
// (itself when kept). `may_merge(i, j)` says whether two such vertices are
// a seam's two copies.
std::vector<int> duplicates(const Eigen::MatrixX3d& v, double distance, const std::function<bool(int, int)>& may_merge) {
  std::vector<int> order(static_cast<std::size_t>(v.rows()));
  for (int i = 0; i < v.rows(); ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return v(a, 0) < v(b, 0) || (v(a, 0) == v(b, 0) && a < b); });
  std::vector<int> into(static_cast<std::size_t>(v.rows()));
  for (int i = 0; i < v.rows(); ++i) into[static_cast<std::size_t>(i)] = i;
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size() && v(order[b], 0) - v(order[a], 0) <= distance; ++b) {
      const int i = order[a], j = order[b];
      if ((v.row(i) - v.row(j)).norm() <= distance && may_merge(i, j)) {
        const int keep = std::min(into[static_cast<std::size_t>(i)], into[static_cast<std::size_t>(j)]);
        into[static_cast<std::size_t>(std::max(i, j))] = keep;
      }
    }
  return into;
}

// Welds split seam vertices (weld: true) or refuses them, naming the first pair.
void handle_duplicates(Mesh& mesh, const MeshGarmentOptions& o) {
  // A seam's two copies lie on the borders of their pieces, joined by no
  // edge, within a hair of each other: a thousandth of the mesh's median
  // edge (1 um at least). An exporter's rounding split them by microns (an
  // outside check's copies 5-20 um apart were taken as an open seam, and
  // the skirt fell off through it); two vertices of one edge are a short
  // edge, never a seam's copies.
  const std::vector<std::array<int, 2>> edges = geometry::edge_list(mesh.faces);
  std::vector<double> lengths;
  for (const auto& [a, b] : edges) lengths.push_back((mesh.vertices.row(a) - mesh.vertices.row(b)).norm());
  double median = 0;
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
    median = lengths[lengths.size() / 2];
  }
  const double distance = std::max(o.weld_distance, 1e-3 * median);
  // The border: the corners of each face's edge with no face across it.
  std::vector<char> on_border(static_cast<std::size_t>(mesh.num_vertices()), 0);
  const std::vector<std::array<int, 3>> across = geometry::face_neighbours(mesh.faces);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (across[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)] < 0)
        on_border[static_cast<std::size_t>(mesh.faces(f, k))] = on_border[static_cast<std::size_t>(mesh.faces(f, (k + 1) % 3))] = 1;
  const auto seam_copies = [&](int i, int j) {
    // Two ends of one edge are never a seam's copies, however near: an edge
    // collapsed to a point was "a seam exported with split vertices ... both
    // on the border", and weld: true then made a face use a vertex twice (an
    // outside check). Left apart, the mesh's quality check names the face.
    // (edge_list's edges are sorted, each lower vertex first.)
    if (std::binary_search(edges.begin(), edges.end(), std::array<int, 2>{std::min(i, j), std::max(i, j)})) return false;
    if ((mesh.vertices.row(i) - mesh.vertices.row(j)).norm() <= o.weld_distance) return true;  // (on one spot: as ever)
    return on_border[static_cast<std::size_t>(i)] && on_border[static_cast<std::size_t>(j)];
  };
  const std::vector<int> into = duplicates(mesh.vertices, distance, seam_copies);
  int merged = 0, first = -1;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    if (into[static_cast<std::size_t>(i)] != i) {
      ++merged;
      if (first < 0) first = i;
    }
  if (merged == 0) return;
  if (!o.weld)
    throw ConfigError(where(o) + ": " + std::to_string(merged) + " vertices duplicate an earlier one (" + vertex_name(first) + " sits on " +
                      vertex_name(into[static_cast<std::size_t>(first)]) +
                      [&] {
                        const double apart = (mesh.vertices.row(first) - mesh.vertices.row(into[static_cast<std::size_t>(first)])).norm();
                        char text[96] = "";
                        if (apart > 0) std::snprintf(text, sizeof text, ", %.3g um from it, both on the border", 1e6 * apart);
                        return std::string(text);
                      }() +
                      "): a seam exported with split vertices would let the garment fall apart there; set weld: true "
                      "to merge them (the garment then has fewer vertices than the file)");
  std::vector<int> index(static_cast<std::size_t>(mesh.num_vertices()), -1);
  Eigen::MatrixX3d kept(mesh.num_vertices() - merged, 3);
  int n = 0;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    if (into[static_cast<std::size_t>(i)] == i) {
      index[static_cast<std::size_t>(i)] = n;
      kept.row(n++) = mesh.vertices.row(i);
    }
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) mesh.faces(f, c) = index[static_cast<std::size_t>(into[static_cast<std::size_t>(mesh.faces(f, c))])];
  mesh.vertices = kept;
}

// Cloth must be a 2-manifold: an edge of three or more faces is refused, as is
// a face that uses a vertex twice.
void check_manifold(const Mesh& mesh, const MeshGarmentOptions& o) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    if (a == b || b == c || a == c) throw ConfigError(where(o) + ": " + face_name(f) + " uses a vertex twice");
  }
  const geometry::TopologyReport t = geometry::check_topology(mesh.faces, mesh.num_vertices());
  if (t.nonmanifold_edges > 0)
    throw ConfigError(where(o) + ": the edge between " + vertex_name(t.first_nonmanifold_edge[0]) + " and " +
                      vertex_name(t.first_nonmanifold_edge[1]) + " is shared by 3 or more faces (non-manifold; " +
                      std::to_string(t.nonmanifold_edges) + " such edges); cloth needs every edge on one or two faces");
}

// A vertex no face uses is no cloth: it would be written back where it was,
// untouched by gravity or contact, and counted in p. Refused, naming it (the
// file's vertex order is the garment's, so it is not dropped silently).
void check_every_vertex_used(const Mesh& mesh, const MeshGarmentOptions& o) {
  std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) used[static_cast<std::size_t>(mesh.faces(f, c))] = 1;
  const auto unused = static_cast<int>(std::count(used.begin(), used.end(), 0));
  if (unused == 0) return;
  const auto first = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
  char at[96];
  std::snprintf(at, sizeof at, " (at %.3f, %.3f, %.3f)", mesh.vertices(first, 0), mesh.vertices(first, 1), mesh.vertices(first, 2));
  throw ConfigError(where(o) + ": " + vertex_name(first) + at + " is used by no face (" + std::to_string(unused) +
                    (unused == 1 ? " such vertex" : " such vertices") +
                    "): a loose point is no cloth; remove it from the file");
}

// Per-corner material coordinates (metres) of the rest shape: each triangle
// laid flat with its first edge along u.
void rest_shape_material_space(Mesh& mesh) {
  mesh.uv.resize(3 * mesh.num_faces(), 2);
  mesh.uv_faces.resize(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d p0 = mesh.vertices.row(mesh.faces(f, 0)), p1 = mesh.vertices.row(mesh.faces(f, 1)),
                          p2 = mesh.vertices.row(mesh.faces(f, 2));
    const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
    const Eigen::Vector3d u = e1.normalized(), n = e1.cross(e2).normalized(), v = n.cross(u);
    mesh.uv.row(3 * f) << 0, 0;
    mesh.uv.row(3 * f + 1) << e1.norm(), 0;
    mesh.uv.row(3 * f + 2) << e2.dot(u), e2.dot(v);
    mesh.uv_faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  }
}

// Refuses a face whose material-space triangle is degenerate (zero or negative
// area, or a sliver), naming it: its rest strain would be undefined.
void check_material_space(const Mesh& mesh, const MeshGarmentOptions& o) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector2d a = mesh.uv.row(mesh.uv_faces(f, 0)), b = mesh.uv.row(mesh.uv_faces(f, 1)),
                          c = mesh.uv.row(mesh.uv_faces(f, 2));
    const Eigen::Vector2d e1 = b - a, e2 = c - a;
    const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    const double longest = std::max({e1.norm(), e2.norm(), (c - b).norm()});
    if (!(area > 1e-4 * longest * longest)) {
      char sizes[96];
      std::snprintf(sizes, sizeof sizes, " has area %.3g m^2 for a longest side of %.3g m", area, longest);
      throw ConfigError(where(o) + ": " + face_name(f) + " is degenerate in material space (" +
                        (o.material_space == "uv" ? "its UV triangle" : "its rest triangle") + sizes + "): " +
                        (o.material_space == "uv" ? "fix its UVs, or use material_space: rest"
                                                  : "the mesh's triangle is a sliver; collapse or remesh it"));
    }
  }
}

class MeshGarment final : public GarmentSource {
 public:
  explicit MeshGarment(MeshGarmentOptions o) : o_(std::move(o)) {}

  Garment build() const override {
    if (o_.file.empty() || o_.file == "none") throw ConfigError("garment mesh: give the file, e.g. params: {file: my_skirt.obj}");
    if (!std::filesystem::exists(o_.file))
      throw ConfigError(where(o_) + ": no such file" +
                        (std::filesystem::path(o_.file).is_absolute()
                             ? std::string()
                             : " (a relative file is read from the folder drape runs in, " +
                                   std::filesystem::current_path().string() + ", not the scene's)"));
    Garment g;
    // Material regions: an OBJ's `usemtl` groups or a glTF's materials (one
    // region "cloth" when the file has fewer than two).
    MaterialMesh file = read_mesh_with_materials(o_.file);
    g.mesh = std::move(file.mesh);
    std::vector<std::string> regions{"cloth"};
    Eigen::VectorXi face_region;
    if (file.material_names.size() > 1) {
      regions = file.material_names;
      face_region = Eigen::Map<const Eigen::VectorXi>(file.face_material.data(), static_cast<Eigen::Index>(file.face_material.size()));
    }
    if (g.mesh.num_faces() == 0) throw ConfigError(where(o_) + ": has no faces");
    if (!g.mesh.vertices.allFinite()) throw ConfigError(where(o_) + ": has a non-finite vertex");
    if (o_.material_space == "uv") {
      if (!g.mesh.has_uv())
        throw ConfigError(where(o_) + ": has no UVs (per-corner texture coordinates); give the file a sewing pattern "
                          "as UVs, or use material_space: rest to measure the cloth on its rest shape");
      g.mesh.uv *= o_.uv_scale;
    }
    handle_duplicates(g.mesh, o_);
    check_manifold(g.mesh, o_);
    check_every_vertex_used(g.mesh, o_);
    if (o_.material_space == "rest") rest_shape_material_space(g.mesh);
    check_material_space(g.mesh, o_);
    // Every region starts as the knit; the scene's `materials:` names each
    // region's cloth (materials: {print: screen-print}).
    for (const std::string& region : regions) {
      Material m = MaterialTable::builtin().get("gray-interlock");
      m.name = region;
      g.materials.push_back(m);
    }
    g.face_material = face_region;
    return g;
  }

 private:
  MeshGarmentOptions o_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "garment";
  d.name = "mesh";
  d.doc = "A garment from a mesh file (OBJ, PLY, glTF/GLB), modelled around the body model's mean shape; material space "
          "from its UVs (a sewing pattern, uv_scale metres per unit) or its rest shape; material regions from an OBJ's "
          "usemtl groups or a glTF's materials, else one region 'cloth' (docs/garments.md).";
  d.params = {
      {.name = "file", .type = ParamType::String, .default_value = "none",
       .doc = "the garment mesh (required; relative to the working folder); its vertex order is kept"},
      {.name = "material_space", .type = ParamType::String, .default_value = "uv",
       .doc = "uv: the file's UVs are a sewing pattern; rest: the rest 3D shape",
       .choices = {"uv", "rest"}},
      {.name = "uv_scale", .type = ParamType::Float, .default_value = "1.0",
       .doc = "metres per UV unit (material_space: uv)", .min = 1e-6, .max = 1e6},
      {.name = "weld", .type = ParamType::Bool, .default_value = "false",
       .doc = "merge vertices that duplicate an earlier one (seams exported split)"},
  };
  d.create_garment = [](const Params& p) -> std::unique_ptr<GarmentSource> {
    MeshGarmentOptions o;
    o.file = p.get_string("file");
    o.material_space = p.get_string("material_space");
    o.uv_scale = p.get_float("uv_scale");
    o.weld = p.get_bool("weld");
    return std::make_unique<MeshGarment>(std::move(o));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
