#pragma once
/// A contact sheet: several meshes rendered side by side with the same camera,
/// each with lines of text under it, in one picture (the original's Figure
/// 5.5: every LOD level of a shape with its triangle count and switching
/// distance). Because all panels frame one common sphere, sizes compare.
///
/// Typical use, one panel per LOD level:
///
///   std::vector<ContactSheetPanel> panels;
///   for (std::size_t k = 0; k < levels.size(); ++k)
///     panels.push_back({.mesh = &levels[k],
///                       .labels = lod_level_labels(k, levels[k].triangle_count(),
///                                                  k == 0 ? 0.0 : ranges[k - 1])});
///   write_png(render_contact_sheet(panels, {.panel = {.width = 320, .height = 320}}).image, out);
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/render/image.h"
#include "lodforge/render/render_mesh.h"

namespace lodforge {

struct ContactSheetPanel {
  /// The mesh of this panel; nullptr or an empty mesh gives an empty panel
  /// (e.g. the empty last level of a LOD). Must outlive the call.
  const TriangleMesh* mesh = nullptr;
  /// Text lines written centred under the picture. Printable ASCII; other
  /// characters are drawn as '?'.
  std::vector<std::string> labels;
};

struct ContactSheetOptions {
  /// Size, view, colours and shading of every panel. Its `frame` is ignored:
  /// the sheet frames the bounding sphere of all panels' meshes together.
  RenderOptions panel;
  int gap = 8;         ///< pixels between panels and around the sheet
  int text_scale = 0;  ///< font pixel size multiplier; 0 = chosen from the panel height
  Vec3 text_color{0.05f, 0.05f, 0.05f};  ///< RGB in [0,1]
};

struct ContactSheetResult {
  Image image;
  int panel_width = 0;   ///< width of each panel's picture
  int panel_height = 0;  ///< height of each panel's picture (labels not included)
  /// Left edge of each panel's picture in `image`; the pictures' top edge is
  /// at `panel_top`.
  std::vector<int> panel_x;
  int panel_top = 0;
  FrameSphere frame;  ///< the common sphere all panels frame
};

/// Renders the panels left to right into one image of width
/// n * panel.width + (n + 1) * gap, with room for the longest label list under
/// the pictures; background colour from `options.panel.background`. No panels
/// gives an empty image. Throws DataError like render_mesh on bad mesh data.
ContactSheetResult render_contact_sheet(std::span<const ContactSheetPanel> panels,
                                        const ContactSheetOptions& options = {});

/// The labels of a LOD level panel: "level K", "N triangles" and, for levels
/// after the first, "from D" (the distance beyond which the level is shown,
/// in scene units, 3 significant digits).
std::vector<std::string> lod_level_labels(std::size_t level, std::size_t triangles,
                                          double switch_distance);

}  // namespace lodforge
