#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/svg_figure.hpp>

#include "xml_escape.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace drape {

namespace {

constexpr double kPanelWidth = 300, kPanelHeight = 420, kMargin = 12, kTitleHeight = 34, kBarHeight = 60;
constexpr double kNoteHeight = 18;  // one line of notes under the title

std::array<double, 3> rgb_of(const std::string& hex) {
  unsigned r = 0, g = 0, b = 0;
  if (hex.size() != 7 || std::sscanf(hex.c_str(), "#%02x%02x%02x", &r, &g, &b) != 3)
    throw Error("svg: colour '" + hex + "' is not #rrggbb");
  return {double(r), double(g), double(b)};
}

std::string hex_of(const std::array<double, 3>& c) {
  char out[8];
  std::snprintf(out, sizeof out, "#%02x%02x%02x", int(std::clamp(c[0], 0.0, 255.0)), int(std::clamp(c[1], 0.0, 255.0)),
                int(std::clamp(c[2], 0.0, 255.0)));
  return out;
}

// About how wide a character of the sans-serif font is, per pixel of its size.
constexpr double kCharWidth = 0.55;
constexpr double kCaptionLine = 14;  // a panel caption's line (12 px text)

// `text` in lines of at most `chars` characters, broken at spaces (a word
// longer than a line stands alone): a panel's caption (the drape's figures,
// its crossings) ran past the picture's right edge.
std::vector<std::string> wrapped(const std::string& text, std::size_t chars) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string line;
  for (std::string word; words >> word;) {
    if (!line.empty() && line.size() + 1 + word.size() > chars) lines.push_back(line), line.clear();
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

struct Triangle {
  double depth;
  std::array<Eigen::Vector2d, 3> corners;  // in panel pixels
  std::string fill;
};

}  // namespace

// Viridis by linear segments, as 0-255 channels.
std::array<double, 3> colour_map_rgb(double t) {
  static const std::array<std::array<double, 3>, 5> stops = {{
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * (stops.size() - 1);
  const auto i = std::min<std::size_t>(static_cast<std::size_t>(t), stops.size() - 2);
  const double f = t - double(i);
  std::array<double, 3> c;
  for (int k = 0; k < 3; ++k) c[k] = (1 - f) * stops[i][k] + f * stops[i + 1][k];
  return c;
}

std::string colour_map(double t) { return hex_of(colour_map_rgb(t)); }

std::vector<std::array<double, 3>> SvgFigure::face_colours(const SvgLayer& l) const {
  const bool by_value = l.values.size() > 0;
  if (by_value && l.values.size() != l.vertices.rows())
    throw Error("figure: a layer has " + std::to_string(l.values.size()) + " values for " +
                std::to_string(l.vertices.rows()) + " vertices");
  std::vector<std::array<double, 3>> out(static_cast<std::size_t>(l.faces.rows()), by_value ? std::array<double, 3>{} : rgb_of(l.colour));
  if (!by_value) return out;
  for (Eigen::Index f = 0; f < l.faces.rows(); ++f) {
    const double v = (l.values(l.faces(f, 0)) + l.values(l.faces(f, 1)) + l.values(l.faces(f, 2))) / 3;
    out[static_cast<std::size_t>(f)] =
        scale_ && !scale_->below_label.empty() && v < scale_->lo
            ? rgb_of(scale_->below_colour)
            : colour_map_rgb(scale_ ? (v - scale_->lo) / std::max(scale_->hi - scale_->lo, 1e-30) : v);
  }
  return out;
}

std::string SvgFigure::svg() const {
  if (panels_.empty()) throw Error("svg: a figure needs at least one panel");
  // One scale for all panels, so drapes compare: the largest extent of any panel.
  double extent = 0, tallest = 0;
  for (const SvgPanel& p : panels_)
    for (const SvgLayer& l : p.layers)
      if (l.vertices.rows() > 0) {
        const Eigen::RowVector3d lo = l.vertices.colwise().minCoeff(), hi = l.vertices.colwise().maxCoeff();
        extent = std::max({extent, (hi(0) - lo(0)) / (kPanelWidth - 2 * kMargin), (hi(1) - lo(1)) / (kPanelHeight - 30)});
        tallest = std::max(tallest, hi(1) - lo(1));
      }
  if (!(extent > 0)) throw Error("svg: nothing to draw");
  const double scale = 1.0 / extent;
  // The panels' captions wrapped to their width: the drawing starts below the longest.
  const auto caption_chars = static_cast<std::size_t>((kPanelWidth - 8) / (12 * kCharWidth));
  std::size_t caption_lines = 1;
  for (const SvgPanel& p : panels_) caption_lines = std::max(caption_lines, wrapped(p.title, caption_chars).size());
  const double caption_extra = kCaptionLine * static_cast<double>(caption_lines - 1);
  const double panel_height = tallest * scale + 30 + caption_extra;  // the drawing, then the panel's title
  // The panels' width, or a line of kNoteChars characters of notes when that
  // is wider; the title and the notes wrapped to it (a warning of one line
  // made a one-panel picture 4,000 px wide and its drape a speck, and a long
  // title ran past the right edge: an outside check).
  constexpr double kNoteChars = 90;
  // At most kColumns panels a row (a grid of 16 sampled bodies was one row
  // 5,000 px wide: an outside check).
  constexpr std::size_t kColumns = 6;
  const std::size_t columns = std::min(panels_.size(), kColumns), rows = (panels_.size() + kColumns - 1) / kColumns;
  const double width = std::max(kMargin + static_cast<double>(columns) * (kPanelWidth + kMargin),
                                2 * kMargin + 12 * kCharWidth * kNoteChars);
  const std::vector<std::string> title_lines = wrapped(title_, static_cast<std::size_t>((width - 2 * kMargin) / (15 * kCharWidth)));
  std::vector<std::pair<std::string, bool>> note_lines;  // (a line, of a warning)
  for (const std::string& note : notes_)
    for (const std::string& line : wrapped(note, static_cast<std::size_t>((width - 2 * kMargin) / (12 * kCharWidth))))
      note_lines.emplace_back(line, note.rfind("warning:", 0) == 0);
  const double title_height = kTitleHeight + kNoteHeight * static_cast<double>(title_lines.size() - 1);
  const double notes_height = kNoteHeight * static_cast<double>(note_lines.size());
  const double panels_height = static_cast<double>(rows) * panel_height + static_cast<double>(rows - 1) * kMargin;
  const double height = title_height + notes_height + panels_height + (scale_ ? kBarHeight : 0) + kMargin;
  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(1);
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 "
    << width << " " << height << "\" font-family=\"sans-serif\">\n";
  o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  for (std::size_t i = 0; i < title_lines.size(); ++i)
    o << "<text x=\"" << kMargin << "\" y=\"" << 20 + kNoteHeight * static_cast<double>(i) << "\" font-size=\"15\">"
      << xml_escaped(title_lines[i]) << "</text>\n";
  for (std::size_t i = 0; i < note_lines.size(); ++i)
    o << "<text x=\"" << kMargin << "\" y=\"" << title_height + kNoteHeight * (static_cast<double>(i) + 0.5)
      << "\" font-size=\"12\" fill=\"" << (note_lines[i].second ? "#b00020" : "#444") << "\">"
      << xml_escaped(note_lines[i].first) << "</text>\n";

  const Eigen::Vector3d light = Eigen::Vector3d(0.3, 0.4, 1.0).normalized();

  for (std::size_t pi = 0; pi < panels_.size(); ++pi) {
    const SvgPanel& panel = panels_[pi];
    const double left = kMargin + static_cast<double>(pi % kColumns) * (kPanelWidth + kMargin),
                 top = title_height + notes_height + static_cast<double>(pi / kColumns) * (panel_height + kMargin);
    // Centre the panel's content horizontally, its top a little below the title.
    Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(1e30), hi = Eigen::RowVector3d::Constant(-1e30);
    for (const SvgLayer& l : panel.layers)
      if (l.vertices.rows() > 0) {
        lo = lo.cwiseMin(l.vertices.colwise().minCoeff());
        hi = hi.cwiseMax(l.vertices.colwise().maxCoeff());
      }
    const double cx = 0.5 * (lo(0) + hi(0));
    auto to_pixels = [&](const Eigen::RowVector3d& v) {
      return Eigen::Vector2d(left + kPanelWidth / 2 + (v(0) - cx) * scale, top + 24 + caption_extra + (hi(1) - v(1)) * scale);
    };
    std::vector<Triangle> triangles;
    for (const SvgLayer& l : panel.layers) {
      const std::vector<std::array<double, 3>> colours = face_colours(l);
      for (Eigen::Index f = 0; f < l.faces.rows(); ++f) {
        const Eigen::RowVector3d a = l.vertices.row(l.faces(f, 0)), b = l.vertices.row(l.faces(f, 1)),
                                 c = l.vertices.row(l.faces(f, 2));
        Eigen::Vector3d n = Eigen::Vector3d(b - a).cross(Eigen::Vector3d(c - a));
        if (!(n.norm() > 0)) continue;
        n.normalize();
        if (l.cull_back_faces && n.z() < 0) continue;
        // Two-sided lighting for open cloth, a floor so nothing turns black.
        const double shade = 0.45 + 0.55 * std::abs(n.dot(light));
        std::array<double, 3> rgb = colours[static_cast<std::size_t>(f)];
        for (double& ch : rgb) ch *= shade;
        const double depth = l.under ? std::min({a(2), b(2), c(2)}) : (a(2) + b(2) + c(2)) / 3;
        triangles.push_back({depth + l.depth_bias, {to_pixels(a), to_pixels(b), to_pixels(c)}, hex_of(rgb)});
      }
    }
    std::sort(triangles.begin(), triangles.end(), [](const Triangle& x, const Triangle& y) { return x.depth < y.depth; });
    o << "<g>\n";
    const std::vector<std::string> caption = wrapped(panel.title, caption_chars);
    for (std::size_t line = 0; line < caption.size(); ++line)
      o << "<text x=\"" << left + 4 << "\" y=\"" << top + 14 + kCaptionLine * static_cast<double>(line)
        << "\" font-size=\"12\">" << xml_escaped(caption[line]) << "</text>\n";
    for (const Triangle& t : triangles) {
      o << "<path d=\"M" << t.corners[0].x() << " " << t.corners[0].y() << "L" << t.corners[1].x() << " "
        << t.corners[1].y() << "L" << t.corners[2].x() << " " << t.corners[2].y() << "Z\" fill=\"" << t.fill
        << "\" stroke=\"" << t.fill << "\" stroke-width=\"0.3\"/>\n";
    }
    o << "</g>\n";
  }
  if (scale_) {
    const double y = title_height + notes_height + panels_height + 8, x0 = kMargin, w = std::min(360.0, width - 2 * kMargin);
    o << "<defs><linearGradient id=\"cmap\">";
    o.precision(3);  // (the eighths, not 0.1, 0.2, 0.4: the faces' colours are the eighths')
    for (int i = 0; i <= 8; ++i) o << "<stop offset=\"" << i / 8.0 << "\" stop-color=\"" << colour_map(i / 8.0) << "\"/>";
    o << "</linearGradient></defs>\n";
    o << "<rect x=\"" << x0 << "\" y=\"" << y << "\" width=\"" << w << "\" height=\"12\" fill=\"url(#cmap)\"/>\n";
    o.precision(2);
    o << "<text x=\"" << x0 << "\" y=\"" << y + 28 << "\" font-size=\"11\">" << scale_->lo << "</text>\n";
    o << "<text x=\"" << x0 + w << "\" y=\"" << y + 28 << "\" font-size=\"11\" text-anchor=\"end\">&#8805; " << scale_->hi
      << "</text>\n";
    // The label on a line of its own: on a one-panel figure the bar is too short for it between the two ends.
    o << "<text x=\"" << x0 + w / 2 << "\" y=\"" << y + 42 << "\" font-size=\"11\" text-anchor=\"middle\">"
      << xml_escaped(scale_->label) << "</text>\n";
    // Beside the bar (a figure is at least 90 characters of notes wide: room for both).
    if (!scale_->below_label.empty())
      o << "<rect x=\"" << x0 + w + 12 << "\" y=\"" << y << "\" width=\"12\" height=\"12\" fill=\"" << scale_->below_colour
        << "\"/>\n<text x=\"" << x0 + w + 28 << "\" y=\"" << y + 11 << "\" font-size=\"11\">"
        << xml_escaped(scale_->below_label) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

void SvgFigure::write(const std::filesystem::path& file) const {
  const std::string ext = file.extension().string();
  write_text_atomically(file, ext == ".html" || ext == ".htm" ? html() : svg());
}

}  // namespace drape
