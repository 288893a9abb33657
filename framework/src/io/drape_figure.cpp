#include <drape/geometry/closest_point.hpp>
#include <drape/mesh.hpp>
#include <drape/io/svg_figure.hpp>

namespace drape {

SvgPanel drape_panel(const std::string& caption, const Mesh& body, const Mesh& garment, Eigen::VectorXd garment_values) {
  return {caption,
          {SvgLayer{body.vertices, body.faces, "#c9b8a8", {}, true, 0.0, true},
           SvgLayer{garment.vertices, garment.faces, "", std::move(garment_values), false, 0.02}}};
}

SvgColourScale clearance_scale() { return {"distance of the garment to the body (cm)", 0.0, 5.0, "inside the body"}; }

SvgFigure drape_figure(const std::string& title, const std::string& caption, const Mesh& body, const Mesh& garment) {
  const geometry::BodySurface surface(body.vertices, body.faces);
  const Eigen::VectorXd clearance = 100.0 * surface.signed_distances(garment.vertices);
  SvgFigure figure(title);
  // Inside the body in a colour of its own: clamped to 0 it was the map's
  // darkest, and a shirt 81 % inside the body read as a tight fit (an
  // outside check). Drawn over the skin, as all the cloth is, so it shows.
  figure.add_panel(drape_panel(caption, body, garment, clearance));
  figure.set_colour_scale(clearance_scale());
  return figure;
}

}  // namespace drape
