#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/svg_chart.hpp>

#include "xml_escape.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace drape {

namespace {

constexpr double kWidth = 640, kHeight = 420, kLeft = 70, kRight = 30, kTop = 40, kBottom = 56;

std::string svg_number(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

// A round step for about `count` ticks up to `top`: 1, 2 or 5 times a power of ten.
double round_step(double top, int count) {
  const double raw = top / count, decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= raw) return m * decade;
  return 10 * decade;
}

// Where a point's number goes: beside the point, on the side that overlaps
// the least of the numbers placed so far and of the points (numbers of
// points close together ran into each other, "1" and "09" read as "109": an
// outside check). A box is the number's extent in pixels.
struct Box {
  double x0, y0, x1, y1;
  double overlap(const Box& o) const {
    return std::max(0.0, std::min(x1, o.x1) - std::max(x0, o.x0)) * std::max(0.0, std::min(y1, o.y1) - std::max(y0, o.y0));
  }
};

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
  const double y_step = round_step(y1, 5);
  y1 = std::ceil(y1 / y_step - 1e-9) * y_step;  // the axis ends on a round tick
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
  const int y_ticks = static_cast<int>(std::lround(y1 / y_step));
  for (int i = 0; i <= y_ticks; ++i) {
    const double value = y_step * i, y = py(value);
    o << "<path d=\"M" << kLeft - 5 << " " << y << "h5\" stroke=\"black\"/><text x=\"" << kLeft - 8 << "\" y=\"" << y + 4
      << "\" text-anchor=\"end\">" << svg_number(std::round(value * 1e6) / 1e6) << "</text>\n";
  }
  o << "<text x=\"" << kLeft + w / 2 << "\" y=\"" << kHeight - 14 << "\" text-anchor=\"middle\">" << xml_escaped(x_label)
    << (log_x ? " (log scale)" : "") << "</text>\n";
  o << "<text transform=\"translate(16 " << kTop + h / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escaped(y_label)
    << "</text>\n";
  // The front: a dashed line through its points in x order.
  std::vector<std::pair<double, double>> front;
  for (const ChartPoint& p : points)
    if (p.on_front) front.emplace_back(px(p.x), py(p.y));
  std::sort(front.begin(), front.end());
  if (front.size() > 1) {
    o << "<path d=\"";
    for (std::size_t k = 0; k < front.size(); ++k) o << (k ? "L" : "M") << front[k].first << " " << front[k].second;
    o << "\" stroke=\"#d0553d\" stroke-dasharray=\"5 3\" fill=\"none\"/>\n";
  }
  std::vector<Box> taken;  // the points, then each number as it is placed
  for (const ChartPoint& p : points) taken.push_back({px(p.x) - 5, py(p.y) - 5, px(p.x) + 5, py(p.y) + 5});
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ChartPoint& p = points[i];
    const double x = px(p.x), y = py(p.y);
    o << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"5\" fill=\"#3b528b\"/>\n";
    // Candidate places (the text's anchor point, left-aligned or right-aligned): above right first, as before.
    const double text_width = 7.5 * static_cast<double>(std::to_string(i + 1).size()), text_height = 12;
    struct Place {
      double dx, dy;
      bool end;
    };
    const auto box_at = [&](const Place& c) {
      const double left = c.end ? x + c.dx - text_width : x + c.dx;
      return Box{left, y + c.dy - text_height + 2, left + text_width, y + c.dy + 2};
    };
    double best_cost = 1e300;
    Place best{7, -6, false};
    for (const Place c : {Place{7, -6, false}, Place{-7, -6, true}, Place{7, 16, false}, Place{-7, 16, true},
                          Place{9, 5, false}, Place{-9, 5, true}, Place{7, -18, false}, Place{-7, -18, true},
                          Place{7, 28, false}, Place{-7, 28, true}}) {
      const Box box = box_at(c);
      double cost = 0;
      for (const Box& t : taken) cost += t.overlap(box);
      if (box.x0 < kLeft || box.x1 > kLeft + w || box.y0 < kTop || box.y1 > kTop + h) cost += 1e4;  // off the plot
      if (cost < best_cost) best_cost = cost, best = c;
      if (cost == 0) break;
    }
    taken.push_back(box_at(best));
    o << "<text x=\"" << x + best.dx << "\" y=\"" << y + best.dy << "\" font-weight=\"bold\""
      << (best.end ? " text-anchor=\"end\"" : "") << ">" << i + 1 << "</text>\n";
    o << "<text x=\"" << kLeft << "\" y=\"" << kHeight + legend_line * static_cast<double>(i) << "\"><tspan font-weight=\"bold\">"
      << i + 1 << "</tspan>  " << xml_escaped(p.label) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

void ScatterChart::write(const std::filesystem::path& file) const { write_text_atomically(file, svg()); }

}  // namespace drape
