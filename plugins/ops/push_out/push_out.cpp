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
// With `untangle` (the default) the garment's crossings of itself are then
// undone (geometry::Untangler: the patch each closed intersection curve cuts
// off moved back through the cloth it went through, an open curve's edge and
// face pulled apart) and each round's moves pushed off the body again: the
// push-out keeps the cloth off the body, not off itself, and a heavy body's
// sleeve predicted through the shirt's side is what it leaves.
// With `strain_limit` s > 0, before all that, every garment edge longer than
// (1 + s) times its rest length is shortened to it (geometry::limit_strain):
// the skinning stretches a raised arm's underarm where cloth would not. The
// rest lengths are those of the garment of the input `grade` (when it is
// connected): the model's size of that grade (its size chart's pattern,
// NodeContext::garment_sizes, built when a body first wears it), else the
// bound template's material space graded by it (grade_material). A model
// of drapes in each body's own size must connect it (its graph's
// garment_grade), or a 5xlarge shirt is held to the design size's lengths. The limit must lie above the simulations' own
// strain (the shipped sized data: 44-56 % at worst over 4,700 drapes), or
// it pulls a tight shirt into the body.
// `mirror_average` is the model's (Model::predict), kept among this node's
// parameters because it changes what this node is fed and nothing else:
// `drape model set post.mirror_average=true` and `--set` turn it on and off.
#include <drape/assets/assets.hpp>
#include <drape/garment_grading.hpp>
#include <drape/garment_sizes.hpp>
#include <drape/geometry/garment_clearance.hpp>
#include <drape/geometry/strain_limit.hpp>
#include <drape/plugin.hpp>

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace drape;

// Rounds of the strain limit after the push-out, each followed by the
// push-out of what it moved, until no edge is strained beyond the limit by
// more than kLimitSlack: the limit and the push-out pull against each other
// where an edge runs over the body. Each sweep shortens only edges beyond
// half that slack: exactly, a heavy posed body took three rounds of 41-47
// sweeps (0.73 -> 0.65 -> 0.62 -> 0.60); so, one round of 4. The heaviest
// body of the human rig's posed held-out set (BMI 62.8) kept 0.80 after 3
// rounds, 0.65 after 8.
constexpr int kLimitRounds = 8;
constexpr int kLimitSweeps = 50;
constexpr double kLimitSlack = 0.05;

class PushOut final : public Node {
 public:
  PushOut(double epsilon, bool enabled, bool edges, bool untangle, double strain_limit)
      : epsilon_(epsilon), enabled_(enabled), lift_edges_(edges), untangle_(untangle), strain_limit_(strain_limit) {}

  ShapeMap setup(const ShapeMap& in, const NodeContext& context) override {
    if (!context.assets) throw ConfigError("push_out needs the body's faces: no template assets are bound");
    faces_ = context.assets->body.faces;
    clearance_.reset();
    rest_lengths_.clear();
    sizes_.reset();
    garment_.reset();
    geometry::GarmentClearanceOptions clearing;
    clearing.margin = epsilon_;
    clearing.lift_edges = lift_edges_;
    clearing.untangle = untangle_;
    if (lift_edges_ || untangle_ || strain_limit_ > 0) {
      const std::string which = lift_edges_ ? "edges: true" : untangle_ ? "untangle: true" : "strain_limit";
      if (!context.assets->garment) throw ConfigError("push_out with " + which + " needs the garment's faces: no garment is bound");
      const int garment_vertices = context.assets->garment->mesh.num_vertices();
      if (in.at("x").rows != garment_vertices)
        throw ConfigError("push_out with " + which + ": input 'x' has " + std::to_string(in.at("x").rows) +
                          " rows, the bound garment " + std::to_string(garment_vertices) +
                          " vertices (edges: false and untangle: false push out the vertices of any mesh)");
      garment_ = context.assets->garment;
      clearance_.emplace(garment_->mesh.faces, garment_vertices, clearing);
      if (strain_limit_ > 0) {
        // A garment without UVs is refused here, not at the first body
        // (without building a size of the model's chart).
        if (!garment_->mesh.has_uv())
          throw ConfigError("push_out with strain_limit needs the garment's material space (UVs); the bound garment has none");
        // A model of drapes in each body's own size: each size's own
        // pattern, built when a body first wears it.
        sizes_ = context.garment_sizes;
      }
    }
    if (const auto grade = in.find("grade"); grade != in.end() && (grade->second.rows != 1 || grade->second.cols != 1))
      throw ConfigError("input 'grade' must be [1, 1] (the garment's grade), got " + grade->second.str());
    // The vertices of any mesh: no faces, so no edges nor untangle.
    if (!clearance_) clearance_.emplace(Eigen::MatrixX3i(0, 3), in.at("x").rows, clearing);
    surface_.reset();  // built again for these faces at the next forward
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
      const std::vector<double>* rest = nullptr;
      if (strain_limit_ > 0) {
        const auto grade = in.find("grade");
        rest = &rest_for(grade != in.end() ? (*grade->second)(b, 0, 0) : 1.0f);
        geometry::limit_strain(points, clearance_->edges(), *rest, strain_limit_, kLimitSweeps, kLimitSlack / 2);
      }
      clearance_->push_out(*surface_, points);
      // The push-out stretches again the edges whose ends it moved apart (a
      // vertex deep in the body lifted out, its neighbour left where it was):
      // limited again, and what that moved pushed out again (kLimitRounds).
      for (int round = 0; rest && round < kLimitRounds; ++round) {
        const std::vector<std::array<int, 2>>& edges = clearance_->edges();
        if (geometry::worst_strain(points, edges, *rest) <= strain_limit_ + kLimitSlack) break;
        std::vector<char> moved(static_cast<std::size_t>(points.rows()), 0);
        if (geometry::limit_strain(points, edges, *rest, strain_limit_, kLimitSweeps, kLimitSlack / 2, &moved).shortened == 0)
          break;
        clearance_->push_out_moved(*surface_, points, moved);
      }
      // The template dressed on the mean body: where two layers the network
      // pinched through each other belong (UntangleOptions::rest).
      // (Nothing when the node's untangle is off: the clearance was made without it.)
      if (garment_) clearance_->untangle(*surface_, points, &garment_->mesh.vertices);
      y.mat(b) = points.cast<float>();
    }
  }

  // The rest length of each edge of the garment of grade g: the model's size
  // of that grade, else the template graded by g (cached: a model's sizes
  // are a dozen grades). A size's pattern is not the template graded alike:
  // on the T-shirt's sizes their edges differ by -33 to +48 % (3xsmall,
  // 6xlarge).
  const std::vector<double>& rest_for(float g) {
    if (const auto it = rest_lengths_.find(g); it != rest_lengths_.end()) return it->second;
    std::vector<double> lengths;
    if (const std::optional<std::size_t> size = sizes_ ? sizes_->find(g) : std::nullopt) {
      lengths = geometry::material_edge_lengths(sizes_->material(*size), clearance_->edges());
    } else {
      Mesh graded = garment_->mesh;
      grade_material(graded, static_cast<double>(g));
      lengths = geometry::material_edge_lengths(graded, clearance_->edges());
    }
    return rest_lengths_.emplace(g, std::move(lengths)).first->second;
  }

  void backward(const TensorIn&, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    if (auto g = gin.find("x"); g != gin.end()) g->second->vec() = gout.at("out")->vec();  // straight through
  }

 private:
  double epsilon_;
  bool enabled_;
  bool lift_edges_;
  bool untangle_;
  double strain_limit_;  // 0: off
  // The bound garment (shared with the assets), when edges, untangle or
  // strain_limit: its faces, its template (the untangle's rest) and its
  // material space (the strain limit's rest lengths).
  std::shared_ptr<const Garment> garment_;
  std::shared_ptr<const GarmentSizes> sizes_;          // the model's sizes, when strain_limit_ > 0 (may be null)
  std::map<float, std::vector<double>> rest_lengths_;  // of the clearance's edges, by grade: the grades met so far
  Eigen::MatrixX3i faces_;                              // the body's
  // The garment's push-out and untangle (with its edges, and each vertex's
  // closest face on the last body); of faceless vertices when no garment is
  // needed.
  std::optional<geometry::GarmentClearance> clearance_;
  std::optional<geometry::BodySurface> surface_;  // the last body's, refitted to the next
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "push_out";
  d.doc = "TailorNet's post-processing: garment vertices inside the body (or within epsilon) moved to epsilon outside.";
  d.inputs = {{"x", "garment vertices [Ng, 3]"},
              {"body", "body vertices [Nb, 3] of the bound template's topology"},
              {.name = "grade", .doc = "the garment's grade [1, 1] (a sized graph's garment_grade), for strain_limit's rest lengths",
               .optional = true}};
  d.outputs = {{"out", "the garment with no vertex inside the body [Ng, 3]"}};
  d.params = {{.name = "epsilon", .type = ParamType::Float, .default_value = "0.002",
               .doc = "clearance in m a pushed vertex gets", .min = 0.0, .max = 0.1},
              {.name = "enabled", .type = ParamType::Bool, .default_value = "true",
               .doc = "false: pass the garment through unchanged"},
              {.name = "edges", .type = ParamType::Bool, .default_value = "true",
               .doc = "also lift each garment edge whose midpoint lies within epsilon / 2 of the body (the body's ridges "
                      "through the cloth between two cleared vertices)"},
              {.name = "untangle", .type = ParamType::Bool, .default_value = "true",
               .doc = "then undo the garment's crossings of itself (each patch a closed intersection curve cuts off moved "
                      "back through the cloth it went through, 1 mm beyond) each round's moves pushed out again, 6 rounds at most"},
              {.name = "mirror_average", .type = ParamType::Bool, .default_value = "false",
               .doc = "read by the model, not by this node: the network also drapes each body in its mirrored pose, "
                      "and what this node is fed is the mean of the garment and that twin's reflection (a model of "
                      "posed drapes on drape's human pose space; the network's nodes that read the pose run twice)"},
              {.name = "strain_limit", .type = ParamType::Float, .default_value = "0",
               .doc = "> 0: first shorten every garment edge longer than (1 + strain_limit) times its rest length (the "
                      "template's material space, graded by the input grade) to that length; 0: off",
               .min = 0.0, .max = 10.0}};
  d.create_node = [](const Params& p) {
    return std::make_unique<PushOut>(p.get_float("epsilon"), p.get_bool("enabled"), p.get_bool("edges"),
                                     p.get_bool("untangle"), p.get_float("strain_limit"));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
