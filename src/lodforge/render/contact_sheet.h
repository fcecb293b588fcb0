#pragma once
/// A contact sheet: several meshes rendered with the same camera, each with
/// lines of text under it, in one picture of rows of panels (the original's
/// Figure 5.5: every LOD level of a shape with its triangle count). Because
/// all panels frame one common sphere, sizes compare; panels with a camera of
/// their own (the views from given distances) show that camera's perspective.
///
/// Typical use, one panel per LOD level:
///
///   std::vector<ContactSheetPanel> panels;
///   for (std::size_t k = 0; k < levels.size(); ++k)
///     panels.push_back({.mesh = &levels[k], .labels = lod_labels(levels[k].triangle_count(), k)});
///   write_png(render_contact_sheet(panels, {.panel = {.width = 320, .height = 320}}).image, out);
#include <cstddef>
#include <optional>
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
  /// This panel's camera; unset: the sheet's (options.panel.camera, or the
  /// common framing camera).
  std::optional<LookAt> camera;
  /// Textures and opacity of this panel's mesh (options.panel.appearance is
  /// not used: every panel's mesh has its own). Must outlive the call.
  Appearance appearance;
};

struct ContactSheetOptions {
  /// Size, view, colours and shading of every panel. Its `frame` is ignored:
  /// the sheet frames the bounding sphere of all panels' meshes together.
  RenderOptions panel;
  int columns = 0;     ///< panels per row, filled left to right; 0 = all in one row
  int gap = 8;         ///< pixels between panels and around the sheet
  int text_scale = 0;  ///< font pixel size multiplier; 0 = chosen from the panel height
  Vec3 text_color{0.05f, 0.05f, 0.05f};  ///< RGB in [0,1]
};

struct ContactSheetResult {
  Image image;
  int panel_width = 0;   ///< width of each panel's picture
  int panel_height = 0;  ///< height of each panel's picture (labels not included)
  /// Top-left corner of each panel's picture in `image`.
  std::vector<int> panel_x, panel_y;
  FrameSphere frame;  ///< the common sphere all panels frame
};

/// Renders the panels in rows of c = `columns` (all n when 0) into one image
/// of width c * panel.width + (c + 1) * gap, each row with room for the
/// longest label list under its pictures; background colour from
/// `options.panel.background`. No panels gives an empty image. Throws
/// DataError like render_mesh on bad mesh data.
ContactSheetResult render_contact_sheet(std::span<const ContactSheetPanel> panels,
                                        const ContactSheetOptions& options = {});

/// The labels of a picture of a scene with LOD nodes: what each LOD shows,
/// "every LOD at child K" (`child` set) or "each LOD by its distance", and
/// "N tris"; with the camera's `distance` the first line is "d D: N tris"
/// (D with up to 6 significant digits), then what each LOD shows.
std::vector<std::string> lod_labels(std::size_t triangles, std::optional<std::size_t> child,
                                    std::optional<double> distance = {});

}  // namespace lodforge
