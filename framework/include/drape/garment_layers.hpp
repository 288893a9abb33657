#pragma once
// A garment of several pieces (connected components: a T-shirt and jeans, a
// two-piece top) lies in layers. Dressing pushes every piece out to its
// clearance from the body on its own, so where one lies over another closer
// than that, the inner one is pushed through the outer -- the jeans'
// waistband through the T-shirt's hem of MakeHuman's male_casualsuit04, 120
// edge-face pairs in its drape at BMI 25 -- and the cloth's self-contact can
// only leave such places out. dress() ends by laying them in layers: of two pieces that come within `reach` of each other, the one
// closer to the body there is inside, and the outer one is moved out of it
// to `margin`, with the move spread over its neighbours as dress spreads its
// own. A garment of one piece is not touched.
#include <drape/energy.hpp>

namespace drape {

struct LayerOptions {
  double margin = 0.004;  // m: clearance left between an outer piece and the one inside it
  double reach = 0.03;    // m: an outer vertex farther than this from the inner piece is left alone
  int rounds = 30;
  int smoothing_steps = 2;
};

struct LayerReport {
  int pieces = 1;
  int moved = 0;      // vertices moved
  int crossings = 0;  // edges of one piece through faces of another left afterwards (0: in layers)
};

// Connected pieces by shared vertices: per face, its piece (0, 1, ... by first face).
std::vector<int> garment_pieces(const Eigen::MatrixX3i& faces, int vertex_count);

LayerReport separate_layers(Garment& garment, const BodyQuery& body, const LayerOptions& options = {});

}  // namespace drape
