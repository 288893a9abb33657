#pragma once
// Pictures of drapes for people to look at: meshes drawn in an orthographic
// front view (x to the right, y up, seen from +z, the bodies' facing
// direction), one panel per drape, written as a single SVG file. Triangles are
// sorted back to front (painter's algorithm) and flat-shaded by a light from
// the viewer, so shapes read as 3D; a layer is either one colour or a value
// per vertex through a colour map, with a colour bar.
#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace drape {

struct SvgLayer {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  std::string colour = "#b8b8b8";          // used when `values` is empty
  Eigen::VectorXd values;                  // per vertex (face colour: the mean of its corners)
  bool cull_back_faces = false;            // true for closed meshes (a body): halves the file
  // m towards the viewer when sorting: cloth lies within millimetres of the
  // skin, closer than the body's triangles are long, so without it skin pokes through.
  double depth_bias = 0;
  // Sorted by its farthest corner instead of its centre: a layer under
  // another (the body under the cloth), whose triangles can be longer than
  // the gap is deep (a heavy body's 4 cm faces under cloth 5 mm off them
  // showed through the cloth as specks with the centre and the bias alone).
  bool under = false;
};

struct SvgPanel {
  std::string title;
  std::vector<SvgLayer> layers;
};

struct SvgColourScale {
  SvgColourScale() = default;
  SvgColourScale(std::string label, double lo, double hi, std::string below_label = "")
      : label(std::move(label)), lo(lo), hi(hi), below_label(std::move(below_label)) {}
  std::string label;  // e.g. "error (cm)"
  double lo = 0, hi = 1;
  // Non-empty: a face whose value is below lo is drawn in `below_colour`
  // ("#rrggbb", outside the colour map) and the legend names it, instead of
  // taking lo's colour: cloth inside the body looked like a tight fit.
  std::string below_label;
  std::string below_colour = "#e4002b";
};

class SvgFigure {
 public:
  explicit SvgFigure(std::string title) : title_(std::move(title)) {}
  void add_panel(SvgPanel panel) { panels_.push_back(std::move(panel)); }
  const std::vector<SvgPanel>& panels() const { return panels_; }
  // A line under the title: what the command printed about its input ("note:
  // the body was moved ...", "warning: outside the model's training domain"),
  // so the picture says it too. Lines starting "warning:" are drawn in red.
  void add_note(std::string note) { notes_.push_back(std::move(note)); }
  const std::vector<std::string>& notes() const { return notes_; }
  // The range of the `values` of every layer (values outside are clamped).
  void set_colour_scale(SvgColourScale scale) { scale_ = std::move(scale); }
  const std::string& title() const { return title_; }
  const std::optional<SvgColourScale>& colour_scale() const { return scale_; }
  std::string svg() const;
  // Each face's colour (0-255 channels, unshaded): the layer's colour, or the
  // colour map at the mean of its corners' values over the colour scale.
  // Error when a layer has values for another number of vertices.
  std::vector<std::array<double, 3>> face_colours(const SvgLayer& layer) const;
  // The same figure as a self-contained HTML page with a 3D viewer (figure_html.cpp):
  // drag to turn each drape, wheel to zoom; no network, no WebGL.
  std::string html() const;
  // Atomically (atomic_file.hpp): HTML when the file ends in .html or .htm, else SVG.
  void write(const std::filesystem::path& file) const;

 private:
  std::string title_;
  std::vector<SvgPanel> panels_;
  std::vector<std::string> notes_;
  std::optional<SvgColourScale> scale_;
};

// Viridis, approximated by linear segments; t in [0, 1] -> "#rrggbb".
std::string colour_map(double t);
// The same as 0-255 channels.
std::array<double, 3> colour_map_rgb(double t);

struct Mesh;
// One drape as a panel: the body (skin colour, back faces culled) and the
// garment coloured by a value per vertex, drawn a little in front of the skin.
SvgPanel drape_panel(const std::string& caption, const Mesh& body, const Mesh& garment, Eigen::VectorXd garment_values);
// The garment's signed distance to the body in cm: 0 to 5, a face inside
// the body in the below colour, named (drape_figure's, drape render's).
SvgColourScale clearance_scale();
// One drape as a figure: the body, and the garment coloured by its signed
// distance to the body (0 to 5 cm; a face inside the body in red, named in
// the legend, drawn over the skin so it shows).
SvgFigure drape_figure(const std::string& title, const std::string& caption, const Mesh& body, const Mesh& garment);

}  // namespace drape
