#pragma once
// Mesh Laplacians, all sparse, in double (cast to float where a network uses them).
//
// Which one where:
//  * graph_laplacian(random_walk), L = I - D^-1 A: the L_k of the seed's
//    Laplacian difference loss (eq. 6.12, "the Laplacian operator on the mesh
//    graph" at each of the 4 resolutions). (L x)_i = x_i - mean of its neighbours
//    is a length (the differential coordinate), independent of valence and
//    comparable across resolutions; rows sum to 0; not symmetric.
//  * graph_laplacian(combinatorial), D - A: symmetric positive semi-definite,
//    so its eigenvectors are orthonormal; valence-weighted, hence not a length.
//  * cotangent_stiffness K (with lumped_mass M): the discretised Dirichlet
//    energy, geometry-aware; symmetric PSD with constants in its kernel. The
//    spectral basis (drape/spectral/spectral.hpp) uses K by default: see there why.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace drape::geometry {

enum class GraphLaplacian {
  random_walk,    // I - D^-1 A (isolated vertices get a zero row)
  combinatorial,  // D - A
};

Eigen::SparseMatrix<double, Eigen::RowMajor> graph_laplacian(const Eigen::MatrixX3i& faces, int num_vertices,
                                                             GraphLaplacian kind = GraphLaplacian::random_walk);

// K_ij = -(cot a_ij + cot b_ij) / 2 for an edge ij with opposite angles a, b,
// K_ii = -sum_j K_ij. Cotangents are clamped to [-1e3, 1e3] so that a sliver
// cannot dominate. Symmetric, positive semi-definite, rows sum to 0.
Eigen::SparseMatrix<double> cotangent_stiffness(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

// Barycentric lumped mass: a third of the area of each adjacent face.
Eigen::VectorXd lumped_mass(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i& faces);

}  // namespace drape::geometry
