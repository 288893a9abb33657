#pragma once
// A scatter chart as SVG, for trade-offs people read at a glance (accuracy
// against time): labelled points, a log-scale x axis when asked, decade ticks.
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

struct ChartPoint {
  double x = 0, y = 0;
  std::string label;
  bool on_front = false;  // joined to the other points on it by a dashed line, in x order (a Pareto front)
};

struct ScatterChart {
  std::string title, x_label, y_label;
  bool log_x = true;
  std::vector<ChartPoint> points;

  std::string svg() const;
  void write(const std::filesystem::path& file) const;  // atomically
};

}  // namespace drape
