#include "hinges.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <cstdint>
#include <string>

namespace drape::bending {

std::vector<HingeTopology> find_hinges(const Mesh& mesh) {
  struct HalfEdge {
    std::uint64_t key;  // (min vertex, max vertex)
    int face, corner;
  };
  const int nf = mesh.num_faces();
  const int nv = mesh.num_vertices();
  std::vector<HalfEdge> half;
  half.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      if (a < 0 || a >= nv) throw ConfigError("face " + std::to_string(f) + " has a vertex index out of range");
      if (a == b) throw ConfigError("face " + std::to_string(f) + " repeats vertex " + std::to_string(a));
      const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
      half.push_back({lo << 32 | hi, f, k});
    }
  }
  // Sorting by (key, face, corner) makes the order, and so the hinges, deterministic.
  std::sort(half.begin(), half.end(), [](const HalfEdge& l, const HalfEdge& r) {
    return l.key != r.key ? l.key < r.key : l.face != r.face ? l.face < r.face : l.corner < r.corner;
  });
  std::vector<HingeTopology> hinges;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    if (j - i > 2)
      throw ConfigError("the edge between vertices " + std::to_string(half[i].key >> 32) + " and " +
                        std::to_string(half[i].key & 0xffffffffu) + " is shared by " + std::to_string(j - i) +
                        " faces; the garment must be a manifold surface");
    if (j - i == 2) {
      HingeTopology h;
      for (int s = 0; s < 2; ++s) {
        h.face[s] = half[i + s].face;
        h.corner[s] = half[i + s].corner;
      }
      const int f0 = h.face[0], c0 = h.corner[0], f1 = h.face[1];
      h.vertex[0] = mesh.faces(f0, c0);
      h.vertex[1] = mesh.faces(f0, (c0 + 1) % 3);
      h.vertex[2] = mesh.faces(f0, (c0 + 2) % 3);
      h.vertex[3] = mesh.faces(f1, (h.corner[1] + 2) % 3);
      hinges.push_back(h);
    }
    i = j;
  }
  return hinges;
}

}  // namespace drape::bending
