// `concat`: two tensors side by side, [R, Ca] and [R, Cb] -> [R, Ca + Cb]; a
// one-row `b` is repeated on every row. How a per-sample flag joins per-vertex
// features: the seed's size flag appended to the encoded body (Table 6.7,
// graphs/sizes/drape_size_flag.yaml).
#include <drape/plugin.hpp>

#include <algorithm>
#include <cstddef>

namespace {

using namespace drape;

class Concat final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext&) override {
    a_ = in.at("a");
    b_ = in.at("b");
    if (b_.rows != a_.rows && b_.rows != 1)
      throw ConfigError("cannot put " + b_.str() + " beside " + a_.str() + ": 'b' needs " + std::to_string(a_.rows) +
                        " rows or one (repeated)");
    return {{"out", {a_.rows, a_.cols + b_.cols}}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& a = *in.at("a");
    const Tensor& b = *in.at("b");
    Tensor& y = *out.at("out");
    // Row by row with plain copies: a copy of contiguous rows is memory-bound,
    // and Eigen's strided block assignment (and replicate) ran at a third of
    // that on the encoder's 6,490 x 65 features.
    const int ca = a_.cols, cb = b_.cols, cy = ca + cb;
    for (int s = 0; s < a.batch(); ++s) {
      const float* pa = a.mat(s).data();
      const float* pb = b.mat(s).data();
      float* py = y.mat(s).data();
      const bool repeated = b_.rows != a_.rows;
      for (int r = 0; r < a_.rows; ++r) {
        float* row = py + static_cast<std::ptrdiff_t>(r) * cy;
        std::copy_n(pa + static_cast<std::ptrdiff_t>(r) * ca, ca, row);
        std::copy_n(pb + (repeated ? 0 : static_cast<std::ptrdiff_t>(r) * cb), cb, row + ca);
      }
    }
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& g = *gout.at("out");
    for (int s = 0; s < g.batch(); ++s) {
      if (auto ga = gin.find("a"); ga != gin.end()) ga->second->mat(s) = g.mat(s).leftCols(a_.cols);
      if (auto gb = gin.find("b"); gb != gin.end()) {
        if (b_.rows == a_.rows)
          gb->second->mat(s) = g.mat(s).rightCols(b_.cols);
        else
          gb->second->mat(s) = g.mat(s).rightCols(b_.cols).colwise().sum();
      }
    }
  }

 private:
  Shape a_, b_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "concat";
  d.doc = "Two tensors side by side along the channels; a one-row second input is repeated on every row.";
  d.inputs = {{"a", "[R, Ca]"}, {"b", "[R, Cb] or [1, Cb] (repeated)"}};
  d.outputs = {{"out", "[R, Ca + Cb]"}};
  d.create_node = [](const Params&) { return std::make_unique<Concat>(); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
