// A figure as one self-contained HTML page: the meshes as JSON and a small
// Canvas 2D renderer (orthographic, painter's algorithm, flat shading by a
// light at the viewer, like the SVG), one canvas per panel, turned by dragging
// and zoomed by the wheel. Canvas 2D rather than WebGL so that the page draws
// the same in any browser, headless ones without a GPU included. When a frame
// is drawn the page records on <body data-drawn-pixels="N"> how many pixels
// differ from the background, so a test in a headless browser can tell that
// it really drew.
#include <drape/errors.hpp>
#include <drape/io/svg_figure.hpp>

#include "xml_escape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace drape {
namespace {

// Numbers for JSON: millimetre resolution is plenty for a picture and keeps the page small.
void append_fixed(std::ostringstream& o, double v, const char* format) {
  char b[32];
  std::snprintf(b, sizeof b, format, std::isfinite(v) ? v : 0.0);
  o << b;
}

std::string json_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\')
      q += std::string("\\") + c;
    else if (c == '<')
      q += "\\u003c";  // never close the <script> early
    else if (static_cast<unsigned char>(c) < 0x20)
      q += ' ';
    else
      q += c;
  }
  return q + "\"";
}

const char* kScript = R"JS(
(function () {
  const figure = JSON.parse(document.getElementById('figure-data').textContent);
  const background = [255, 255, 255];
  // One scale for every panel, so drapes compare.
  let lo = [1e30, 1e30, 1e30], hi = [-1e30, -1e30, -1e30];
  for (const panel of figure.panels) for (const layer of panel.layers)
    for (let i = 0; i < layer.v.length; i += 3) for (let k = 0; k < 3; ++k) {
      lo[k] = Math.min(lo[k], layer.v[i + k]); hi[k] = Math.max(hi[k], layer.v[i + k]);
    }
  const extent = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
  const views = [];
  function draw(view) {
    const ctx = view.canvas.getContext('2d');
    const w = view.canvas.width, h = view.canvas.height;
    ctx.fillStyle = 'rgb(' + background.join(',') + ')';
    ctx.fillRect(0, 0, w, h);
    const cy = Math.cos(view.yaw), sy = Math.sin(view.yaw), cp = Math.cos(view.pitch), sp = Math.sin(view.pitch);
    const scale = 0.9 * Math.min(w, h) / extent * view.zoom;
    const tris = [];
    for (const layer of view.panel.layers) {
      const n = layer.v.length / 3, p = new Float64Array(3 * n);
      for (let i = 0; i < n; ++i) {
        const x = layer.v[3 * i] - view.centre[0], y = layer.v[3 * i + 1] - view.centre[1], z = layer.v[3 * i + 2] - view.centre[2];
        const x1 = cy * x + sy * z, z1 = -sy * x + cy * z;   // turn about y
        const y2 = cp * y - sp * z1, z2 = sp * y + cp * z1;  // tilt about x
        // Depth in pixels too, so that normals come out in one unit.
        p[3 * i] = w / 2 + scale * x1; p[3 * i + 1] = h / 2 - scale * y2; p[3 * i + 2] = scale * z2;
      }
      for (let f = 0; f < layer.f.length; f += 3) {
        const a = 3 * layer.f[f], b = 3 * layer.f[f + 1], c = 3 * layer.f[f + 2];
        // Screen-space normal's z (y is down on screen): the facing and the shade.
        const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], vx = p[c] - p[a], vy = p[c + 1] - p[a + 1];
        const uz = p[b + 2] - p[a + 2], vz = p[c + 2] - p[a + 2];
        const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = -(ux * vy - uy * vx);
        if (layer.cull && nz <= 0) continue;
        const len = Math.hypot(nx, ny, nz) || 1;
        const shade = 0.35 + 0.65 * Math.abs(nz) / len;
        const k = f;  // face index x 3 into the colours
        const depth = layer.under ? Math.min(p[a + 2], p[b + 2], p[c + 2]) : (p[a + 2] + p[b + 2] + p[c + 2]) / 3;
        tris.push([depth + scale * layer.bias, p[a], p[a + 1], p[b], p[b + 1], p[c], p[c + 1],
                   Math.round(layer.c[k] * shade), Math.round(layer.c[k + 1] * shade), Math.round(layer.c[k + 2] * shade)]);
      }
    }
    tris.sort((s, t) => s[0] - t[0]);  // far first
    for (const t of tris) {
      const colour = 'rgb(' + t[7] + ',' + t[8] + ',' + t[9] + ')';
      ctx.fillStyle = colour; ctx.strokeStyle = colour; ctx.lineWidth = 0.6;
      ctx.beginPath(); ctx.moveTo(t[1], t[2]); ctx.lineTo(t[3], t[4]); ctx.lineTo(t[5], t[6]); ctx.closePath();
      ctx.fill(); ctx.stroke();
    }
    view.triangles = tris.length;
  }
  function drawnPixels() {
    let count = 0;
    for (const view of views) {
      const d = view.canvas.getContext('2d').getImageData(0, 0, view.canvas.width, view.canvas.height).data;
      for (let i = 0; i < d.length; i += 4)
        if (d[i] !== background[0] || d[i + 1] !== background[1] || d[i + 2] !== background[2]) ++count;
    }
    return count;
  }
  const container = document.getElementById('panels');
  for (const panel of figure.panels) {
    const box = document.createElement('div');
    box.className = 'panel';
    const title = document.createElement('div');
    title.textContent = panel.title;
    const canvas = document.createElement('canvas');
    canvas.width = 420; canvas.height = 560;
    box.appendChild(title); box.appendChild(canvas); container.appendChild(box);
    let c = [0, 0, 0], n = 0;
    for (const layer of panel.layers) for (let i = 0; i < layer.v.length; i += 3) { c[0] += layer.v[i]; c[1] += layer.v[i + 1]; c[2] += layer.v[i + 2]; ++n; }
    const view = {panel, canvas, yaw: 0, pitch: 0, zoom: 1, centre: c.map(x => x / Math.max(n, 1))};
    views.push(view);
    let last = null;
    canvas.addEventListener('mousedown', e => { last = [e.clientX, e.clientY]; });
    window.addEventListener('mouseup', () => { last = null; });
    canvas.addEventListener('mousemove', e => {
      if (!last) return;
      view.yaw += 0.01 * (e.clientX - last[0]);
      view.pitch = Math.max(-1.5, Math.min(1.5, view.pitch + 0.01 * (e.clientY - last[1])));
      last = [e.clientX, e.clientY];
      draw(view);
    });
    canvas.addEventListener('wheel', e => { e.preventDefault(); view.zoom *= Math.exp(-0.001 * e.deltaY); draw(view); });
    canvas.addEventListener('dblclick', () => { view.yaw = 0; view.pitch = 0; view.zoom = 1; draw(view); });
  }
  for (const b of document.querySelectorAll('button[data-yaw]'))
    b.addEventListener('click', () => { for (const v of views) { v.yaw = parseFloat(b.dataset.yaw); v.pitch = 0; draw(v); } });
  for (const view of views) draw(view);
  document.body.dataset.drawnPixels = String(drawnPixels());
  document.body.dataset.triangles = String(views.reduce((s, v) => s + v.triangles, 0));
})();
)JS";

}  // namespace

std::string SvgFigure::html() const {
  if (panels_.empty()) throw Error("html: a figure needs at least one panel");
  std::ostringstream data;
  data << "{\"panels\":[";
  for (std::size_t p = 0; p < panels_.size(); ++p) {
    const SvgPanel& panel = panels_[p];
    data << (p ? "," : "") << "{\"title\":" << json_string(panel.title) << ",\"layers\":[";
    for (std::size_t l = 0; l < panel.layers.size(); ++l) {
      const SvgLayer& layer = panel.layers[l];
      data << (l ? "," : "") << "{\"cull\":" << (layer.cull_back_faces ? "true" : "false")
           << ",\"under\":" << (layer.under ? "true" : "false") << ",\"bias\":";
      append_fixed(data, layer.depth_bias, "%.4f");
      data << ",\"v\":[";
      for (Eigen::Index i = 0; i < layer.vertices.rows(); ++i)
        for (int k = 0; k < 3; ++k) {
          if (i || k) data << ",";
          append_fixed(data, layer.vertices(i, k), "%.4f");
        }
      data << "],\"f\":[";
      for (Eigen::Index f = 0; f < layer.faces.rows(); ++f)
        for (int k = 0; k < 3; ++k) data << (f || k ? "," : "") << layer.faces(f, k);
      data << "],\"c\":[";
      const std::vector<std::array<double, 3>> colours = face_colours(layer);
      for (std::size_t f = 0; f < colours.size(); ++f)
        for (int k = 0; k < 3; ++k)
          data << (f || k ? "," : "") << static_cast<int>(std::lround(std::clamp(colours[f][k], 0.0, 255.0)));
      data << "]}";
    }
    data << "]}";
  }
  data << "]}";

  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << xml_escaped(title_)
    << "</title>\n<style>body{font:14px sans-serif;margin:16px;color:#222}#panels{display:flex;flex-wrap:wrap;gap:12px}"
       ".panel{border:1px solid #ddd;padding:6px;width:420px;overflow-wrap:anywhere}canvas{display:block;cursor:grab}.bar{width:320px;height:12px;"
       "background:linear-gradient(to right";
  for (int i = 0; i <= 8; ++i) o << "," << colour_map(i / 8.0);
  // A note may hold a long unbroken run (a pose "name=deg,name=deg,..."): wrapped anywhere, not past the page.
  o << ")}.warning{color:#b00020}.note,.warning{overflow-wrap:anywhere}</style></head>\n<body>\n<h3>" << xml_escaped(title_) << "</h3>\n";
  for (const std::string& note : notes_)
    o << "<p class=\"" << (note.rfind("warning:", 0) == 0 ? "warning" : "note") << "\">" << xml_escaped(note) << "</p>\n";
  o << "<p>Drag to turn, wheel to zoom, double-click to reset. "
       "<button data-yaw=\"0\">front</button> <button data-yaw=\"1.5708\">side</button> "
       "<button data-yaw=\"3.1416\">back</button></p>\n";
  if (scale_) {
    char range[96];
    std::snprintf(range, sizeof range, "%.3g &mdash; &ge; %.3g", scale_->lo, scale_->hi);
    o << "<p>" << xml_escaped(scale_->label) << ": " << range << "</p><div class=\"bar\"></div>\n";
    if (!scale_->below_label.empty())
      o << "<p><span style=\"display:inline-block;width:12px;height:12px;background:" << scale_->below_colour
        << "\"></span> " << xml_escaped(scale_->below_label) << "</p>\n";
  }
  o << "<div id=\"panels\"></div>\n<script type=\"application/json\" id=\"figure-data\">" << data.str()
    << "</script>\n<script>" << kScript << "</script>\n</body></html>\n";
  return o.str();
}

}  // namespace drape
