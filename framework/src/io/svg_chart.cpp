#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/svg_chart.hpp>

#include "xml_escape.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape {

namespace {

constexpr double kWidth = 640, kHeight = 420, kLeft = 70, kRight = 30, kTop = 40, kBottom = 56;

std::string svg_number(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

std::string ScatterChart::svg() const {
  if (points.empty()) throw Error("chart: no points");
  auto tx = [&](double x) {
    if (log_x && !(x > 0)) throw Error("chart: x = " + svg_number(x) + " on a log axis");
    return log_x ? std::log10(x) : x;
  };
  double x0 = 1e300, x1 = -1e300, y1 = 0;
  for (const ChartPoint& p : points) {
    x0 = std::min(x0, tx(p.x));
    x1 = std::max(x1, tx(p.x));
    y1 = std::max(y1, p.y);
  }
  if (log_x) {
    x0 = std::floor(x0);
    x1 = std::max(std::ceil(x1), x0 + 1);
  } else if (x1 <= x0) {
    x1 = x0 + 1;
  }
  y1 = y1 > 0 ? 1.15 * y1 : 1;
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  auto px = [&](double x) { return kLeft + (tx(x) - x0) / (x1 - x0) * w; };
  auto py = [&](double y) { return kTop + h - y / y1 * h; };

  std::ostringstream o;
  o.setf(std::ios::fixed);
  o.precision(1);
  // Points are numbered on the chart and labelled in a list under it: long
  // labels of points at similar heights would otherwise run into each other.
  const double legend_line = 16, height = kHeight + legend_line * static_cast<double>(points.size()) + 8;
  // The legend's lines can be longer than the plot is wide: the picture grows
  // to hold them (about 7 px a character at 12 px sans-serif, generous).
  std::size_t longest = 0;
  for (const ChartPoint& p : points) longest = std::max(longest, p.label.size() + 4);
  const double width = std::max(kWidth, kLeft + 7.0 * static_cast<double>(longest) + kRight);
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"" << kLeft << "\" y=\"22\" font-size=\"15\">" << xml_escaped(title) << "</text>\n";
  o << "<path d=\"M" << kLeft << " " << kTop << "V" << kTop + h << "H" << kLeft + w << "\" stroke=\"black\" fill=\"none\"/>\n";
  // x ticks: decades on a log axis, 5 even steps otherwise.
  const int steps = log_x ? static_cast<int>(x1 - x0) : 5;
  for (int i = 0; i <= steps; ++i) {
    const double t = x0 + (x1 - x0) * i / steps;
    const double value = log_x ? std::pow(10.0, t) : t;
    const double x = kLeft + (t - x0) / (x1 - x0) * w;
    o << "<path d=\"M" << x << " " << kTop + h << "v5\" stroke=\"black\"/><text x=\"" << x << "\" y=\"" << kTop + h + 18
      << "\" text-anchor=\"middle\">" << svg_number(value) << "</text>\n";
    if (i > 0) o << "<path d=\"M" << x << " " << kTop << "V" << kTop + h << "\" stroke=\"#e4e4e4\"/>\n";
  }
  for (int i = 0; i <= 4; ++i) {
    const double value = y1 * i / 4, y = py(value);
    o << "<path d=\"M" << kLeft - 5 << " " << y << "h5\" stroke=\"black\"/><text x=\"" << kLeft - 8 << "\" y=\"" << y + 4
      << "\" text-anchor=\"end\">" << svg_number(std::round(value * 100) / 100) << "</text>\n";
  }
  o << "<text x=\"" << kLeft + w / 2 << "\" y=\"" << kHeight - 14 << "\" text-anchor=\"middle\">" << xml_escaped(x_label)
    << (log_x ? " (log scale)" : "") << "</text>\n";
  o << "<text transform=\"translate(16 " << kTop + h / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escaped(y_label)
    << "</text>\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ChartPoint& p = points[i];
    const double x = px(p.x), y = py(p.y);
    o << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"5\" fill=\"#3b528b\"/>\n";
    const bool right_half = x > kLeft + w * 0.85;
    o << "<text x=\"" << (right_half ? x - 7 : x + 7) << "\" y=\"" << y - 6 << "\" font-weight=\"bold\""
      << (right_half ? " text-anchor=\"end\"" : "") << ">" << i + 1 << "</text>\n";
    o << "<text x=\"" << kLeft << "\" y=\"" << kHeight + legend_line * static_cast<double>(i) << "\"><tspan font-weight=\"bold\">"
      << i + 1 << "</tspan>  " << xml_escaped(p.label) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

void ScatterChart::write(const std::filesystem::path& file) const { write_text_atomically(file, svg()); }

}  // namespace drape
