// A small software rasteriser for headless pictures of meshes.
//
// Backend choice: always this CPU rasteriser, no OSMesa. Mesa's OSMesa does
// work on this machine (Mesa 22.3, llvmpipe), but:
//  * Mesa removed the OSMesa front end in release 25.1, so the Debian package
//    will disappear; a CPU fallback would be needed anyway, and two renderers
//    mean two code paths to test, with pictures that differ between machines.
//  * llvmpipe is itself a CPU rasteriser; the pictures here are small (a few
//    hundred pixels a side) and the meshes at most a few 100 000 triangles, so
//    a plain z-buffer renders them in milliseconds to a fraction of a second.
//  * The output is then bit-for-bit deterministic everywhere (CI, any distro,
//    any thread), which the tests rely on, and there is no global GL context.
//
// Pipeline: validate the mesh -> camera framing a bounding sphere -> per-vertex
// Lambert lighting (head light + ambient, two-sided) -> z-buffered triangles
// with perspective-correct colour, texture coordinate and opacity
// interpolation, edge functions over the triangle's bounding box, sample at
// pixel centres (texels bilinear; opacity as a screen door: an ordered 4x4
// Bayer dither over the supersamples, so transparency needs no sorting) -> lines (the mesh's
// segments and the optional wireframe) with a small depth bias so they show on
// the surface they lie on -> average supersample x supersample blocks down to
// the output size.
#include "lodforge/render/render_mesh.h"

#include <fmt/core.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

#include "lodforge/core/error.h"
#include "lodforge/mesh/vertex_normals.h"

namespace lodforge {
namespace {

constexpr float kAmbient = 0.28f;
constexpr float kDiffuse = 0.72f;
// Computed smooth normals: a corner whose vertex normal differs from the face
// normal by more than this uses the face normal (like VRML's creaseAngle), so
// a cube made of 8 shared vertices still has flat sides (its corner normals are
// 54.7 degrees from each face), while curved surfaces tessellated at up to
// ~90 degrees between neighbouring faces stay smooth.
constexpr float kCreaseCos = 0.7071f;  // cos 45 degrees
// Margin around the framed sphere, as a fraction of its radius.
constexpr float kFrameMargin = 0.04f;
// Lines are drawn over a surface at the same depth: they win within this
// fraction of the framed sphere's radius.
constexpr float kLineDepthBias = 0.01f;
constexpr float kMinAngle = static_cast<float>(kPi / 180);        // 1 degree
constexpr float kMaxAngle = static_cast<float>(170 * kPi / 180);  // 170 degrees

void validate(const TriangleMesh& mesh) {
  const std::size_t nv = mesh.positions.size();
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (auto i : mesh.triangles[f])
      if (i >= nv)
        throw DataError(
            fmt::format("render: triangle {} uses vertex {}, the mesh has {} vertices", f, i, nv));
  for (std::size_t l = 0; l < mesh.lines.size(); ++l)
    for (auto i : mesh.lines[l])
      if (i >= nv)
        throw DataError(fmt::format(
            "render: line segment {} uses vertex {}, the mesh has {} vertices", l, i, nv));
  if (!mesh.normals.empty() && mesh.normals.size() != nv)
    throw DataError(fmt::format("render: {} normals for {} vertices", mesh.normals.size(), nv));
  if (!mesh.colors.empty() && mesh.colors.size() != nv)
    throw DataError(fmt::format("render: {} colours for {} vertices", mesh.colors.size(), nv));
}

// The appearance's arrays against the mesh; throws DataError like validate.
void validate(const TriangleMesh& mesh, const Appearance& look) {
  const std::size_t nv = mesh.positions.size();
  if (!look.opacity.empty() && look.opacity.size() != nv)
    throw DataError(fmt::format("render: {} opacities for {} vertices", look.opacity.size(), nv));
  if (look.textures.empty()) return;
  if (mesh.has_texcoords() && mesh.texcoords.size() != nv)
    throw DataError(
        fmt::format("render: {} texture coordinates for {} vertices", mesh.texcoords.size(), nv));
  if (mesh.has_materials() && mesh.materials.size() != mesh.triangles.size())
    throw DataError(fmt::format("render: {} triangle materials for {} triangles",
                                mesh.materials.size(), mesh.triangles.size()));
  for (const Texture& t : look.textures)
    if (t.image.pixels.size() !=
        std::size_t(std::max(t.image.width, 0)) * std::max(t.image.height, 0) * 4)
      throw DataError("render: a texture's pixel array has the wrong size");
}

struct Camera {
  Vec3 eye, right, up, forward;  // forward points into the picture
  float focal = 1;               // pixels per unit at depth 1
  float cx = 0, cy = 0;          // image centre in pixels
  float near = 0;                // points nearer than this are not drawn

  // Depth along `forward`; <= near means behind the camera or too close.
  float depth(const Vec3& p) const { return dot(p - eye, forward); }
  // Screen position (x right, y down, in pixels) of a point with depth z > 0.
  Vec2 project(const Vec3& p, float z) const {
    const Vec3 v = p - eye;
    return {cx + focal * dot(v, right) / z, cy - focal * dot(v, up) / z};
  }
};

// The framing camera looks at the frame's centre from just far enough for the
// sphere to fill the narrower image angle; an explicit camera is taken as
// given. Y is up in both: right = forward x Y, which the framing camera takes
// from the azimuth, (cos az, 0, -sin az), so that looking straight down keeps
// the orientation --view asks for.
Camera make_camera(const FrameSphere& frame, const RenderOptions& o, int w, int h) {
  Camera c;
  float half_angle = 0, distance = 0;
  if (o.camera) {
    half_angle = std::clamp(o.camera->height_angle, kMinAngle, kMaxAngle) / 2;
    const Vec3 view = o.camera->target - o.camera->eye;
    distance = length(view);
    c.eye = o.camera->eye;
    c.forward = distance > 0 ? view / distance : Vec3{0, 0, -1};
    const Vec3 right = cross(c.forward, {0, 1, 0});
    c.right = length(right) > 1e-6f ? right / length(right) : Vec3{1, 0, 0};
  } else {
    const double az = o.azimuth * kPi / 180;
    half_angle = static_cast<float>(std::clamp(o.field_of_view, 1.f, 170.f) * kPi / 360);
    const float radius = frame.radius > 0 ? frame.radius : 1.f;
    distance = radius * (1 + kFrameMargin) / std::sin(half_angle);
    const Vec3 to_eye = view_direction(o.azimuth, o.elevation);
    c.eye = frame.center + to_eye * distance;
    c.forward = -to_eye;
    c.right = {static_cast<float>(std::cos(az)), 0, static_cast<float>(-std::sin(az))};
  }
  c.up = cross(c.right, c.forward);
  // The framing camera fits the narrower image angle; a VRML camera's
  // heightAngle is the vertical one.
  const float fitted_side = static_cast<float>(o.camera ? h : std::min(w, h));
  c.focal = 0.5f * fitted_side / std::tan(half_angle);
  c.cx = 0.5f * static_cast<float>(w);
  c.cy = 0.5f * static_cast<float>(h);
  c.near = 1e-4f * distance;
  return c;
}

struct Framebuffer {
  int width, height;
  std::vector<Vec3> color;
  std::vector<float> depth;  // distance along the view direction; +inf = empty

  Framebuffer(int w, int h, const Vec3& background)
      : width(w),
        height(h),
        color(static_cast<std::size_t>(w) * h, background),
        depth(static_cast<std::size_t>(w) * h, std::numeric_limits<float>::infinity()) {}
};

struct ScreenVertex {
  Vec2 p;      // pixels
  float iz;    // 1 / depth, linear in screen space
  Vec3 c_iz;   // colour / depth, so colour interpolates perspective-correctly
  Vec2 uv_iz;  // texture coordinate / depth
  float a_iz;  // opacity / depth
};

// Wraps (REPEAT) or clamps (CLAMP) a texel index.
int texel_index(int i, int size, bool repeat) {
  if (repeat) return ((i % size) + size) % size;
  return std::clamp(i, 0, size - 1);
}

// The texel colour at (s, t), bilinear; RGB and alpha in [0,1]. t = 0 is
// the bottom of the image.
Vec3 sample(const Texture& tex, Vec2 st, float& alpha) {
  const Image& img = tex.image;
  // Whole repeats removed first, so huge coordinates keep their precision.
  if (tex.repeat_s) st.x -= std::floor(st.x);
  if (tex.repeat_t) st.y -= std::floor(st.y);
  const float u = st.x * float(img.width) - 0.5f, v = (1 - st.y) * float(img.height) - 0.5f;
  const float fu = std::floor(u), fv = std::floor(v);
  const float du = u - fu, dv = v - fv;
  const int x0 = static_cast<int>(std::clamp(fu, -2.f, float(img.width)));
  const int y0 = static_cast<int>(std::clamp(fv, -2.f, float(img.height)));
  float rgba[4] = {0, 0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const int x = texel_index(x0 + (k & 1), img.width, tex.repeat_s);
    const int y = texel_index(y0 + (k >> 1), img.height, tex.repeat_t);
    const float w = ((k & 1) ? du : 1 - du) * ((k >> 1) ? dv : 1 - dv);
    const std::uint8_t* px = img.at(x, y);
    for (int c = 0; c < 4; ++c) rgba[c] += w * float(px[c]);
  }
  alpha = rgba[3] / 255.f;
  if (tex.intensity) return Vec3{rgba[0], rgba[0], rgba[0]} / 255.f;
  return Vec3{rgba[0], rgba[1], rgba[2]} / 255.f;
}

// The 4x4 ordered-dither threshold of a sample, in (0,1): a surface covers
// the samples whose threshold is below its opacity.
float dither_threshold(int x, int y) {
  static constexpr std::uint8_t kBayer[4][4] = {
      {0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
  return (float(kBayer[y & 3][x & 3]) + 0.5f) / 16.f;
}

// How the pixels of one triangle are coloured beyond its vertex colours.
struct TriangleLook {
  const Texture* texture = nullptr;  // multiplies the interpolated colour
  bool translucent = false;          // opacity below 1 somewhere: dithered
};

float edge(const Vec2& a, const Vec2& b, float x, float y) {
  return (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x);
}

// Returns false if the triangle covers no area on screen.
bool draw_triangle(Framebuffer& fb, const ScreenVertex& a, const ScreenVertex& b,
                   const ScreenVertex& c, const TriangleLook& look) {
  const float area = edge(a.p, b.p, c.p.x, c.p.y);
  if (!(std::abs(area) > 1e-12f)) return false;
  const float inv_area = 1.f / area;
  // Bounding box clamped to the picture before converting to int (a vertex
  // just in front of the camera may project very far away).
  const auto span = [](float lo, float hi, int size, int& i0, int& i1) {
    i0 = static_cast<int>(std::floor(std::clamp(lo, 0.f, static_cast<float>(size - 1))));
    i1 = static_cast<int>(std::ceil(std::clamp(hi, 0.f, static_cast<float>(size - 1))));
  };
  int x0, x1, y0, y1;
  span(std::min({a.p.x, b.p.x, c.p.x}), std::max({a.p.x, b.p.x, c.p.x}), fb.width, x0, x1);
  span(std::min({a.p.y, b.p.y, c.p.y}), std::max({a.p.y, b.p.y, c.p.y}), fb.height, y0, y1);
  for (int y = y0; y <= y1; ++y) {
    const float sy = static_cast<float>(y) + 0.5f;
    for (int x = x0; x <= x1; ++x) {
      const float sx = static_cast<float>(x) + 0.5f;
      // Barycentric weights; all >= 0 inside whichever way the triangle winds.
      const float wa = edge(b.p, c.p, sx, sy) * inv_area;
      const float wb = edge(c.p, a.p, sx, sy) * inv_area;
      const float wc = 1.f - wa - wb;
      if (wa < 0 || wb < 0 || wc < 0) continue;
      const float iz = wa * a.iz + wb * b.iz + wc * c.iz;
      const float z = 1.f / iz;
      const std::size_t i = static_cast<std::size_t>(y) * fb.width + x;
      if (!(z < fb.depth[i])) continue;
      if (look.translucent &&
          (a.a_iz * wa + b.a_iz * wb + c.a_iz * wc) * z <= dither_threshold(x, y))
        continue;
      Vec3 color = (a.c_iz * wa + b.c_iz * wb + c.c_iz * wc) * z;
      if (look.texture) {
        float alpha = 1;
        const Vec3 texel =
            sample(*look.texture, (a.uv_iz * wa + b.uv_iz * wb + c.uv_iz * wc) * z, alpha);
        if (alpha < look.texture->alpha_cutoff) continue;
        color = {color.x * texel.x, color.y * texel.y, color.z * texel.z};
      }
      fb.depth[i] = z;
      fb.color[i] = color;
    }
  }
  return true;
}

// A line `thickness` pixels wide from p to q (depths zp, zq), depth-tested with
// a bias so it shows on the surface it lies on.
void draw_line(Framebuffer& fb, const Camera& cam, const Vec3& p, const Vec3& q, const Vec3& color,
               int thickness, float bias) {
  const float zp = cam.depth(p), zq = cam.depth(q);
  if (zp <= cam.near || zq <= cam.near) return;
  const Vec2 a = cam.project(p, zp), b = cam.project(q, zq);
  // Clip the segment's parameter range to the picture (Liang-Barsky), so a
  // segment reaching far outside is not walked pixel by pixel.
  float t0 = 0, t1 = 1;
  const float d[2] = {b.x - a.x, b.y - a.y}, o[2] = {a.x, a.y};
  const float limit[2] = {static_cast<float>(fb.width), static_cast<float>(fb.height)};
  for (int axis = 0; axis < 2; ++axis) {
    const float lo_edge = -1 - o[axis], hi_edge = limit[axis] + 1 - o[axis];
    if (d[axis] == 0) {
      if (lo_edge > 0 || hi_edge < 0) return;
      continue;
    }
    float ta = lo_edge / d[axis], tb = hi_edge / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return;
  const float len = (t1 - t0) * std::max(std::abs(d[0]), std::abs(d[1]));
  const int steps = static_cast<int>(std::ceil(len));
  const int lo = -(thickness - 1) / 2, hi = thickness / 2;
  for (int s = 0; s <= steps; ++s) {
    // 1/depth is linear in screen space, so the screen parameter t serves both.
    const float t =
        t0 + (steps > 0 ? (t1 - t0) * static_cast<float>(s) / static_cast<float>(steps) : 0.f);
    const float x = a.x + (b.x - a.x) * t, y = a.y + (b.y - a.y) * t;
    const float z = 1.f / ((1 - t) / zp + t / zq);
    const int cx = static_cast<int>(std::floor(x)), cy = static_cast<int>(std::floor(y));
    for (int dy = lo; dy <= hi; ++dy)
      for (int dx = lo; dx <= hi; ++dx) {
        const int px = cx + dx, py = cy + dy;
        if (px < 0 || py < 0 || px >= fb.width || py >= fb.height) continue;
        const std::size_t i = static_cast<std::size_t>(py) * fb.width + px;
        if (z - bias > fb.depth[i]) continue;
        fb.depth[i] = std::min(fb.depth[i], z);
        fb.color[i] = color;
      }
  }
}

Image downsample(const Framebuffer& fb, int factor) {
  Image img(fb.width / factor, fb.height / factor);
  const float norm = 1.f / static_cast<float>(factor * factor);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      Vec3 sum;
      for (int dy = 0; dy < factor; ++dy)
        for (int dx = 0; dx < factor; ++dx)
          sum += fb.color[static_cast<std::size_t>(y * factor + dy) * fb.width +
                          static_cast<std::size_t>(x * factor + dx)];
      sum *= norm;
      std::uint8_t* px = img.at(x, y);
      px[0] = to_byte(sum.x);
      px[1] = to_byte(sum.y);
      px[2] = to_byte(sum.z);
      px[3] = 255;
    }
  return img;
}

Vec3 clamp01(const Vec3& c) {
  return {std::clamp(c.x, 0.f, 1.f), std::clamp(c.y, 0.f, 1.f), std::clamp(c.z, 0.f, 1.f)};
}

}  // namespace

Vec3 view_direction(float azimuth, float elevation) {
  const double az = azimuth * kPi / 180, el = std::clamp(elevation, -90.f, 90.f) * kPi / 180;
  return {static_cast<float>(std::cos(el) * std::sin(az)), static_cast<float>(std::sin(el)),
          static_cast<float>(std::cos(el) * std::cos(az))};
}

FrameSphere bounding_sphere(const TriangleMesh& mesh) {
  std::vector<char> used(mesh.positions.size(), 0);
  for (const auto& t : mesh.triangles)
    for (auto i : t)
      if (i < used.size()) used[i] = 1;
  for (const auto& l : mesh.lines)
    for (auto i : l)
      if (i < used.size()) used[i] = 1;
  Box3 box;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i] && is_finite(mesh.positions[i])) box.add(mesh.positions[i]);
  if (box.empty()) return {};
  FrameSphere s{box.center(), 0};
  float r2 = 0;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i] && is_finite(mesh.positions[i]))
      r2 = std::max(r2, length_squared(mesh.positions[i] - s.center));
  s.radius = std::sqrt(r2);
  // A single point (or all points equal) still needs a visible extent.
  if (!(s.radius > 0)) s.radius = std::max(1e-6f, 1e-6f * length(s.center));
  return s;
}

RenderResult render_mesh(const TriangleMesh& mesh, const RenderOptions& options) {
  assert(options.width >= 1 && options.width <= 16384);
  assert(options.height >= 1 && options.height <= 16384);
  assert(options.supersample >= 1 && options.supersample <= 8);
  validate(mesh);
  const bool colored = options.use_colors && mesh.has_colors();
  const Appearance none;
  const Appearance& look = options.use_colors ? options.appearance : none;
  validate(mesh, look);

  RenderResult result;
  result.frame = options.frame.radius > 0 ? options.frame : bounding_sphere(mesh);
  // Supersampling is lowered for very large pictures, keeping the framebuffer
  // (16 bytes a sample) under about 1 GB.
  int ss = std::clamp(options.supersample, 1, 8);
  while (ss > 1 && static_cast<double>(options.width) * options.height * ss * ss > 64e6) --ss;
  const int w = options.width * ss, h = options.height * ss;
  Framebuffer fb(w, h, clamp01(options.background));
  if (result.frame.radius <= 0) {  // nothing to draw
    result.image = downsample(fb, ss);
    return result;
  }
  const Camera cam = make_camera(result.frame, options, w, h);
  const Vec3 light = normalized(-cam.forward + cam.up * 0.45f - cam.right * 0.3f);

  const bool textured = !look.textures.empty() && mesh.has_texcoords() && mesh.has_materials();
  const bool smooth = options.shading == Shading::kSmooth;
  const bool given_normals = mesh.has_normals();
  const std::vector<Vec3> computed =
      smooth && !given_normals ? angle_weighted_normals(mesh) : std::vector<Vec3>{};
  const std::vector<Vec3>& normals = given_normals ? mesh.normals : computed;

  std::vector<float> z(mesh.positions.size());
  for (std::size_t i = 0; i < z.size(); ++i)
    z[i] = is_finite(mesh.positions[i]) ? cam.depth(mesh.positions[i]) : -1.f;

  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (z[t[0]] <= cam.near || z[t[1]] <= cam.near || z[t[2]] <= cam.near) continue;
    TriangleLook tri_look;
    if (textured && mesh.materials[f] < look.textures.size() &&
        !look.textures[mesh.materials[f]].image.empty())
      tri_look.texture = &look.textures[mesh.materials[f]];
    const Vec3& p0 = mesh.positions[t[0]];
    const Vec3 fn = normalized(cross(mesh.positions[t[1]] - p0, mesh.positions[t[2]] - p0));
    // Two-sided lighting: normals of a face seen from behind are turned round.
    const float side = dot(fn, cam.eye - p0) >= 0 ? 1.f : -1.f;
    ScreenVertex sv[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = t[k];
      Vec3 n = fn;
      if (smooth) {
        const Vec3& vn = normals[v];
        if (given_normals || dot(vn, fn) >= kCreaseCos) n = vn;
      }
      const float lambert = std::max(0.f, dot(n * side, light));
      // An RGB texture replaces the colour it is lit with, an intensity
      // texture scales it (the VRML lighting model); a glTF texture scales it.
      const Vec3 base =
          tri_look.texture && !tri_look.texture->intensity && !tri_look.texture->modulates
              ? Vec3{1, 1, 1}
          : colored ? clamp01(mesh.colors[v])
                    : options.surface_color;
      const Vec3 lit = clamp01(base * (kAmbient + kDiffuse * lambert));
      sv[k].p = cam.project(mesh.positions[v], z[v]);
      sv[k].iz = 1.f / z[v];
      sv[k].c_iz = lit * sv[k].iz;
      sv[k].uv_iz = tri_look.texture ? mesh.texcoords[v] * sv[k].iz : Vec2{};
      const float opacity = look.opacity.empty() ? 1.f : std::clamp(look.opacity[v], 0.f, 1.f);
      tri_look.translucent = tri_look.translucent || opacity < 1;
      sv[k].a_iz = opacity * sv[k].iz;
    }
    if (draw_triangle(fb, sv[0], sv[1], sv[2], tri_look)) ++result.triangles_drawn;
  }

  const float bias = kLineDepthBias * result.frame.radius;
  for (const auto& l : mesh.lines) {
    if (z[l[0]] <= cam.near || z[l[1]] <= cam.near) continue;
    const Vec3 color =
        colored ? clamp01((mesh.colors[l[0]] + mesh.colors[l[1]]) * 0.5f) : options.line_color;
    draw_line(fb, cam, mesh.positions[l[0]], mesh.positions[l[1]], color, ss, bias);
    ++result.lines_drawn;
  }
  if (options.wireframe) {
    for (const auto& t : mesh.triangles) {
      if (z[t[0]] <= cam.near || z[t[1]] <= cam.near || z[t[2]] <= cam.near) continue;
      for (int k = 0; k < 3; ++k)
        draw_line(fb, cam, mesh.positions[t[k]], mesh.positions[t[(k + 1) % 3]], options.wire_color,
                  ss, bias);
    }
  }
  result.image = downsample(fb, ss);
  return result;
}

}  // namespace lodforge
