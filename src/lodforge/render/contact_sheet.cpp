// Contact sheets: panels rendered with one shared camera, labels under them
// (render/draw_text.h).
#include "lodforge/render/contact_sheet.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "lodforge/render/draw_text.h"

namespace lodforge {
namespace {

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
  const int line_height = kTextLineHeight * scale;
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
      const int width = text_width(label) * scale;
      draw_text(sheet, x + (panel_options.width - width) / 2, y, label, scale, options.text_color,
                x, x + panel_options.width);
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
