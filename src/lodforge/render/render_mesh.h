#pragma once
/// Headless pictures of a triangle mesh: a small software rasteriser (z-buffer,
/// Gouraud or flat Lambert shading, per-vertex colours, textures, screen-door
/// transparency, lines, wireframe), needing no display, no GPU and no GL
/// library.
///
/// Camera: Y is up (as in VRML). The camera looks at the centre of a bounding
/// sphere from outside it, with a perspective projection whose field of view
/// just contains the sphere, so the whole mesh is in view and centred for any
/// azimuth and elevation. Azimuth 0, elevation 0 is the VRML default view
/// (camera on +Z looking towards -Z); positive azimuth orbits the camera
/// towards +X, positive elevation raises it (looking down). An explicit
/// camera (RenderOptions::camera) replaces this framing where pictures must
/// show the true perspective from a given place.
#include <cstddef>
#include <optional>
#include <span>

#include "lodforge/core/math.h"
#include "lodforge/mesh/triangle_mesh.h"
#include "lodforge/render/image.h"
#include "lodforge/render/texture_image.h"

namespace lodforge {

enum class Shading {
  /// Per-vertex normals, Gouraud shaded. The mesh's own normals if it has
  /// them; else angle-weighted face normals summed over all vertices at the
  /// same position, except at corners more than 45 degrees from their face's
  /// normal, which keep the face normal (so cubes keep sharp edges).
  kSmooth,
  kFlat,  ///< one face normal per triangle
};

/// The sphere a camera frames. A radius <= 0 means "fit the mesh itself".
struct FrameSphere {
  Vec3 center;
  float radius = 0;
};

/// An explicit perspective camera, Y up in the picture (when looking straight
/// up or down, +X is right).
struct LookAt {
  Vec3 eye;     ///< world space
  Vec3 target;  ///< the point at the centre of the picture; must differ from `eye`
  /// Radians, the full vertical angle of view (VRML PerspectiveCamera
  /// heightAngle), clamped to 1..170 degrees.
  float height_angle = static_cast<float>(kPi / 4);
};

/// The unit vector from the framed centre towards the eye for an azimuth and
/// elevation in degrees, as RenderOptions reads them: (0, 0) gives +Z.
Vec3 view_direction(float azimuth, float elevation);

/// What a scene's surfaces look like beyond the mesh's vertex colours (see
/// scene::flatten_scene_appearance). Both views must outlive the call.
struct Appearance {
  /// Triangle f shows textures[mesh.materials[f]] when the mesh has texture
  /// coordinates and that index is in range (others, and triangles of a
  /// texture with an empty image, are untextured).
  /// Bilinear, perspective-correct; the texel replaces the vertex colour
  /// (an intensity texture, and one that Texture::modulates, scales it) and
  /// is lit like it; texels with alpha below the texture's alpha_cutoff are
  /// holes.
  std::span<const Texture> textures;
  /// Empty or #V, 0..1: a surface of opacity a covers about a of the
  /// samples (an ordered dither over the supersamples), so what is behind
  /// shows through, blended when the picture is averaged down.
  std::span<const float> opacity;
};

struct RenderOptions {
  int width = 640;                          ///< pixels, 1..16384
  int height = 480;                         ///< pixels, 1..16384
  float azimuth = 30;                       ///< degrees about +Y
  float elevation = 20;                     ///< degrees above the horizontal plane, -90..90
  Vec3 background{1, 1, 1};                 ///< RGB in [0,1]
  bool use_colors = true;                   ///< use the mesh's vertex colours when it has them
  Vec3 surface_color{0.72f, 0.74f, 0.80f};  ///< RGB of meshes without (or ignoring) colours
  Shading shading = Shading::kSmooth;
  bool wireframe = false;              ///< draw triangle edges over the surface
  Vec3 wire_color{0.1f, 0.1f, 0.15f};  ///< RGB of wireframe edges
  Vec3 line_color{0.1f, 0.1f, 0.1f};   ///< RGB of the mesh's line segments without vertex colours
  float field_of_view = 30;            ///< degrees, the narrower of the two image angles
  /// Sphere to frame; radius <= 0 (the default) frames the mesh's own bounding
  /// sphere. Pictures that must compare in size (a contact sheet) share one.
  FrameSphere frame;
  /// When set, this camera is used as it is: azimuth, elevation,
  /// field_of_view and the framing are ignored (`frame` only scales the depth
  /// bias of lines), so the mesh may be small or partly out of the picture.
  std::optional<LookAt> camera;
  /// Anti-aliasing: the picture is rendered at supersample x the size and
  /// averaged down. 1 = off; 2 (the default) is smooth enough for documents.
  /// Lowered automatically when width * height * supersample^2 exceeds 64 M.
  int supersample = 2;
  /// Textures and opacity (drawn only with use_colors).
  Appearance appearance;
};

struct RenderResult {
  Image image;                      ///< width x height, opaque
  std::size_t triangles_drawn = 0;  ///< triangles in front of the camera and not degenerate
  std::size_t lines_drawn = 0;      ///< line segments (not wireframe edges) drawn
  FrameSphere frame;                ///< the sphere the camera framed
};

/// The bounding sphere used to frame `mesh`: centre of the bounding box of the
/// vertices used by triangles and lines, radius the largest distance from it
/// (radius 0 when the mesh has nothing to draw). Non-finite points are ignored.
FrameSphere bounding_sphere(const TriangleMesh& mesh);

/// Renders `mesh` (triangles and line segments) into a new image. An empty
/// mesh gives a picture of only the background. Lighting is a head light
/// (slightly above and left of the camera) plus ambient, two-sided, so
/// inconsistently oriented faces are lit too. Triangles with a non-finite
/// vertex are skipped.
/// Throws DataError if an index is out of range or an attribute array has the
/// wrong length (bad data); sizes outside 1..16384 are caller bugs (assert).
RenderResult render_mesh(const TriangleMesh& mesh, const RenderOptions& options = {});

}  // namespace lodforge
