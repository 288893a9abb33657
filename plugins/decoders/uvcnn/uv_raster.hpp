#pragma once
// The fixed linear maps between a garment's vertices and a square UV image:
// rasterise ([pixels, Ng]) and sample ([Ng, pixels]). Both are sparse and
// depend on the template only, so the decoder's gradients through them are
// their transposes.
//
// Layout. Every UV chart (pattern panel) gets its own tile of a grid over the
// image, all charts at one scale (pixels per meter of material space, so a
// convolution kernel covers the same cloth everywhere), centred in its tile
// with a one-pixel border; the grid shape is the one with the largest scale.
// A vertex on a seam has one UV per chart and so a position in each tile.
//
// Rasterise. Each vertex position is splatted bilinearly onto its four nearest
// pixel centres; a pixel's value is the splat-weighted mean of the vertices
// that reach it. Pixels inside a UV triangle that no splat reaches (a mesh
// coarser than the image) take the barycentric interpolation of that
// triangle's corners. Other pixels are 0 (background).
//
// Sample. Each vertex reads the image bilinearly at its position(s), averaged
// over its charts.
#include <drape/mesh.hpp>

#include <Eigen/SparseCore>

#include <vector>

namespace drape::uvcnn {

using SparseRM = Eigen::SparseMatrix<float, Eigen::RowMajor>;

struct UvRaster {
  int resolution = 0;       // the image is resolution x resolution, pixel (row, col) -> row * resolution + col
  int charts = 0;
  int grid_rows = 0, grid_cols = 0;
  double pixels_per_meter = 0;  // scale of material space in the image
  SparseRM rasterise;       // [resolution^2, vertices]
  SparseRM sample;          // [vertices, resolution^2]
  int covered_pixels = 0;   // pixels with a value (rows of rasterise that are not empty)
};

// Throws ConfigError when the mesh has no UVs or a chart has no extent.
UvRaster build_uv_raster(const Mesh& garment, int resolution);

}  // namespace drape::uvcnn
