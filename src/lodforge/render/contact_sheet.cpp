// Contact sheets: panels rendered with one shared camera, labels under them.
//
// Text uses stb_easy_font (Debian libstb-dev, header only, public domain): it
// turns a string into axis-aligned quads in a ~6 x 12 pixel cell, which are
// filled here as rectangles scaled by an integer factor. No font files, no
// antialiasing needed at these sizes.
#include "lodforge/render/contact_sheet.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace lodforge {
namespace {

constexpr int kLineHeight = 12;  // stb_easy_font's line advance, in font pixels

// Printable ASCII only: a newline would start a second line inside one label.
std::string printable(const std::string& s) {
  std::string out = s;
  for (char& c : out)
    if (c < 32 || c > 126) c = '?';
  return out;
}

int text_width(const std::string& text) {
  std::string copy = text;  // stb_easy_font takes a non-const char*
  return stb_easy_font_width(copy.data());
}

// Draws `text` with its top-left corner at (x, y), clipped to [clip_x0, clip_x1).
void draw_text(Image& img, int x, int y, const std::string& text, int scale, const Vec3& color,
               int clip_x0, int clip_x1) {
  std::string copy = text;
  // ~270 bytes per character on average (stb's estimate); be generous.
  std::vector<char> buffer(copy.size() * 600 + 64);
  const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(),
                                        static_cast<int>(buffer.size()));
  const std::uint8_t rgb[3] = {to_byte(color.x), to_byte(color.y), to_byte(color.z)};
  // Each quad is 4 vertices of 16 bytes: x, y, z as floats, then RGBA bytes.
  constexpr std::size_t kVertexBytes = 16;
  const auto vertex_xy = [&](std::size_t i) {
    float xy[2];
    std::memcpy(xy, buffer.data() + i * kVertexBytes, sizeof xy);
    return Vec2{xy[0], xy[1]};
  };
  for (std::size_t q = 0; q < static_cast<std::size_t>(std::max(quads, 0)); ++q) {
    const Vec2 first = vertex_xy(4 * q);
    float qx0 = first.x, qx1 = qx0, qy0 = first.y, qy1 = qy0;
    for (std::size_t k = 1; k < 4; ++k) {
      const Vec2 p = vertex_xy(4 * q + k);
      qx0 = std::min(qx0, p.x);
      qx1 = std::max(qx1, p.x);
      qy0 = std::min(qy0, p.y);
      qy1 = std::max(qy1, p.y);
    }
    const int px0 = std::max({0, clip_x0, x + static_cast<int>(std::lround(qx0 * scale))});
    const int px1 = std::min({img.width, clip_x1, x + static_cast<int>(std::lround(qx1 * scale))});
    const int py0 = std::max(0, y + static_cast<int>(std::lround(qy0 * scale)));
    const int py1 = std::min(img.height, y + static_cast<int>(std::lround(qy1 * scale)));
    for (int py = py0; py < py1; ++py)
      for (int px = px0; px < px1; ++px) {
        std::uint8_t* p = img.at(px, py);
        p[0] = rgb[0];
        p[1] = rgb[1];
        p[2] = rgb[2];
      }
  }
}

// One sphere containing the bounding spheres of all panels' meshes.
FrameSphere common_frame(std::span<const ContactSheetPanel> panels) {
  std::vector<FrameSphere> spheres;
  Box3 box;
  for (const auto& panel : panels) {
    if (!panel.mesh) continue;
    const FrameSphere s = bounding_sphere(*panel.mesh);
    if (s.radius <= 0) continue;
    spheres.push_back(s);
    box.add(s.center - Vec3{s.radius, s.radius, s.radius});
    box.add(s.center + Vec3{s.radius, s.radius, s.radius});
  }
  if (spheres.empty()) return {};
  FrameSphere frame{box.center(), 0};
  for (const auto& s : spheres)
    frame.radius = std::max(frame.radius, length(s.center - frame.center) + s.radius);
  return frame;
}

}  // namespace

ContactSheetResult render_contact_sheet(std::span<const ContactSheetPanel> panels,
                                        const ContactSheetOptions& options) {
  ContactSheetResult result;
  if (panels.empty()) return result;
  RenderOptions panel_options = options.panel;
  panel_options.frame = common_frame(panels);
  result.frame = panel_options.frame;
  result.panel_width = panel_options.width;
  result.panel_height = panel_options.height;

  const int n = static_cast<int>(panels.size());
  const int columns = options.columns > 0 ? std::min(options.columns, n) : n;
  const int rows = (n + columns - 1) / columns;
  const int gap = std::max(0, options.gap);
  const int scale =
      options.text_scale > 0
          ? options.text_scale
          : std::clamp(std::min(panel_options.width, panel_options.height) / 120, 1, 8);
  std::size_t max_lines = 0;
  for (const auto& panel : panels) max_lines = std::max(max_lines, panel.labels.size());
  const int line_height = kLineHeight * scale;
  const int label_height = static_cast<int>(max_lines) * line_height;
  const int row_height = panel_options.height + (max_lines ? gap / 2 + label_height : 0) + gap;

  const Vec3& bg = panel_options.background;
  Image sheet(columns * panel_options.width + (columns + 1) * gap, gap + rows * row_height, bg.x,
              bg.y, bg.z);
  const TriangleMesh empty;
  for (int i = 0; i < n; ++i) {
    const ContactSheetPanel& panel = panels[static_cast<std::size_t>(i)];
    const int x = gap + (i % columns) * (panel_options.width + gap);
    const int top = gap + (i / columns) * row_height;
    result.panel_x.push_back(x);
    result.panel_y.push_back(top);
    RenderOptions own = panel_options;
    if (panel.camera) own.camera = panel.camera;
    own.appearance = panel.appearance;
    sheet.blit(render_mesh(panel.mesh ? *panel.mesh : empty, own).image, x, top);
    int y = top + panel_options.height + gap / 2;
    for (const auto& label : panel.labels) {
      const std::string text = printable(label);
      const int width = text_width(text) * scale;
      draw_text(sheet, x + (panel_options.width - width) / 2, y, text, scale, options.text_color, x,
                x + panel_options.width);
      y += line_height;
    }
  }
  result.image = std::move(sheet);
  return result;
}

std::vector<std::string> lod_labels(std::size_t triangles, std::optional<std::size_t> child,
                                    std::optional<double> distance) {
  const std::string shown =
      child ? fmt::format("every LOD at child {}", *child) : "each LOD by its distance";
  const std::string tris = fmt::format("{} tris", triangles);
  if (!distance) return {shown, tris};
  return {fmt::format("d {:g}: {}", *distance, tris), shown};
}

}  // namespace lodforge
