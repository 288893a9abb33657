#pragma once
// Small meshes for the mesh I/O tests.
#include <drape/mesh.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace drape::test {

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

// A unit cube as 6 quads with a cross-shaped UV net: 8 positions, 14 UVs
// (the net is cut along 7 edges, so corners on the cut have several UVs).
inline std::string cube_obj() {
  return "# cube with UV seams\n"
         "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
         // strip around the sides: bottom row 1..5, top row 6..10
         "vt 0 0.33\nvt 0.25 0.33\nvt 0.5 0.33\nvt 0.75 0.33\nvt 1 0.33\n"
         "vt 0 0.66\nvt 0.25 0.66\nvt 0.5 0.66\nvt 0.75 0.66\nvt 1 0.66\n"
         "vt 0.25 1\nvt 0 1\nvt 0.25 0\nvt 0 0\n"
         "g sides\n"
         "f 1/1 2/2 3/7 4/6\n"   // front
         "f 2/2 6/3 7/8 3/7\n"   // right
         "f 6/3 5/4 8/9 7/8\n"   // back
         "f 5/4 1/5 4/10 8/9\n"  // left
         "g caps\n"
         "f 4/6 3/7 7/11 8/12\n"   // top
         "f 5/14 6/13 2/2 1/1\n";  // bottom
}

// A bumpy grid of nx*ny vertices with per-vertex UVs, its vertex order shuffled
// so that any reordering by a reader or writer shows.
inline Mesh shuffled_grid(int nx, int ny, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.3, 0.3);
  const int V = nx * ny;
  std::vector<int> order(static_cast<std::size_t>(V));
  for (int i = 0; i < V; ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);  // grid vertex g is stored at order[g]
  Mesh m;
  m.vertices.resize(V, 3);
  m.uv.resize(V, 2);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int g = j * nx + i;
      m.vertices.row(order[g]) << 0.1 * i + 0.01 * noise(rng), 0.5 * noise(rng), -0.1 * j + 0.01 * noise(rng);
      m.uv.row(order[g]) << double(i) / (nx - 1), double(j) / (ny - 1);
    }
  m.faces.resize(2 * (nx - 1) * (ny - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = order[j * nx + i], b = order[j * nx + i + 1], c = order[(j + 1) * nx + i + 1],
                d = order[(j + 1) * nx + i];
      m.faces.row(f++) << a, b, c;
      m.faces.row(f++) << a, c, d;
    }
  m.uv_faces = m.faces;
  return m;
}

}  // namespace drape::test
