// `push_out`: TailorNet's post-processing -- every garment vertex inside the
// body, or closer to it than `epsilon`, is moved along the body's normal to
// `epsilon` outside (geometry::push_out: exact closest points on the body mesh
// of the bound template's faces and the sample's vertices, searched again
// where a move brought a vertex near another part of the body), and with
// `edges` (the default) each garment edge whose midpoint lies within
// epsilon / 2 of the body lifted off it, so the body's ridges do not poke
// through the cloth between two cleared vertices. Not a learnt layer: its backward
// passes the gradient straight through, so a graph may keep it in place while
// training, and `enabled: false` turns it off without changing the weights
// (drape eval --set post.enabled=true measures a model with and without it).
#include <drape/assets/assets.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/push_out.hpp>
#include <drape/plugin.hpp>

#include <array>
#include <optional>
#include <vector>

namespace {

using namespace drape;

class PushOut final : public Node {
 public:
  PushOut(double epsilon, bool enabled, bool edges) : epsilon_(epsilon), enabled_(enabled), lift_edges_(edges) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets) throw ConfigError("push_out needs the body's faces: no template assets are bound");
    faces_ = context.assets->body.faces;
    edges_.clear();
    if (lift_edges_) {
      if (!context.assets->garment) throw ConfigError("push_out with edges: true needs the garment's faces: no garment is bound");
      const int garment_vertices = context.assets->garment->mesh.num_vertices();
      if (in.at("x").rows != garment_vertices)
        throw ConfigError("push_out with edges: true: input 'x' has " + std::to_string(in.at("x").rows) +
                          " rows, the bound garment " + std::to_string(garment_vertices) +
                          " vertices (edges: false pushes out the vertices of any mesh)");
      edges_ = geometry::edge_list(context.assets->garment->mesh.faces);
    }
    surface_.reset();  // built again for these faces at the next forward
    closest_faces_.clear();
    const Shape body = in.at("body");
    if (body.rows != context.assets->body.num_vertices() || body.cols != 3)
      throw ConfigError("input 'body' must be [" + std::to_string(context.assets->body.num_vertices()) + ", 3], got " + body.str());
    if (in.at("x").cols != 3) throw ConfigError("input 'x' must be vertices [N, 3], got " + in.at("x").str());
    return {{"out", in.at("x")}};
  }

  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    Tensor& y = *out.at("out");
    y.vec() = x.vec();
    if (!enabled_) return;
    for (int b = 0; b < x.batch(); ++b) {
      // One surface for every body: building it (the face adjacency, the
      // hierarchy) cost three quarters of a push-out; a body of the same
      // topology only moves its vertices, so the hierarchy's boxes are
      // refitted and only the normals the closest points land on computed
      // (all of them cost as much as the searches); each search starts at
      // the face the last body's search ended on. Exact closest points and
      // the same bits either way (tests/geometry_queries/push_out_test.cpp).
      const Eigen::MatrixX3d body = in.at("body")->mat(b).cast<double>();
      if (surface_) surface_->update(body, geometry::BodySurface::Normals::on_demand);
      else surface_.emplace(body, faces_);
      Eigen::MatrixX3d points = x.mat(b).cast<double>();
      geometry::PushOutOptions options;
      options.margin = epsilon_;
      options.closest_faces = &closest_faces_;
      if (lift_edges_) options.edges = &edges_;
      geometry::push_out(*surface_, points, options);
      y.mat(b) = points.cast<float>();
    }
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (auto g = gin.find("x"); g != gin.end()) g->second->vec() = gout.at("out")->vec();  // straight through
  }

 private:
  double epsilon_;
  bool enabled_;
  bool lift_edges_;
  Eigen::MatrixX3i faces_;
  std::vector<std::array<int, 2>> edges_;  // the garment's, when lift_edges_
  std::optional<geometry::BodySurface> surface_;  // the last body's, refitted to the next
  std::vector<int> closest_faces_;                // the last body's closest face of each garment vertex
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "push_out";
  d.doc = "TailorNet's post-processing: garment vertices inside the body (or within epsilon) moved to epsilon outside.";
  d.inputs = {{"x", "garment vertices [Ng, 3]"}, {"body", "body vertices [Nb, 3] of the bound template's topology"}};
  d.outputs = {{"out", "the garment with no vertex inside the body [Ng, 3]"}};
  d.params = {{.name = "epsilon", .type = ParamType::Float, .default_value = "0.002",
               .doc = "clearance in m a pushed vertex gets", .min = 0.0, .max = 0.1},
              {.name = "enabled", .type = ParamType::Bool, .default_value = "true",
               .doc = "false: pass the garment through unchanged"},
              {.name = "edges", .type = ParamType::Bool, .default_value = "true",
               .doc = "also lift each garment edge whose midpoint lies within epsilon / 2 of the body (the body's ridges "
                      "through the cloth between two cleared vertices)"}};
  d.create_node = [](const Params& p) {
    return std::make_unique<PushOut>(p.get_float("epsilon"), p.get_bool("enabled"), p.get_bool("edges"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
