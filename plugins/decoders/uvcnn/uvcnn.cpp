// The seed's 2D CNN decoder ablation (Table 6.2, after [124]): the garment's
// per-vertex features are rasterised into a square UV image (every pattern
// panel in its own tile, uv_raster.hpp), convolved by a few same-size 2D
// convolutions (im2col + GEMM, conv2d.hpp), the last one linear to 3 channels,
// and the image is sampled back at every vertex's UV position. Rasterising and
// sampling are fixed sparse matrices R [pixels, Ng] and S [Ng, pixels] built
// from the template, so out = S conv(R x) and the backward pass multiplies by
// their transposes.
#include "conv2d.hpp"
#include "uv_raster.hpp"

#include <drape/assets/assets.hpp>
#include <drape/nn/layer_stack.hpp>
#include <drape/plugin.hpp>

#include <string>
#include <vector>

namespace {

using namespace drape;
using namespace drape::uvcnn;

class UvCnn final : public Node {
 public:
  UvCnn(int resolution, std::vector<long> channels, int kernel, nn::Activation activation)
      : resolution_(resolution), channels_(std::move(channels)), kernel_(kernel), activation_(activation) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets || !context.assets->garment)
      throw ConfigError("uvcnn needs the garment's UV layout, but no garment template is bound to this graph");
    const Mesh& mesh = context.assets->garment->mesh;
    const Shape x = in.at("x");
    if (x.rows != mesh.num_vertices() || x.cols < 1)
      throw ConfigError("input 'x' must be [" + std::to_string(mesh.num_vertices()) +
                        ", C] (features per garment vertex), got " + x.str());
    raster_ = build_uv_raster(mesh, resolution_);
    raster_t_ = SparseRM(raster_.rasterise.transpose());
    sample_t_ = SparseRM(raster_.sample.transpose());
    vertices_ = x.rows;
    in_channels_ = x.cols;
    layers_.clear();
    int c = x.cols;
    for (long out : channels_) {
      layers_.emplace_back(Conv2dGeometry{resolution_, c, kernel_}, static_cast<int>(out), activation_);
      c = static_cast<int>(out);
    }
    layers_.emplace_back(Conv2dGeometry{resolution_, c, kernel_}, 3, nn::Activation{});
    nn::create_stack_weights(*this, layers_, "conv", context.seed);
    return {{"out", {vertices_, 3}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    const int batch = x.batch();
    const Eigen::Index pixels = raster_.rasterise.rows();
    MatrixRM image(batch * pixels, in_channels_);
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) image.middleRows(b * pixels, pixels).noalias() = raster_.rasterise * x.mat(b);
    const MatrixRM* h = &nn::forward_stack(layers_, image, batch);
    Tensor& y = *out.at("out");
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) y.mat(b).noalias() = raster_.sample * h->middleRows(b * pixels, pixels);
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& gy = *gout.at("out");
    const int batch = gy.batch();
    const Eigen::Index pixels = raster_.rasterise.rows();
    MatrixRM g(batch * pixels, 3);
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) g.middleRows(b * pixels, pixels).noalias() = sample_t_ * gy.mat(b);
    const auto gx = gin.find("x");
    nn::backward_stack(layers_, g, batch, gx != gin.end());
    if (gx == gin.end()) return;
    Tensor& gxt = *gx->second;
#pragma omp parallel for schedule(static) if (batch > 1)
    for (int b = 0; b < batch; ++b) gxt.mat(b).noalias() = raster_t_ * g.middleRows(b * pixels, pixels);
  }

  double flops_per_sample() const override {
    return nn::stack_flops(layers_,
                           double(raster_.rasterise.nonZeros()) * in_channels_ + double(raster_.sample.nonZeros()) * 3.0);
  }

 private:
  int resolution_;
  std::vector<long> channels_;
  int kernel_;
  nn::Activation activation_;
  UvRaster raster_;
  SparseRM raster_t_, sample_t_;  // transposes, row-major for the backward products
  int vertices_ = 0, in_channels_ = 0;
  std::vector<Conv2dLayer> layers_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "decoder";
  d.name = "uvcnn";
  d.doc = "2D CNN in UV space (the seed's 2D CNN decoder ablation): per-vertex features rasterised into a UV image, "
          "convolved, sampled back at the vertices.";
  d.inputs = {{"x", "per-garment-vertex features [Ng, C]"}};
  d.outputs = {{"out", "garment vertices or offsets [Ng, 3]"}};
  d.params = {{.name = "resolution", .type = ParamType::Int, .default_value = "64",
               .doc = "side of the square UV image in pixels", .min = 8, .max = 1024},
              {.name = "channels", .type = ParamType::IntList, .default_value = "[16, 16]",
               .doc = "output channels of the hidden convolutions (may be empty: [])", .min = 1, .max = 4096},
              {.name = "kernel", .type = ParamType::Int, .default_value = "3",
               .doc = "odd kernel size", .min = 1, .max = 15},
              nn::activation_param("leaky_relu"),
              nn::negative_slope_param()};
  d.create_node = [](const Params& p) {
    const long kernel = p.get_int("kernel");
    if (kernel % 2 == 0) throw ConfigError("parameter 'kernel' must be odd, got " + std::to_string(kernel));
    return std::make_unique<UvCnn>(static_cast<int>(p.get_int("resolution")), p.get_int_list("channels"),
                                   static_cast<int>(kernel), nn::activation_from(p));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
