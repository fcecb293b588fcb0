#include "lodforge/render/color_bar.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

#include "lodforge/render/draw_text.h"

namespace lodforge {
namespace {

// The colour at t in [0,1] of evenly spaced stops, linear in between.
Vec3 ramp(const std::vector<Vec3>& stops, float t) {
  if (stops.empty()) return Vec3{1, 1, 1} * std::clamp(t, 0.f, 1.f);
  if (stops.size() == 1) return stops[0];
  const float x = std::clamp(t, 0.f, 1.f) * float(stops.size() - 1);
  const std::size_t i = std::min(std::size_t(x), stops.size() - 2);
  const float f = x - float(i);
  return stops[i] * (1 - f) + stops[i + 1] * f;
}

}  // namespace

Image add_color_bar(const Image& picture, const ColorBarOptions& o) {
  const int scale = o.text_scale > 0 ? o.text_scale : std::clamp(picture.height / 240, 1, 4);
  const int ticks = std::max(2, o.ticks);
  std::vector<std::string> labels;
  int label_width = text_width(o.title) * scale;
  for (int k = 0; k < ticks; ++k) {
    labels.push_back(fmt::format("{:.4g}", o.min + (o.max - o.min) * k / (ticks - 1)));
    label_width = std::max(label_width, text_width(labels.back()) * scale);
  }
  // Layout of the strip: margin, bar, tick gap, labels, margin.
  const int margin = 6 * scale, bar_width = 12 * scale, line = kTextLineHeight * scale;
  const int strip = margin + bar_width + margin + label_width + margin;
  Image out(picture.width + strip, picture.height, o.background.x, o.background.y, o.background.z);
  out.blit(picture, 0, 0);

  const int x0 = picture.width + margin;
  const int top = std::min(picture.height / 2, (o.title.empty() ? line / 2 : line + line / 2));
  const int bottom = std::max(top + 1, picture.height - line / 2);
  for (int y = top; y < bottom; ++y) {
    const float t = 1.f - float(y - top) / float(std::max(1, bottom - top - 1));
    const Vec3 c = ramp(o.stops, t);
    for (int x = x0; x < x0 + bar_width && x < out.width; ++x) {
      std::uint8_t* p = out.at(x, y);
      p[0] = to_byte(c.x);
      p[1] = to_byte(c.y);
      p[2] = to_byte(c.z);
    }
  }
  if (!o.title.empty())
    draw_text(out, x0, std::max(0, top - line - scale), o.title, scale, o.text_color);
  for (int k = 0; k < ticks; ++k) {
    const int y = bottom - 1 - (bottom - 1 - top) * k / (ticks - 1);
    for (int x = x0 + bar_width; x < x0 + bar_width + margin / 2; ++x)
      for (int dy = 0; dy < scale; ++dy)
        if (y + dy < out.height) {
          std::uint8_t* p = out.at(x, y + dy);
          p[0] = to_byte(o.text_color.x);
          p[1] = to_byte(o.text_color.y);
          p[2] = to_byte(o.text_color.z);
        }
    draw_text(out, x0 + bar_width + margin, y - line / 2 + scale, labels[std::size_t(k)], scale,
              o.text_color);
  }
  return out;
}

}  // namespace lodforge
