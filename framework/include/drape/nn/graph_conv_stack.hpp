#pragma once
// A stack of graph convolutions that all read one fixed aggregation, the
// original GCN's (Kipf & Welling: D^-1/2 (A + I) D^-1/2 of a mesh's vertex
// graph), as the gcn encoder and gcn_decoder build it; and the passes through
// such a stack, where layer l reads the output of layer l - 1.
#include <drape/mesh.hpp>
#include <drape/nn/graph_conv.hpp>

#include <vector>

namespace drape::nn {

// One layer per entry of channels (its output width), the first taking `in` channels.
std::vector<GraphConvLayer> kipf_stack(const Mesh& mesh, int in, const std::vector<long>& channels,
                                       Activation activation);

// x [batch*n, in] through every layer in turn; the last layer's output.
const MatrixRM& forward_graph_stack(std::vector<GraphConvLayer>& layers, ConstMatRef x, int batch);
// g = dLoss/d(the last output) back through the layers (x: the last forward's
// input), accumulating their weight gradients; leaves dLoss/dx in g when
// want_input, otherwise the first layer skips it and g is not to be read.
void backward_graph_stack(std::vector<GraphConvLayer>& layers, ConstMatRef x, MatrixRM& g, int batch, bool want_input);

}  // namespace drape::nn
