// Untangling a garment's self-crossings: a strip folded over itself with a
// bump of the upper layer pushed through the lower one (a closed curve: two
// patches; near the fold, crumples), the same bump at the strip's free end (an open curve), two
// separate sheets, a mesh without crossings, and bad input. Crossings are
// counted here by a brute-force segment-triangle test of this file's own
// (Moller-Trumbore), not by the code under test.
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/untangle.hpp>

#include <catch2/catch.hpp>

#include "folded_strip.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

using drape::geometry::untangle;
using drape::geometry::UntangleOptions;

using namespace drape::test;

TEST_CASE("untangle: a bump pushed through the fold below goes back, the rest of the strip stays") {
  const double height = 0.02, depth = 0.006;
  Strip s = folded_strip(41, 21, height);
  REQUIRE(brute_force_crossings(s.x, s.faces) == 0);
  push_bump(s, 0.503, 0.497, 0.1, depth, height);  // off the grid: no edge just touches a face
  const Eigen::MatrixX3d before = s.x;
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 10);

  UntangleOptions options;
  options.gap = 1e-3;
  const auto report = untangle(s.x, s.faces, options);
  CHECK(report.crossings_before == crossings);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, s.faces) == 0);
  CHECK(report.patches_moved >= 2);  // the bump's tip and the lower layer's disc inside it
  CHECK(report.crumples_smoothed == 0);  // the layers meet many rings from the fold: no crumple
  // The right side: the bump's lowest vertex above the lower layer's vertex under it.
  const int tip = s.at(30, 10), under = s.at(10, 10);  // u = 1.5 -> x = 0.5; u = 0.5 -> x = 0.5
  REQUIRE(before(tip, 0) == Approx(0.5));
  REQUIRE(before(under, 0) == Approx(0.5));
  CHECK(s.x(tip, 2) > s.x(under, 2));
  // Moved by about the depth, not more than the depth and the gap twice over.
  CHECK(report.largest_move <= 2 * (depth + options.gap));
  CHECK(report.largest_move > 0.5 * depth);
  // Far from the bump every vertex keeps its bits.
  int far = 0;
  for (int v = 0; v < s.x.rows(); ++v)
    if (std::hypot(before(v, 0) - 0.503, before(v, 1) - 0.497) > 0.25) {
      ++far;
      CHECK(s.x.row(v) == before.row(v));
    }
  CHECK(far > 500);
}

TEST_CASE("untangle: two separate sheets, one poked through the other, each piece keeps its largest part") {
  // The two layers of the strip cut apart at the fold: two pieces.
  const double height = 0.02, depth = 0.004;
  Strip s = folded_strip(41, 21, height);
  push_bump(s, 0.403, 0.597, 0.08, depth, height);
  std::vector<Eigen::RowVector3i> kept;
  for (Eigen::Index f = 0; f < s.faces.rows(); ++f) {
    bool lower = false, upper = false;
    for (int k = 0; k < 3; ++k) (s.faces(f, k) % s.cols <= 20 ? lower : upper) = true;
    if (!(lower && upper)) kept.push_back(s.faces.row(f));
  }
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t f = 0; f < kept.size(); ++f) faces.row(static_cast<Eigen::Index>(f)) = kept[f];
  REQUIRE(brute_force_crossings(s.x, faces) > 0);
  const auto report = untangle(s.x, faces);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, faces) == 0);
  const int tip = s.at(32, 12), under = s.at(8, 12);  // x = 0.4, y = 0.6 on both layers
  REQUIRE(s.x(tip, 0) == Approx(0.4));
  CHECK(s.x(tip, 2) > s.x(under, 2));
}

TEST_CASE("untangle: the upper layer's free end bent through the lower one (a curve open on one sheet)") {
  // The upper layer ends at x = 0.3, over the lower one; its end is bent
  // down through it. On the upper layer the curve runs border to border and
  // cuts off the end (a patch); on the lower layer it ends where the upper
  // layer's border pierces it, so the cut separates nothing there and its
  // pierced edges are moved one end at a time.
  const double height = 0.02, depth = 0.005;
  Strip s = folded_strip(41, 21, height, 0.3);
  push_bump(s, 0.3, 0.503, 0.08, depth, height);
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 0);
  UntangleOptions options;
  options.max_rounds = 8;
  const auto report = untangle(s.x, s.faces, options);
  CHECK(report.crossings_before == crossings);
  CHECK(report.crossings_after == brute_force_crossings(s.x, s.faces));
  CHECK(report.crossings_after == 0);
  CHECK(report.patches_moved >= 1);
  CHECK(report.largest_move <= 2 * (depth + options.gap));
  // The end back above the lower layer.
  const int end = s.at(40, 10), under = s.at(6, 10);  // u = 2 -> x = 0.3; u = 0.3
  REQUIRE(s.x(under, 0) == Approx(0.3));
  CHECK(s.x(end, 2) > s.x(under, 2));
}

TEST_CASE("untangle: a mesh that does not cross itself is left bit for bit") {
  Strip s = folded_strip(21, 11, 0.02);
  const Eigen::MatrixX3d before = s.x;
  const auto report = untangle(s.x, s.faces);
  CHECK(report.crossings_before == 0);
  CHECK(report.crossings_after == 0);
  CHECK(report.rounds == 0);
  CHECK(report.vertices_moved == 0);
  CHECK(s.x == before);
}

TEST_CASE("untangle: bad input is refused") {
  Strip s = folded_strip(5, 3, 0.02);
  Eigen::MatrixX3i faces = s.faces;
  faces(0, 1) = 99;
  CHECK_THROWS_WITH(untangle(s.x, faces), Catch::Contains("outside the garment's 15"));
  Eigen::MatrixX3d x = s.x;
  x(3, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(untangle(x, s.faces), Catch::Contains("non-finite"));
  UntangleOptions options;
  options.gap = -1;
  CHECK_THROWS_WITH(untangle(s.x, s.faces, options), Catch::Contains("gap"));
}

TEST_CASE("untangle: two cards slotted into each other (a curve open on both) are left as they were") {
  // Card A in the plane z = 0 over [0, 1] x [0, 1]; card B in the plane
  // x = 0.503 over y in [0.6, 1.4], z in [-0.2, 0.2]. They cross along
  // x = 0.503, z = 0 from B's border (y = 0.6) to A's (y = 1): the cut
  // separates neither card, and pulling each pierced edge off its face only
  // hands the crossing on to the next edge (one card would have to leave
  // the other whole). The fewest crossings seen are the start's: the cards
  // come back bit for bit, and the report says the crossings are left.
  const int n = 21;
  Eigen::MatrixX3d x(2 * n * n, 3);
  Eigen::MatrixX3i faces(4 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int card = 0; card < 2; ++card) {
    const int base = card * n * n;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double s = static_cast<double>(i) / (n - 1), t = static_cast<double>(j) / (n - 1);
        if (card == 0) x.row(base + i + n * j) << s, t + 0.0071, 0.0;
        else x.row(base + i + n * j) << 0.503, 0.6 + 0.8 * s, -0.2 + 0.4 * t + 0.0033;
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const int v = base + i + n * j;
        faces.row(f++) << v, v + 1, v + 1 + n;
        faces.row(f++) << v, v + 1 + n, v + n;
      }
  }
  const int crossings = brute_force_crossings(x, faces);
  REQUIRE(crossings > 5);
  const Eigen::MatrixX3d before = x;
  UntangleOptions options;
  options.max_rounds = 8;
  const auto report = untangle(x, faces, options);
  CHECK(report.patches_moved == 0);
  CHECK(report.crossings_after == brute_force_crossings(x, faces));
  CHECK(report.crossings_after > 0);
  CHECK(report.crossings_after <= report.crossings_before);
  if (report.crossings_after == report.crossings_before) {
    CHECK(report.rounds == 0);
    CHECK(x == before);
  }
}

// A strip of 6 x 9 vertices, rows along y. In cross-section the sheet runs
// flat to row 3 (y = 3), folds back under itself to row 4 (y = back,
// z = -depth) and comes up through itself between rows 2 and 3 to row 5
// (y = up, z = depth), then runs on flat. Each crossing edge (rows 4-5) is
// a ring from the face it pierces (row 4's neighbour in row 3 is a
// corner): a fold narrower than the mesh's ring.
Strip z_crumple(double back, double depth, double up) {
  const std::vector<std::array<double, 2>> profile = {{0, 0},          {1, 0},          {2, 0},
                                                      {3, 0},          {back, -depth},  {up, depth},
                                                      {up + 1, depth}, {up + 2, depth}, {up + 3, depth}};
  Strip s{Eigen::MatrixX3d(6 * 9, 3), Eigen::MatrixX3i(2 * 5 * 8, 3), 6, 9};
  for (int j = 0; j < s.rows; ++j)
    for (int i = 0; i < s.cols; ++i) s.x.row(s.at(i, j)) << i + 0.013 * j, profile[j][0], profile[j][1];
  grid_faces(s);
  return s;
}

TEST_CASE("untangle: a Z-shaped crumple (the sheet folded back under itself and up through itself) is smoothed out") {
  // Pulling edge and face apart along the face's normal hands the crossing
  // on (3 of 20 were left); the crumples' smoothing flattens it.
  Strip s = z_crumple(2.2, 0.3, 3.5);
  const Eigen::MatrixX3d before = s.x;
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 0);
  const auto report = untangle(s.x, s.faces);
  CHECK(report.crossings_before == crossings);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, s.faces) == 0);
  CHECK(report.crumples_smoothed > 0);
  CHECK(report.patches_moved == 0);
  CHECK(report.largest_move < 0.5);  // half an edge: the fold is 0.3 deep
  // Rows two rings or more from the crumple keep their bits.
  for (const int j : {0, s.rows - 2, s.rows - 1})
    for (int i = 0; i < s.cols; ++i) CHECK(s.x.row(s.at(i, j)) == before.row(s.at(i, j)));
}

TEST_CASE("untangle: a deeper crumple is smoothed over three rounds, though the count holds for two") {
  // 0.4 deep: the first two rounds of smoothing leave all 20 crossings (the
  // fold flattens, its layers still through each other), the third none.
  // Rounds that only smooth crumples are not idle: with the default patience
  // of two idle rounds the run used to stop after the second and return the
  // crumple as it was (a heavy held-out body's underarm, docs/bodies.md).
  Strip s = z_crumple(2.0, 0.4, 3.6);
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings == 20);
  const auto report = untangle(s.x, s.faces);
  CHECK(report.crossings_before == crossings);
  CHECK(report.rounds == 3);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, s.faces) == 0);
  CHECK(report.patches_moved == 0);
}

TEST_CASE("untangle: a bump pushed through four rings from the fold is smoothed with the wider reach") {
  // The upper layer pushed through the lower one round x = 0.858, upper
  // columns 22-23 and lower 17-18: the crossings are four rings and more
  // apart through the fold. With the crumples' reach of three rings the
  // untangle cut them as two sheets and left 22 of 30 (measured); the run
  // again with four smooths them all (the posed human model's hardest case,
  // a BMI 64 woman's underarm, was two edges interlocked four rings apart).
  const double height = 0.02, depth = 0.006;
  Strip s = folded_strip(41, 21, height);
  push_bump(s, 0.8583, 0.5117, 0.04, depth, height);
  const Eigen::MatrixX3d before = s.x;
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings == 30);
  const auto report = untangle(s.x, s.faces);
  CHECK(report.crossings_before == crossings);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, s.faces) == 0);
  CHECK(report.crumples_smoothed > 0);
  CHECK(report.largest_move <= 2 * (depth + 1e-3));
  // Far from the bump every vertex keeps its bits.
  int far = 0;
  for (int v = 0; v < s.x.rows(); ++v)
    if (std::abs(before(v, 0) - 0.8583) > 0.3 || std::abs(before(v, 1) - 0.5117) > 0.3) {
      ++far;
      CHECK(s.x.row(v) == before.row(v));
    }
  CHECK(far > 400);
}

TEST_CASE("untangle: two layers pinched through each other beside their fold go back to their sides at rest") {
  // A sleeve's two layers at the underarm, where the seam joins them: the
  // upper layer pushed down through the lower one a ring or two from the
  // fold, so every crossing is within the crumples' reach. Smoothing does
  // not flatten that (the layers are 2 cm apart at rest, not one sheet);
  // the side each edge has at rest tells which way it goes back.
  const double height = 0.02, depth = 0.006;
  const Strip rest = folded_strip(41, 21, height);
  Strip s = rest;
  push_bump(s, 0.9583, 0.5117, 0.04, depth, height);  // upper columns 21-22 (x = 0.95, 0.90), a ring or two from the fold
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 0);
  const Eigen::MatrixX3d pinched = s.x;

  UntangleOptions without;
  const auto smoothed = untangle(s.x, s.faces, without);
  CHECK(smoothed.crumples_smoothed > 0);
  CHECK(smoothed.layers_pulled == 0);
  CHECK(smoothed.crossings_after >= crossings / 3);  // smoothing alone leaves many of them

  s.x = pinched;
  UntangleOptions options;
  options.rest = &rest.x;
  const auto report = untangle(s.x, s.faces, options);
  CHECK(report.crossings_before == crossings);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, s.faces) == 0);
  CHECK(report.layers_pulled > 0);  // (the edges from the fold's own vertices, on the lower layer's plane at rest, are smoothed)
  // The upper layer above the lower one again where it was pushed through.
  const int tip = s.at(21, 10), under = s.at(19, 10);  // u = 1.05 -> x = 0.95; u = 0.95 -> x = 0.95
  REQUIRE(pinched(tip, 2) < pinched(under, 2));
  CHECK(s.x(tip, 2) > s.x(under, 2));
  CHECK(report.largest_move <= 2 * (depth + options.gap));
  // A garment at rest of another size is refused.
  const Eigen::MatrixX3d short_rest = rest.x.topRows(10);
  options.rest = &short_rest;
  CHECK_THROWS_WITH(untangle(s.x, s.faces, options), Catch::Contains("at rest must have the garment's 861 vertices"));
}

TEST_CASE("untangle: where the sides at rest leave crossings, the crumples' smoothing from the same start is kept") {
  // A rest that puts the crumple's folded rows 2 above the sheet in one
  // column and 2 below it in the next: the pulls to those sides, in turn up
  // and down, do not undo it; the run without them (the smoothing) does,
  // and is what comes back.
  Strip s = z_crumple(2.2, 0.3, 3.5);
  Strip rest = z_crumple(2.2, 0.3, 3.5);
  for (int i = 0; i < rest.cols; ++i)
    for (const int j : {4, 5}) rest.x(rest.at(i, j), 2) = i % 2 ? 2.0 : -2.0;
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 0);
  UntangleOptions options;
  options.rest = &rest.x;
  drape::geometry::Untangler untangler(s.faces, static_cast<int>(s.x.rows()));
  const auto report = untangler.run(s.x, options);
  CHECK(report.crossings_after == 0);
  CHECK(brute_force_crossings(s.x, s.faces) == 0);
  // The report is the smoothing's: the run with the sides at rest (which
  // pulls the edges down a column that has one) left crossings.
  CHECK(report.layers_pulled == 0);
  CHECK(report.crumples_smoothed > 0);
}

// The search for crossings passes over the parts of the cloth that are
// height fields along a coordinate axis with a simple outline
// (UntangleReport::edges_culled). It must find what the brute force finds.

// A grid sheet over [0, 1] x [0, 1], faces turning to +z, its heights from `height`.
Strip grid_sheet(int n, const std::function<double(double, double)>& height) {
  Strip s{Eigen::MatrixX3d(n * n, 3), Eigen::MatrixX3i(2 * (n - 1) * (n - 1), 3), n, n};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = static_cast<double>(i) / (n - 1), y = static_cast<double>(j) / (n - 1);
      s.x.row(s.at(i, j)) << x, y, height(x, y);
    }
  grid_faces(s);
  return s;
}

TEST_CASE("untangle: a gently waved sheet is one height field, and no edge's search looks into it") {
  Strip s = grid_sheet(17, [](double x, double y) { return 0.05 * std::sin(5 * x) * std::cos(4 * y); });
  const auto report = untangle(s.x, s.faces);
  CHECK(report.crossings_before == 0);
  CHECK(report.edges_culled == static_cast<int>(drape::geometry::edge_list(s.faces).size()));
}

TEST_CASE("untangle: a ramp wound one and a quarter turns through itself is found, though every face turns up") {
  // An annulus r in [1, 2] wound over 2.5 pi, tilted across its width by a
  // slope that turns from +0.2 to -0.2 along it: the last quarter turn lies
  // over the first and crosses it along r = 1.5. Seen from above every face
  // turns counter-clockwise and the boundary is one loop, so only the test
  // of the outline (which overlaps itself) tells that the ramp is no height
  // field. (47 steps of angle: the layers' vertices do not line up.)
  const int around = 48, across = 6;
  // (Columns across, rows around: grid_faces then turns them up.)
  Strip s{Eigen::MatrixX3d(around * across, 3), Eigen::MatrixX3i(2 * (around - 1) * (across - 1), 3), across, around};
  const double turn = 2.5 * M_PI;
  for (int j = 0; j < around; ++j)
    for (int i = 0; i < across; ++i) {
      const double theta = turn * j / (around - 1), r = 1.0 + static_cast<double>(i) / (across - 1);
      const double slope = 0.2 - 0.4 * theta / turn;
      s.x.row(s.at(i, j)) << r * std::cos(theta), r * std::sin(theta), slope * (r - 1.5);
    }
  grid_faces(s);
  const int crossings = brute_force_crossings(s.x, s.faces);
  REQUIRE(crossings > 0);
  UntangleOptions options;
  options.max_rounds = 1;
  const auto report = untangle(s.x, s.faces, options);
  CHECK(report.crossings_before == crossings);
  CHECK(report.edges_culled > 0);  // the ramp's parts that do not overlap are height fields
}

TEST_CASE("untangle: on crumpled sheets the search that passes over height fields finds every crossing") {
  // Sheets with random heights: smooth ones (every edge culled), rough ones
  // crossing themselves in many places, and the cases between, where some
  // parts are height fields and others cross.
  std::mt19937 random(7);
  int culled = 0, crossed = 0;
  for (const double roughness : {0.005, 0.02, 0.05, 0.1, 0.3})
    for (int trial = 0; trial < 4; ++trial) {
      std::uniform_real_distribution<double> noise(-roughness, roughness);
      Strip s = grid_sheet(13, [&](double, double) { return noise(random); });
      // Bumps folded over: shift some vertices sideways by more than an edge.
      for (int v = 0; v < s.x.rows(); ++v)
        if (noise(random) > 0.8 * roughness) s.x(v, 0) += 4 * noise(random), s.x(v, 1) -= 4 * noise(random);
      const int expected = brute_force_crossings(s.x, s.faces);
      UntangleOptions options;
      options.max_rounds = 1;
      Eigen::MatrixX3d x = s.x;
      const auto report = untangle(x, s.faces, options);
      INFO("roughness " << roughness << ", trial " << trial);
      CHECK(report.crossings_before == expected);
      culled += report.edges_culled > 0 && expected > 0;
      crossed += expected > 0;
    }
  CHECK(crossed >= 8);
  CHECK(culled == crossed);  // (14 of 14 when written) each crossing sheet is a height field somewhere
}
