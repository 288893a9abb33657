// Why a drape did not settle, in words (unsettled.hpp).
#include "unsettled.hpp"

#include "garment_region.hpp"

#include <drape/garment_layers.hpp>
#include <drape/scene/garment_size.hpp>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <vector>

namespace drape::scene_detail {

namespace {

// The height below which half of the garment's vertices lie (x not empty).
double median_height(const Eigen::MatrixX3d& x) {
  std::vector<double> heights(x.col(1).data(), x.col(1).data() + x.rows());
  const auto middle = heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2);
  std::nth_element(heights.begin(), middle, heights.end());
  return *middle;
}

const char* friction_advice(bool has_friction) {
  return has_friction ? "more friction than the scene's (the barrier's `friction`)" : "the barrier's `friction`, 0 by default";
}

}  // namespace

bool fell_off_body(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body) {
  return x.rows() > 0 && body.rows() > 0 && median_height(x) < body.col(1).minCoeff();
}

std::string pieces_slid_down(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& start_body, const Eigen::MatrixX3d& x,
                             const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces, bool has_friction) {
  if (start.rows() != x.rows() || x.rows() == 0 || start_body.rows() == 0 || body.rows() == 0) return "";
  const double sole0 = start_body.col(1).minCoeff(), height0 = start_body.col(1).maxCoeff() - sole0;
  const double sole = body.col(1).minCoeff(), height = body.col(1).maxCoeff() - sole;
  if (!(height0 > 0) || !(height > 0)) return "";
  const auto n = static_cast<int>(x.rows());
  const std::vector<int> face_piece = garment_pieces(faces, n);
  const std::size_t pieces = face_piece.empty() ? 0 : static_cast<std::size_t>(*std::max_element(face_piece.begin(), face_piece.end())) + 1;
  std::vector<int> piece(static_cast<std::size_t>(n), -1);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) piece[static_cast<std::size_t>(faces(f, k))] = face_piece[static_cast<std::size_t>(f)];
  // Each piece's drop in one pass over the vertices: the sum of its heights,
  // as shares of its body's height above the soles, at the start less now.
  struct Drop {
    double sum = 0;
    int count = 0, first = -1, last = -1;
  };
  std::vector<Drop> drops(pieces);
  for (int v = 0; v < n; ++v) {
    if (piece[static_cast<std::size_t>(v)] < 0) continue;  // (a vertex no face uses)
    Drop& d = drops[static_cast<std::size_t>(piece[static_cast<std::size_t>(v)])];
    d.sum += (start(v, 1) - sole0) / height0 - (x(v, 1) - sole) / height;
    if (d.count++ == 0) d.first = v;
    d.last = v;
  }
  std::string out;
  for (std::size_t p = 0; p < pieces; ++p) {
    const Drop& d = drops[p];
    if (d.count == 0 || !(d.sum / d.count > kSlidShare)) continue;
    const std::string which = pieces > 1 ? "piece " + std::to_string(p + 1) + " of " + std::to_string(pieces) : "the garment";
    char text[400];
    std::snprintf(text, sizeof text,
                  "%s (vertices %d-%d) slid %.2f m down the body from where it was put on, nothing holding it up (a "
                  "garment stays on only if it hangs from the shoulders, grips the body, or its contact has friction "
                  "enough: %s, a smaller size)",
                  which.c_str(), d.first, d.last, d.sum / d.count * height, friction_advice(has_friction));
    out += (out.empty() ? "" : "; ") + std::string(text);
  }
  return out;
}

std::string why_unsettled(const SimulationResult& result, const Eigen::MatrixX3d& x, double tolerance, int settle_steps,
                          double at_rest_limit, double ease, const Eigen::MatrixX3d& body, bool sized, bool has_friction) {
  if (fell_off_body(x, body)) {
    char fell[400];
    std::snprintf(fell, sizeof fell,
                  "the garment fell off the body: half of it or more is below the body's lowest point (its middle %.2f m "
                  "below the soles after %d settling steps). Nothing held it up: a garment stays on only if it hangs from the "
                  "shoulders, grips the body tightly enough, or its contact has friction enough (a smaller size, a "
                  "garment that reaches the shoulders, or %s)",
                  body.col(1).minCoeff() - median_height(x), settle_steps, friction_advice(has_friction));
    return fell;
  }
  char head[320];
  if (result.at_rest)
    std::snprintf(head, sizeof head,
                  "stopped at rest after %d settling steps (no vertex moved in the last one) with stationarity %.2e of "
                  "the weight, above the tolerance %.2e and the at-rest limit %.2e",
                  settle_steps, result.stationarity, tolerance, at_rest_limit);
  else if (result.sliding() && result.stationarity <= tolerance)
    std::snprintf(head, sizeof head,
                  "not settled after %d settling steps: friction balances the forces (stationarity %.2e of the weight) "
                  "but the garment still slides over the body (its fastest contact at %.3g times the barrier's "
                  "slip_velocity)",
                  settle_steps, result.stationarity, result.slip_ratio);
  else
    std::snprintf(head, sizeof head, "not settled after %d settling steps: stationarity %.2e of the weight, tolerance %.2e",
                  settle_steps, result.stationarity, tolerance);
  std::string out = head;
  // The vertices carrying the largest unbalanced forces (the top 2 %, at least 3).
  const Eigen::VectorXd& f = result.vertex_force;
  std::vector<int> order(static_cast<std::size_t>(f.size()));
  std::iota(order.begin(), order.end(), 0);
  const std::size_t shown = std::min(order.size(), std::max<std::size_t>(3, order.size() / 50));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(),
                    [&](int a, int b) { return f[a] > f[b]; });
  order.resize(shown);
  std::sort(order.begin(), order.end());
  out += "; the largest unbalanced forces (up to " + std::to_string(f.maxCoeff()) + " N) are on " + describe_region(x, order);
  if (result.line_search_failures > 0)
    out += "; " + std::to_string(result.line_search_failures) +
           " Newton iterations found no decrease (the garment may be pinched between parts of the body, or not fit it)";
  if (ease < kMinimumEase) {
    // A fact, not a verdict: the knit stretches, and the regular shirt settles
    // on bodies it is up to about 40 % smaller than (docs/scenes.md); the
    // farther below, the likelier the drape is pulled into the body everywhere.
    char fit[300];
    std::snprintf(fit, sizeof fit,
                  "; the garment is %.1f %% smaller around than the body's chest or belly, so it is stretched onto the "
                  "body (%s)",
                  -100.0 * ease,
                  sized ? "size: auto chooses a size at least as large as the body"
                        : "grade: auto grades it to each body; the garment has no sizes to choose from");
    out += fit;
  }
  return out;
}

}  // namespace drape::scene_detail
