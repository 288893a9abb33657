// Pictures: the SVG figure draws every visible triangle once, back to front,
// coloured by value through the colour map, and is written atomically.
#include <drape/errors.hpp>
#include <drape/io/svg_chart.hpp>
#include <drape/io/svg_figure.hpp>

#include <catch2/catch.hpp>

#include <fstream>
#include <regex>
#include <sstream>

#include "test_support.hpp"

using namespace drape;

namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A unit cube (12 outward triangles) centred at the origin.
SvgLayer cube() {
  SvgLayer l;
  l.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) l.vertices.row(i) << (i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5;
  l.faces.resize(12, 3);
  l.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return l;
}

}  // namespace

TEST_CASE("colour_map runs from dark purple to yellow and clamps", "[svg]") {
  CHECK(colour_map(0.0) == "#440154");
  CHECK(colour_map(1.0) == "#fde725");
  CHECK(colour_map(-3.0) == colour_map(0.0));
  CHECK(colour_map(7.0) == colour_map(1.0));
  CHECK(colour_map(0.5) == "#21918c");
}

TEST_CASE("an SVG figure draws each visible triangle once, culls back faces of closed meshes", "[svg]") {
  SvgLayer all = cube();
  SvgLayer culled = cube();
  culled.cull_back_faces = true;
  SvgFigure a("all"), b("culled");
  a.add_panel({"cube", {all}});
  b.add_panel({"cube", {culled}});
  const std::string sa = a.svg(), sb = b.svg();
  CHECK(count(sa, "<path ") == 12);
  // Seen from +z: the faces whose normal has z >= 0 are the front (2) and the
  // four sides (8, edge-on, kept); the back (2) goes.
  CHECK(count(sb, "<path ") == 10);
  CHECK(sa.rfind("<svg ", 0) == 0);
  CHECK(sa.find("</svg>") != std::string::npos);
}

TEST_CASE("values are coloured through the colour scale, with a colour bar", "[svg]") {
  SvgLayer l = cube();
  l.values = Eigen::VectorXd::Constant(8, 2.0);  // the top of the scale everywhere
  SvgFigure f("errors");
  f.add_panel({"cube <1>", {l}});
  f.set_colour_scale({"error (cm)", 0.0, 2.0});
  const std::string s = f.svg();
  CHECK(s.find("linearGradient") != std::string::npos);
  CHECK(s.find("error (cm)") != std::string::npos);
  CHECK(s.find("cube &lt;1&gt;") != std::string::npos);  // titles are escaped
  // Every face is yellow, darkened by the shading: red and green channels well above blue.
  const std::regex fill("fill=\"#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})\" stroke");
  int faces = 0;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), fill); it != std::sregex_iterator(); ++it, ++faces) {
    const int r = std::stoi((*it)[1], nullptr, 16), g = std::stoi((*it)[2], nullptr, 16), b = std::stoi((*it)[3], nullptr, 16);
    CHECK(r > 2 * b);
    CHECK(g > 2 * b);
  }
  CHECK(faces == 12);
  SvgLayer wrong = cube();
  wrong.values = Eigen::VectorXd::Zero(3);
  SvgFigure g("bad");
  g.add_panel({"", {wrong}});
  CHECK_THROWS_WITH(g.svg(), Catch::Contains("3 values for 8 vertices"));
  CHECK_THROWS_AS(SvgFigure("empty").svg(), Error);
}

TEST_CASE("an SVG figure is written atomically", "[svg]") {
  test::TempDir dir;
  SvgFigure f("cube");
  f.add_panel({"", {cube()}});
  f.write(dir / "cube.svg");
  std::ifstream in(dir / "cube.svg");
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str() == f.svg());
  CHECK_THROWS(f.write(dir / "no-such-dir" / "cube.svg"));
  CHECK_FALSE(std::filesystem::exists(dir / "no-such-dir"));
}

TEST_CASE("a scatter chart places labelled points on a log time axis with decade ticks", "[svg][chart]") {
  ScatterChart chart;
  chart.title = "accuracy <vs> time";
  chart.x_label = "ms";
  chart.y_label = "ME (cm)";
  chart.points = {{2.0, 0.5, "network"}, {4000.0, 0.0, "simulation"}};
  const std::string s = chart.svg();
  CHECK(count(s, "<circle ") == 2);
  // 2 ms .. 4000 ms spans the decades 1 .. 10000: five ticks.
  for (const char* tick : {">1<", ">10<", ">100<", ">1000<", ">10000<"}) CHECK(s.find(tick) != std::string::npos);
  CHECK(s.find("accuracy &lt;vs&gt; time") != std::string::npos);
  CHECK(s.find("ms (log scale)") != std::string::npos);
  // The faster point is further left, the more accurate one lower (SVG y grows downwards).
  const std::regex circle("cx=\"([0-9.]+)\" cy=\"([0-9.]+)\"");
  std::vector<std::pair<double, double>> at;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), circle); it != std::sregex_iterator(); ++it)
    at.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  REQUIRE(at.size() == 2);
  CHECK(at[0].first < at[1].first);
  CHECK(at[0].second < at[1].second);
  const std::regex svg_width("<svg [^>]*width=\"([0-9.]+)\"");
  std::smatch m;
  REQUIRE(std::regex_search(s, m, svg_width));
  CHECK(std::stod(m[1]) == 640.0);  // short labels: the plot's own width
  chart.points.push_back({10.0, 0.2, std::string(150, 'x')});
  const std::string wide = chart.svg();
  REQUIRE(std::regex_search(wide, m, svg_width));
  CHECK(std::stod(m[1]) >= 70 + 6 * 150);  // a 150-character legend line fits
  chart.points.back() = {0.0, 1.0, "instant"};
  CHECK_THROWS_WITH(chart.svg(), Catch::Contains("log axis"));
  CHECK_THROWS_AS(ScatterChart{}.svg(), Error);
}

TEST_CASE("a long panel caption is wrapped inside the picture and the colour bar's stops are the faces' eighths", "[svg]") {
  // An outside check: render's caption ran past the 528 px picture's right edge, and the
  // bar's stops were rounded to 0.1, 0.2, 0.4 while the faces take the eighths' colours.
  SvgFigure figure("title");
  const std::string caption = "ME 1.39 cm, max 5.62 cm, p = 0.00%, 0 edges crossing the body, 0 edge-face pairs of the "
                              "garment through itself";
  figure.add_panel({caption, {cube()}});
  figure.set_colour_scale({"distance (cm)", 0.0, 5.0});
  const std::string svg = figure.svg();
  std::smatch m;
  REQUIRE(std::regex_search(svg, m, std::regex("width=\"([0-9.]+)\"")));
  const double width = std::stod(m[1]);
  // Each caption line at 12 px (about 6.6 px a character) ends inside the picture, and together they say it all.
  std::string joined;
  const std::regex line("<text x=\"([0-9.]+)\" y=\"[0-9.]+\" font-size=\"12\">([^<]*)</text>");
  int lines = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator(); ++it) {
    ++lines;
    CHECK(std::stod((*it)[1]) + 6.6 * static_cast<double>((*it)[2].length()) <= width);
    joined += (joined.empty() ? "" : " ") + (*it)[2].str();
  }
  CHECK(lines >= 2);
  CHECK(joined == caption);
  for (int i = 0; i <= 8; ++i) {
    char stop[64];
    std::snprintf(stop, sizeof stop, "<stop offset=\"%.3f\" stop-color=\"%s\"/>", i / 8.0, colour_map(i / 8.0).c_str());
    CHECK_THAT(svg, Catch::Contains(stop));
  }
}

TEST_CASE("a scatter chart's point numbers do not run into each other and its front is drawn", "[svg][chart]") {
  // An outside check: numbers of points close together read "109" and "812", one point's number was hidden,
  // the y ticks were not round numbers, and the promised Pareto front was not drawn.
  ScatterChart chart;
  chart.title = "t";
  for (int i = 0; i < 12; ++i)  // a cluster: twelve points a few pixels apart (as the accuracy-time chart's tiers)
    chart.points.push_back({1.0 + 0.12 * i, 0.70 + 0.01 * (i % 3), "p" + std::to_string(i), i % 5 == 0});
  chart.points.push_back({100.0, 0.1, "far", true});
  const std::string s = chart.svg();
  // The numbers' boxes (7.5 px a digit, 12 px high), from the bold texts.
  const std::regex number("<text x=\"([0-9.]+)\" y=\"([0-9.]+)\" font-weight=\"bold\"( text-anchor=\"end\")?>([0-9]+)</text>");
  struct Box {
    double x0, y0, x1, y1;
  };
  std::vector<Box> boxes;
  for (auto it = std::sregex_iterator(s.begin(), s.end(), number); it != std::sregex_iterator(); ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]), width = 7.5 * (*it)[4].length();
    const double left = (*it)[3].matched ? x - width : x;
    boxes.push_back({left, y - 10, left + width, y + 2});
  }
  REQUIRE(boxes.size() == 13);
  int overlapping = 0;
  for (std::size_t a = 0; a < boxes.size(); ++a)
    for (std::size_t b = a + 1; b < boxes.size(); ++b)
      overlapping += std::min(boxes[a].x1, boxes[b].x1) > std::max(boxes[a].x0, boxes[b].x0) &&
                     std::min(boxes[a].y1, boxes[b].y1) > std::max(boxes[a].y0, boxes[b].y0);
  CHECK(overlapping == 0);
  // Round y ticks: 0, 0.2, 0.4, ... (the top point 0.72 * 1.15 rounded up to a tick).
  for (const char* tick : {">0<", ">0.2<", ">0.4<", ">0.6<", ">0.8<"}) CHECK(s.find(tick) != std::string::npos);
  CHECK(s.find("stroke-dasharray") != std::string::npos);  // the front through the four points on it
}

TEST_CASE("a long note or title is wrapped to the picture's width", "[svg]") {
  // An outside check: a warning of one line made a one-panel render 4,000 px wide, its drape a speck.
  SvgFigure figure("drape render: prediction of a model with a long name for a body described at length " +
                   std::string(60, 'x'));
  figure.add_note("warning: " + std::string(20, 'w') + " " + std::string(400, 'a').replace(0, 400, std::string(80, 'a') + " " + std::string(80, 'b') + " " + std::string(80, 'c')));
  figure.add_panel({"caption", {cube()}});
  const std::string svg = figure.svg();
  std::smatch m;
  REQUIRE(std::regex_search(svg, m, std::regex("width=\"([0-9.]+)\"")));
  CHECK(std::stod(m[1]) < 700);
  CHECK(std::regex_search(svg, std::regex("fill=\"#b00020\">[^<]*bbbb")));  // the warning's later lines still red
}

TEST_CASE("the HTML page's panels are as wide as their canvases", "[svg]") {
  // An outside check: a panel's one-line caption made it twice as wide as its canvas, the drape in its left quarter.
  SvgFigure figure("title");
  figure.add_panel({"p = 0.00% of the vertices inside the body, 0 edges crossing it, " + std::string(200, 'x'), {cube()}});
  const std::string html = figure.html();
  std::smatch canvas, panel;
  REQUIRE(std::regex_search(html, canvas, std::regex("canvas\\.width = ([0-9]+)")));
  REQUIRE(std::regex_search(html, panel, std::regex("\\.panel\\{[^}]*width:([0-9]+)px")));
  CHECK(canvas[1].str() == panel[1].str());
}

TEST_CASE("values below the scale take the below colour and the legend names it when the scale has one", "[svg]") {
  // An outside check: cloth 81 % inside the body was clamped to the map's 0 (its darkest purple) and read as a
  // tight fit. With a below label a face under lo is drawn in the scale's own colour (red, shaded: red well
  // above green and blue), never a map colour, and the legend has its swatch and words; without one, as before.
  SvgLayer l = cube();
  l.values = Eigen::VectorXd::Constant(8, -1.0);
  const std::regex fill("fill=\"#([0-9a-f]{2})([0-9a-f]{2})([0-9a-f]{2})\" stroke");
  for (const bool labelled : {true, false}) {
    SvgFigure f("inside");
    f.add_panel({"cube", {l}});
    f.set_colour_scale({"distance (cm)", 0.0, 5.0, labelled ? "inside the body" : ""});
    const std::string s = f.svg();
    CHECK((s.find("inside the body</text>") != std::string::npos) == labelled);
    CHECK((s.find("fill=\"#e4002b\"/>") != std::string::npos) == labelled);  // the swatch
    int faces = 0;
    for (auto it = std::sregex_iterator(s.begin(), s.end(), fill); it != std::sregex_iterator(); ++it, ++faces) {
      const int r = std::stoi((*it)[1], nullptr, 16), g = std::stoi((*it)[2], nullptr, 16), b = std::stoi((*it)[3], nullptr, 16);
      if (labelled) CHECK((r > 3 * g && r > 3 * b));
      else CHECK(b > r);  // viridis at 0: dark purple, blue above red
    }
    CHECK(faces == 12);
    CHECK((f.html().find("inside the body</p>") != std::string::npos) == labelled);
  }
}
