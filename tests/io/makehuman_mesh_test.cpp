// The real assets: MakeHuman's base mesh (quads, 139 groups) and a T-shirt
// outfit with UVs. Skipped with a warning where /work/shared/assets is absent.
#include <drape/io/mesh_io.hpp>

#include "test_support.hpp"

#include <catch2/catch.hpp>

using namespace drape;
namespace fs = std::filesystem;

namespace {
fs::path makehuman(const std::string& relative) {
  const fs::path assets = drape::test::shared_assets();
  return assets.empty() ? fs::path() : assets / "makehuman" / relative;
}
}  // namespace

TEST_CASE("MakeHuman base mesh: 19158 vertices, quads fanned, 139 groups", "[io][assets]") {
  const fs::path file = makehuman("base/base.obj");
  if (file.empty()) {
    WARN("shared assets not found next to the source tree; skipping the MakeHuman base mesh test");
    SUCCEED();
    return;
  }
  const PolygonMesh polygons = read_obj_polygons(file);
  CHECK(polygons.num_vertices() == 19158);
  CHECK(polygons.num_faces() == 18486);
  CHECK(polygons.uv.rows() == 21334);
  CHECK(polygons.group_names.size() == 139);
  CHECK(polygons.group_names.front() == "body");
  // The README's layout: the skin surface is vertices 0..13379.
  const std::vector<int> body = group_vertices(polygons, "body", file.string());
  REQUIRE(body.size() == 13380);
  CHECK(body.back() == 13379);

  const Mesh mesh = triangulate(polygons);
  CHECK(mesh.num_vertices() == 19158);
  CHECK(mesh.num_faces() == 2 * 18486);
  CHECK(mesh.has_uv());
  CHECK_NOTHROW(require_vertex_count(read_mesh(file), 19158, "base.obj"));

  // A glTF round trip keeps all 19158 vertices in order despite the UV seams.
  drape::test::TempDir dir;
  write_mesh(dir / "base.glb", mesh);
  const Mesh back = read_mesh(dir / "base.glb");
  REQUIRE(back.num_vertices() == 19158);
  CHECK((back.vertices - mesh.vertices).cwiseAbs().maxCoeff() < 1e-5);
  CHECK(back.faces == mesh.faces);
}

TEST_CASE("MakeHuman T-shirt outfit: 1696 vertices with UVs", "[io][assets]") {
  const fs::path file = makehuman("clothes/male_casualsuit04/male_casualsuit04.obj");
  if (file.empty()) {
    WARN("shared assets not found next to the source tree; skipping the MakeHuman clothes test");
    SUCCEED();
    return;
  }
  const Mesh mesh = read_mesh(file);
  CHECK(mesh.num_vertices() == 1696);
  CHECK(mesh.num_faces() == 2 * 1620);
  REQUIRE(mesh.has_uv());
  CHECK(mesh.uv.rows() == 1887);
}
