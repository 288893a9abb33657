#include <drape/nn/graph_conv_stack.hpp>

#include <drape/geometry/adjacency.hpp>
#include <drape/nn/mesh_graph.hpp>

#include <memory>

namespace drape::nn {

std::vector<GraphConvLayer> kipf_stack(const Mesh& mesh, int in, const std::vector<long>& channels,
                                       Activation activation) {
  // One aggregation matrix, shared by the layers.
  const auto propagation = std::make_shared<const SparseOperator>(
      kipf_adjacency(geometry::vertex_neighbours(mesh.faces, mesh.num_vertices())));
  std::vector<GraphConvLayer> layers;
  int width_in = in;
  for (long width : channels) {
    layers.emplace_back(propagation, width_in, static_cast<int>(width), activation);
    width_in = static_cast<int>(width);
  }
  return layers;
}

namespace {

ConstMatRef input_of(const std::vector<GraphConvLayer>& layers, std::size_t l, ConstMatRef x) {
  return l == 0 ? x : ConstMatRef(layers[l - 1].output());
}

}  // namespace

const MatrixRM& forward_graph_stack(std::vector<GraphConvLayer>& layers, ConstMatRef x, int batch) {
  for (std::size_t l = 0; l < layers.size(); ++l) layers[l].forward(input_of(layers, l, x), batch);
  return layers.back().output();
}

void backward_graph_stack(std::vector<GraphConvLayer>& layers, ConstMatRef x, MatrixRM& g, int batch, bool want_input) {
  MatrixRM gx;
  for (std::size_t l = layers.size(); l-- > 0;) {
    layers[l].backward(input_of(layers, l, x), g, batch, l == 0 && !want_input ? nullptr : &gx);
    g.swap(gx);
  }
}

}  // namespace drape::nn
