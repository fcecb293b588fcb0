#pragma once
/// A colour scale beside a picture: a vertical bar from the lowest value
/// (bottom) to the highest (top) with tick labels, so a person can read the
/// values behind the colours of a `compare --colored` mesh.
#include <string>
#include <vector>

#include "lodforge/core/math.h"
#include "lodforge/render/image.h"

namespace lodforge {

struct ColorBarOptions {
  /// Colours at evenly spaced values from `min` to `max`, linear in between
  /// (e.g. kDeviationScale of metrics/colorize_deviation.h); empty: black
  /// to white.
  std::vector<Vec3> stops;
  double min = 0;
  double max = 1;
  std::string title;   ///< written above the bar, e.g. "deviation"; may be empty
  int ticks = 5;       ///< labelled values, min and max included (>= 2)
  int text_scale = 0;  ///< font pixel size; 0 = from the picture's height
  Vec3 background{1, 1, 1};
  Vec3 text_color{0.05f, 0.05f, 0.05f};
};

/// `picture` with a strip added on its right holding the bar and its labels
/// (numbers with up to 4 significant digits); same height. A picture too low
/// for the labels gets them anyway, clipped.
Image add_color_bar(const Image& picture, const ColorBarOptions& options = {});

}  // namespace lodforge
