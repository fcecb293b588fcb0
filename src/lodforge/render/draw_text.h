#pragma once
/// A tiny bitmap text renderer for labels in pictures (contact sheets, colour
/// bars): printable ASCII in a ~6 x 12 pixel cell scaled by an integer
/// factor, no font files. Other characters are drawn as '?'.
#include <climits>
#include <string>

#include "lodforge/core/math.h"
#include "lodforge/render/image.h"

namespace lodforge {

/// Line advance in font pixels (multiply by the scale).
constexpr int kTextLineHeight = 12;

/// Width of `text` in font pixels (multiply by the scale).
int text_width(const std::string& text);

/// Draws `text` with its top-left corner at (x, y), `scale` pixels per font
/// pixel (>= 1), clipped to the image and to columns [clip_x0, clip_x1).
void draw_text(Image& img, int x, int y, const std::string& text, int scale, const Vec3& color,
               int clip_x0 = 0, int clip_x1 = INT_MAX);

}  // namespace lodforge
