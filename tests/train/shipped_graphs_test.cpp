// The shipped model graphs: graphs/drape.yaml (the seed's full model) and one
// file per row of the seed's Tables 6.1-6.3 in graphs/ablations/. Each must
// build on a real T-shirt template, run, and differ from the base in exactly
// the way its table row says; and so must the L2-trained MLP baseline.
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <optional>
#include <set>

#include "train_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

struct Row {
  const char* file;
  const char* encoder;  // type of node `encoder`
  const char* decoder;  // type of node `decoder`
  bool spectral;        // the spectral residual branch is there
  std::set<std::string> losses;
  double penetration_weight = 1.0;  // the penetration loss's weight, where there is one
  std::optional<double> penetration_margin{};  // its margin in m, where the file sets one
  double v2v_weight = 10.0;  // graphs/drape.yaml's, unless the row reweights it
  double l2_weight = 1.0;
};

const std::set<std::string> kSeedLosses = {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss"};

const Row kRows[] = {
    {"drape.yaml", "cnn1d", "msgcn", true, kSeedLosses},
    // Table 6.1
    {"ablations/encoders/pointnet.yaml", "pointnet", "msgcn", true, kSeedLosses},
    {"ablations/encoders/gcn.yaml", "gcn", "msgcn", true, kSeedLosses},
    {"ablations/encoders/gcn_learned.yaml", "gcn_learned", "msgcn", true, kSeedLosses},
    // Table 6.2
    {"ablations/decoders/uvcnn.yaml", "cnn1d", "uvcnn", true, kSeedLosses},
    {"ablations/decoders/mlp.yaml", "cnn1d", "mlp", true, kSeedLosses},
    {"ablations/decoders/cnn1d.yaml", "cnn1d", "cnn1d_decoder", true, kSeedLosses},
    {"ablations/decoders/gcn.yaml", "cnn1d", "gcn_decoder", true, kSeedLosses},
    {"ablations/decoders/msgcn_no_spectral.yaml", "cnn1d", "msgcn", false, kSeedLosses},
    // Table 6.3
    {"ablations/losses/base_l2.yaml", "cnn1d", "msgcn", true, {"l2"}},
    {"ablations/losses/l0_v2v.yaml", "cnn1d", "msgcn", true, {"v2v"}},
    {"ablations/losses/l1_direction.yaml", "cnn1d", "msgcn", true, {"v2v", "direction"}},
    {"ablations/losses/l2_laplacian.yaml", "cnn1d", "msgcn", true, {"v2v", "direction", "laplacian"}},
    {"ablations/losses/l3_edge.yaml", "cnn1d", "msgcn", true, {"v2v", "direction", "laplacian", "edge"}},
    {"ablations/losses/l4_spectral.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "laplacian", "edge", "spectral_loss"}},
    // The ME gap to the baseline (graphs/experiments/me_gap.yaml): V2V reweighted, and L2 in its place.
    {"ablations/losses/v2v_weight30.yaml", "cnn1d", "msgcn", true, kSeedLosses, 1.0, {}, 30.0},
    {"ablations/losses/v2v_weight100.yaml", "cnn1d", "msgcn", true, kSeedLosses, 1.0, {}, 100.0},
    {"ablations/losses/v2v_weight300.yaml", "cnn1d", "msgcn", true, kSeedLosses, 1.0, {}, 300.0},
    {"ablations/losses/l2_with_physics.yaml", "cnn1d", "msgcn", true,
     {"direction", "edge", "deformation", "laplacian", "spectral_loss", "l2"}, 1.0, {}, 10.0, 500.0},
    // Not the seed's: its full model with the template following the body.
    {"bodyspace/drape_follow.yaml", "cnn1d", "msgcn", true, kSeedLosses},
    {"bodyspace/drape_follow_penetration.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss", "penetration"}, 0.1},
    {"bodyspace/drape_follow_penetration_weight1.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss", "penetration"}, 1.0},
    {"bodyspace/drape_follow_penetration_weight3.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss", "penetration"}, 3.0},
    {"bodyspace/drape_follow_penetration_weight10.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss", "penetration"}, 10.0},
    {"bodyspace/drape_follow_penetration_weight100_margin6mm.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss", "penetration"}, 100.0, 0.006},
    // Not the seed's: its full model plus the penetration loss.
    {"ablations/losses/l6_penetration.yaml", "cnn1d", "msgcn", true,
     {"v2v", "direction", "edge", "deformation", "laplacian", "spectral_loss", "penetration"}},
    // The baseline of issue 5: MLP decoder, L2 alone.
    {"baselines/mlp_l2.yaml", "cnn1d", "mlp", false, {"l2"}},
};

const NodeSpec* node_named(const GraphSpec& spec, const std::string& name) {
  for (const auto& n : spec.nodes)
    if (n.name == name) return &n;
  return nullptr;
}

}  // namespace

TEST_CASE("every shipped model graph is its table row, builds on the T-shirt and gives a finite loss", "[graphs]") {
  const auto assets = tiny_assets();
  const int nb = assets->body.num_vertices(), ng = assets->garment->mesh.num_vertices();
  // The mean body and the template itself: a sample every graph can be run on.
  Tensor body(1, nb, 3), target(1, ng, 3);
  body.mat(0) = assets->body.vertices.cast<float>();
  target.mat(0) = assets->garment->mesh.vertices.cast<float>();
  // The template 1 cm lower and slightly squashed: a target every loss sees a difference to.
  Tensor moved_target = target;
  moved_target.mat(0).col(1).array() = moved_target.mat(0).col(1).array() * 0.98f - 0.01f;
  for (const Row& row : kRows) {
    INFO(row.file);
    const GraphSpec spec = parse_graph_file(source_dir() / "graphs" / row.file);
    REQUIRE(node_named(spec, "encoder"));
    REQUIRE(node_named(spec, "decoder"));
    CHECK(node_named(spec, "encoder")->type == row.encoder);
    CHECK(node_named(spec, "decoder")->type == row.decoder);
    CHECK((node_named(spec, "spectral") != nullptr) == row.spectral);
    std::set<std::string> losses;
    // The weights of graphs/drape.yaml (L_V2V and L_e 10, the rest 1), kept by every row but where it says.
    for (const auto& n : spec.nodes)
      if (n.is_loss) {
        losses.insert(n.type);
        if (n.type == "penetration") {
          const auto margin = n.params.find("margin");
          CHECK((margin != n.params.end()) == row.penetration_margin.has_value());
          if (margin != n.params.end() && row.penetration_margin)
            CHECK(margin->second.node.as<double>() == *row.penetration_margin);
        }
        CHECK(n.weight == (n.type == "v2v"           ? row.v2v_weight
                           : n.type == "edge"          ? 10.0
                           : n.type == "penetration"   ? row.penetration_weight
                           : n.type == "l2"            ? row.l2_weight
                                                       : 1.0));
      }
    CHECK(losses == row.losses);

    GraphOptions options;
    options.dims = assets->dims();
    options.assets = assets.get();
    options.seed = 1;
    // Gradient buffers are reused unzeroed; here they start as NaN, so every
    // node of every shipped graph must overwrite its input gradients.
    options.poison_gradient_buffers = true;
    Graph graph(spec, plugins(), options);
    graph.forward({{"body", body}, {"target", target}});
    CHECK(graph.output("garment").shape() == Shape{ng, 3});
    CHECK(std::isfinite(graph.loss()));
    CHECK(graph.flops_per_sample() > 0);
    graph.forward({{"body", body}, {"target", moved_target}});
    graph.backward();
    bool finite = true, moved = false;
    for (const auto& [name, w] : graph.weights()) {
      finite = finite && w->grad.vec().allFinite();
      moved = moved || w->grad.vec().cwiseAbs().maxCoeff() > 0;
    }
    CHECK(finite);
    CHECK(moved);
  }
}

TEST_CASE("the full model's prediction starts at the template and its first steps lower the loss", "[graphs][train]") {
  const auto assets = tiny_assets();
  TempDir dir;
  write_tiny_dataset(dir.path() / "data.h5", 16, 12, 4);
  TrainOptions o = tiny_training(dir.path() / "data.h5", dir.path() / "model.h5");
  o.graph = source_dir() / "graphs/drape.yaml";
  o.epochs = 8;
  o.patience = 100;
  std::ostringstream log;
  o.log = &log;
  const TrainReport r = train(plugins(), o);
  INFO(log.str());
  CHECK(r.finished);
  // Epoch lines hold the validation loss; the best one must beat the first.
  CHECK(r.best_epoch > 1);
}

TEST_CASE("drape_follow: the garment is the template moved with its body vertices plus what the network predicts",
          "[graphs]") {
  const auto assets = tiny_assets();
  TempDir dir;
  // The same graph with the network's two terms as outputs too.
  std::ofstream(dir.path() / "probe.yaml") << "base: " << (source_dir() / "graphs/bodyspace/drape_follow.yaml").string()
                                           << "\noutputs: { garment: garment, decoded: decoder, residual: spectral.out }\n";
  GraphOptions options;
  options.dims = assets->dims();
  options.assets = assets.get();
  options.seed = 3;
  Graph graph(parse_graph_file(dir.path() / "probe.yaml"), plugins(), options);
  const int nb = assets->body.num_vertices(), ng = assets->garment->mesh.num_vertices();
  // A body unlike the mean one: every vertex moved by its own amount.
  Eigen::MatrixX3d shift(nb, 3);
  for (int v = 0; v < nb; ++v) shift.row(v) << 0.01 * std::sin(v), 0.02 * std::cos(0.5 * v), -0.005 * (v % 7);
  Tensor body(1, nb, 3), target(1, ng, 3);
  body.mat(0) = (assets->body.vertices + shift).cast<float>();
  target.mat(0) = assets->garment->mesh.vertices.cast<float>();
  graph.forward({{"body", body}, {"target", target}});
  const Eigen::MatrixX3d garment = graph.output("garment").mat(0).cast<double>(),
                         network = (graph.output("decoded").mat(0) + graph.output("residual").mat(0)).cast<double>();
  REQUIRE(static_cast<int>(assets->correspondence.size()) == ng);
  double worst = 0;
  for (int i = 0; i < ng; ++i) {
    const Eigen::RowVector3d expected = assets->garment->mesh.vertices.row(i) +
                                        shift.row(assets->correspondence[static_cast<std::size_t>(i)]) + network.row(i);
    worst = std::max(worst, (garment.row(i) - expected).norm());
  }
  CHECK(worst < 1e-5);  // float rounding of ~1 m coordinates
  CHECK(shift.cwiseAbs().maxCoeff() > 0.01);
}
