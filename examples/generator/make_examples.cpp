// make_examples [DIR]: writes the example scenes of the repository into DIR
// (default: the current directory):
//
//   scene.wrl       the main example: a noisy terrain of 39 200 triangles and,
//                   around it, every kind of VRML 1.0 node the tools deal with
//                   (primitives with parts, DEF/USE, material and normal
//                   bindings, a texture given inline, text, lines, points,
//                   transforms, a camera, lights, a WWWAnchor, a Switch)
//   primitives.wrl  a small scene of Cube, Sphere, Cone and Cylinder
//
// The text is written directly with fmt, not with lodforge's writer, so the
// examples test the reader against an independent producer. The output is
// deterministic: the terrain's noise comes from an integer hash, not from a
// random generator.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/os.h>

namespace {

/// Appends formatted text to a buffer.
template <typename... Args>
void put(std::string& out, fmt::format_string<Args...> format, Args&&... args) {
  fmt::format_to(std::back_inserter(out), format, std::forward<Args>(args)...);
}

/// A hash of two integers to [0, 1): the lattice values of the value noise.
double lattice(int x, int y, std::uint32_t seed) {
  std::uint32_t h = seed ^ (static_cast<std::uint32_t>(x) * 0x8da6b343u) ^
                    (static_cast<std::uint32_t>(y) * 0xd8163841u);
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return static_cast<double>(h & 0xffffffu) / 16777216.0;
}

/// Smoothly interpolated value noise in [0, 1).
double value_noise(double x, double y, std::uint32_t seed) {
  const int ix = static_cast<int>(std::floor(x));
  const int iy = static_cast<int>(std::floor(y));
  auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
  const double fx = smooth(x - ix);
  const double fy = smooth(y - iy);
  const double a = lattice(ix, iy, seed) + fx * (lattice(ix + 1, iy, seed) - lattice(ix, iy, seed));
  const double b =
      lattice(ix, iy + 1, seed) + fx * (lattice(ix + 1, iy + 1, seed) - lattice(ix, iy + 1, seed));
  return a + fy * (b - a);
}

/// Terrain height: five octaves of value noise plus a ridge.
double terrain_height(double x, double z) {
  double h = 0.0;
  double amplitude = 12.0;
  double frequency = 0.025;
  for (std::uint32_t octave = 0; octave < 5; ++octave) {
    h += amplitude * (value_noise(x * frequency, z * frequency, 0x9e3779b9u + octave) - 0.5);
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return h + 6.0 * std::exp(-((x - 10.0) * (x - 10.0)) / 200.0);
}

/// A square terrain of `cells` x `cells` quads, each split into two
/// triangles, `size` wide, centred on the origin.
void put_terrain(std::string& out, int cells, double size) {
  const int n = cells + 1;
  const double step = size / cells;
  put(out,
      "  DEF Terrain Separator {{\n"
      "    ShapeHints {{ vertexOrdering COUNTERCLOCKWISE  shapeType UNKNOWN_SHAPE_TYPE"
      "  faceType CONVEX  creaseAngle 0.8 }}\n"
      "    Material {{ ambientColor 0.1 0.12 0.08  diffuseColor 0.42 0.52 0.3"
      "  specularColor 0.05 0.05 0.05  shininess 0.1 }}\n"
      "    Coordinate3 {{ point [");
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = -size / 2 + i * step;
      const double z = -size / 2 + j * step;
      put(out, "{}{:.3f} {:.3f} {:.3f}", i % 3 == 0 ? "\n      " : " ", x, terrain_height(x, z), z);
      if (i + 1 < n || j + 1 < n) out += ',';
    }
  }
  put(out, " ] }}\n    IndexedFaceSet {{ coordIndex [");
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      const int a = j * n + i;
      const int b = a + 1;
      const int c = a + n;
      const int d = c + 1;
      // Counter-clockwise seen from above (+y), alternating the diagonal.
      if ((i + j) % 2 == 0) {
        put(out, "\n      {}, {}, {}, -1, {}, {}, {}, -1", a, c, b, b, c, d);
      } else {
        put(out, "\n      {}, {}, {}, -1, {}, {}, {}, -1", a, c, d, a, d, b);
      }
      if (i + 1 < cells || j + 1 < cells) out += ',';
    }
  }
  put(out, " ] }}\n  }}\n");
}

/// A box of six quads with one colour per face (PER_FACE).
void put_house(std::string& out) {
  put(out,
      "  DEF House Separator {{\n"
      "    Translation {{ translation -20 2 -10 }}\n"
      "    Material {{ diffuseColor [ 0.8 0.2 0.2, 0.2 0.8 0.2, 0.2 0.2 0.8,\n"
      "                              0.8 0.8 0.2, 0.2 0.8 0.8, 0.8 0.2 0.8 ] }}\n"
      "    MaterialBinding {{ value PER_FACE }}\n"
      "    ShapeHints {{ vertexOrdering COUNTERCLOCKWISE  shapeType SOLID  faceType CONVEX }}\n"
      "    Coordinate3 {{ point [ -3 -2 -3, 3 -2 -3, 3 2 -3, -3 2 -3,\n"
      "                          -3 -2 3, 3 -2 3, 3 2 3, -3 2 3 ] }}\n"
      "    IndexedFaceSet {{ coordIndex [ 0, 3, 2, 1, -1,  4, 5, 6, 7, -1,  0, 1, 5, 4, -1,\n"
      "                                  3, 7, 6, 2, -1,  0, 4, 7, 3, -1,  1, 2, 6, 5, -1 ] }}\n"
      "    # The roof: a concave pentagon gable on each end, triangulated by the reader.\n"
      "    ShapeHints {{ faceType UNKNOWN_FACE_TYPE }}\n"
      "    MaterialBinding {{ value OVERALL }}\n"
      "    Material {{ diffuseColor 0.5 0.3 0.2 }}\n"
      "    Coordinate3 {{ point [ -3.5 2 -3.5, 3.5 2 -3.5, 0 5 -3.5, -3.5 2 3.5, 3.5 2 3.5,"
      " 0 5 3.5,\n"
      "                          0 4.5 -3.5, 0 4.5 3.5 ] }}\n"
      "    IndexedFaceSet {{ coordIndex [ 0, 6, 1, 2, -1,  3, 4, 7, 5, -1,"
      "  0, 2, 5, 3, -1,  1, 4, 5, 2, -1 ] }}\n"
      "  }}\n");
}

/// A pyramid with explicit normals and per-vertex colours, both indexed.
void put_pyramid(std::string& out) {
  const double s = 1.0 / std::sqrt(2.0);
  put(out,
      "  Separator {{\n"
      "    Transform {{ translation 25 4 -15  rotation 0 1 0 0.5  scaleFactor 2 2 2 }}\n"
      "    Material {{ diffuseColor [ 1 0.9 0.3, 0.9 0.5 0.1, 0.6 0.3 0.05 ] }}\n"
      "    MaterialBinding {{ value PER_VERTEX_INDEXED }}\n"
      "    Normal {{ vector [ 0 {0:.6f} {0:.6f}, {0:.6f} {0:.6f} 0, 0 {0:.6f} -{0:.6f},"
      " -{0:.6f} {0:.6f} 0, 0 -1 0 ] }}\n"
      "    NormalBinding {{ value PER_VERTEX_INDEXED }}\n"
      "    Coordinate3 {{ point [ -1 0 1, 1 0 1, 1 0 -1, -1 0 -1, 0 1.5 0 ] }}\n"
      "    IndexedFaceSet {{\n"
      "      coordIndex    [ 0, 1, 4, -1, 1, 2, 4, -1, 2, 3, 4, -1, 3, 0, 4, -1, 0, 3, 2, 1, -1 ]\n"
      "      materialIndex [ 2, 2, 0, -1, 2, 2, 0, -1, 2, 2, 0, -1, 2, 2, 0, -1, 1, 1, 1, 1, -1 ]\n"
      "      normalIndex   [ 0, 0, 0, -1, 1, 1, 1, -1, 2, 2, 2, -1, 3, 3, 3, -1, 4, 4, 4, 4, -1 ]\n"
      "    }}\n"
      "  }}\n",
      s);
}

/// A quad carrying an 8 x 8 checker texture given inline (SFImage).
void put_textured_sign(std::string& out) {
  put(out,
      "  Separator {{\n"
      "    Translation {{ translation 0 6 -30 }}\n"
      "    Texture2 {{ wrapS REPEAT  wrapT REPEAT  image 8 8 3");
  for (int y = 0; y < 8; ++y) {
    put(out, "\n      ");
    for (int x = 0; x < 8; ++x) {
      put(out, "{}0x{:06X}", x == 0 ? "" : " ", (x + y) % 2 == 0 ? 0xE8D070 : 0x305080);
    }
  }
  put(out,
      " }}\n"
      "    Texture2Transform {{ translation 0.25 0  rotation 0.1  scaleFactor 2 2  center 0.5 0.5 "
      "}}\n"
      "    TextureCoordinate2 {{ point [ 0 0, 1 0, 1 1, 0 1 ] }}\n"
      "    Coordinate3 {{ point [ -6 -3 0, 6 -3 0, 6 3 0, -6 3 0 ] }}\n"
      "    IndexedFaceSet {{ coordIndex [ 0, 1, 2, 3, -1 ]  textureCoordIndex [ 0, 1, 2, 3, -1 ] "
      "}}\n"
      "    Texture2 {{ }}\n"
      "  }}\n");
}

/// A tree defined once and used five more times.
void put_trees(std::string& out) {
  put(out,
      "  Separator {{\n"
      "    Translation {{ translation -30 0 20 }}\n"
      "    DEF Tree Separator {{\n"
      "      Material {{ diffuseColor 0.45 0.3 0.15 }}\n"
      "      Translation {{ translation 0 2 0 }}\n"
      "      Cylinder {{ radius 0.4  height 4  parts (SIDES | BOTTOM) }}\n"
      "      Material {{ diffuseColor 0.1 0.5 0.15 }}\n"
      "      Translation {{ translation 0 4 0 }}\n"
      "      Cone {{ bottomRadius 2.5  height 5 }}\n"
      "    }}\n");
  const double offsets[][3] = {{8, 0, 3}, {4, 0, -9}, {-6, 0, 5}, {11, 0, -4}, {-3, 0, -12}};
  for (const auto& o : offsets) {
    put(out, "    Separator {{ Translation {{ translation {} {} {} }} USE Tree }}\n", o[0], o[1],
        o[2]);
  }
  put(out, "  }}\n");
}

/// Primitives with their parts and a PER_PART material binding.
void put_primitives(std::string& out, const char* indent) {
  const std::string in = indent;
  put(out,
      "{0}Separator {{\n"
      "{0}  Translation {{ translation -6 1 0 }}\n"
      "{0}  Material {{ diffuseColor 0.9 0.9 0.9  specularColor 0.6 0.6 0.6  shininess 0.6 }}\n"
      "{0}  Cube {{ width 2  height 2  depth 2 }}\n"
      "{0}  Translation {{ translation 4 0 0 }}\n"
      "{0}  Material {{ diffuseColor 0.2 0.4 0.9  transparency 0.3 }}\n"
      "{0}  Sphere {{ radius 1.2 }}\n"
      "{0}  Translation {{ translation 4 0 0 }}\n"
      "{0}  Material {{ diffuseColor [ 0.9 0.3 0.1, 0.9 0.8 0.1 ] }}\n"
      "{0}  MaterialBinding {{ value PER_PART }}\n"
      "{0}  Cone {{ bottomRadius 1  height 2.5  parts ALL }}\n"
      "{0}  Translation {{ translation 4 0 0 }}\n"
      "{0}  Material {{ diffuseColor [ 0.3 0.8 0.3, 0.8 0.3 0.3, 0.3 0.3 0.8 ] }}\n"
      "{0}  Cylinder {{ radius 1  height 2 }}\n"
      "{0}  MaterialBinding {{ value OVERALL }}\n"
      "{0}  Material {{ diffuseColor 0.7 0.7 0.2 }}\n"
      "{0}  Translation {{ translation 4 0 0 }}\n"
      "{0}  Cone {{ parts SIDES  bottomRadius 0.8  height 2 }}\n"
      "{0}  Translation {{ translation 0 0 4 }}\n"
      "{0}  Cone {{ parts BOTTOM }}\n"
      "{0}  Translation {{ translation -4 0 0 }}\n"
      "{0}  Cylinder {{ parts (SIDES | TOP)  radius 0.5  height 3 }}\n"
      "{0}  Translation {{ translation -4 0 0 }}\n"
      "{0}  Cylinder {{ parts TOP }}\n"
      "{0}  Translation {{ translation -4 0 0 }}\n"
      "{0}  Cube {{ width 3  height 0.5  depth 1 }}\n"
      "{0}}}\n",
      in);
}

/// A fence of lines and a sky of points.
void put_lines_and_points(std::string& out) {
  put(out,
      "  Separator {{\n"
      "    Material {{ diffuseColor [ 1 1 1, 1 0.5 0 ]  emissiveColor [ 0.6 0.6 0.6, 0.6 0.3 0 ] "
      "}}\n"
      "    MaterialBinding {{ value PER_PART }}\n"
      "    Coordinate3 {{ point [");
  const int posts = 12;
  for (int i = 0; i < posts; ++i) {
    const double x = -33.0 + i * 6.0;
    put(out, "\n      {} 0 35, {} 2 35,", x, x);
  }
  out.pop_back();
  put(out, " ] }}\n    IndexedLineSet {{ coordIndex [");
  for (int i = 0; i < posts; ++i) put(out, " {}, {}, -1,", 2 * i, 2 * i + 1);
  put(out, "\n      ");
  for (int i = 0; i < posts; ++i) put(out, " {},", 2 * i + 1);
  put(out, " -1 ] }}\n");
  put(out,
      "    MaterialBinding {{ value OVERALL }}\n"
      "    Material {{ emissiveColor 1 1 0.9 }}\n"
      "    Coordinate3 {{ point [");
  for (int i = 0; i < 60; ++i) {
    const double a = i * 2.399963;  // golden angle: points spread evenly
    const double r = 40.0 + 10.0 * lattice(i, 7, 1u);
    put(out, "{}{:.2f} {:.2f} {:.2f}{}", i % 4 == 0 ? "\n      " : " ", r * std::cos(a),
        45.0 + 8.0 * lattice(i, 3, 2u), r * std::sin(a), i + 1 < 60 ? "," : "");
  }
  put(out,
      " ] }}\n"
      "    PointSet {{ startIndex 0  numPoints -1 }}\n"
      "  }}\n");
}

void put_scene(std::string& out) {
  put(out,
      "#VRML V1.0 ascii\n"
      "# lodforge example scene, written by examples/generator/make_examples.cpp.\n"
      "# A terrain of 39 200 triangles and one of each kind of node around it.\n"
      "\n"
      "DEF Scene Separator {{\n"
      "  Info {{ string \"lodforge example scene: terrain, village, primitives\" }}\n"
      "  PerspectiveCamera {{ position 0 35 110  orientation 1 0 0 -0.3"
      "  focalDistance 110  heightAngle 0.785398 }}\n"
      "  DirectionalLight {{ direction -0.5 -1 -0.3  intensity 0.8 }}\n"
      "  PointLight {{ location 0 30 0  color 1 0.95 0.8  intensity 0.4 }}\n"
      "  SpotLight {{ location -20 15 -10  direction 0 -1 0  cutOffAngle 0.6"
      "  dropOffRate 0.2  intensity 0.5 }}\n");
  put_terrain(out, 140, 140.0);
  put_house(out);
  put_pyramid(out);
  put_textured_sign(out);
  put_trees(out);
  put(out,
      "  Separator {{\n"
      "    Translation {{ translation 15 8 20 }}\n"
      "    Rotation {{ rotation 0 1 0 0.785398 }}\n"
      "    Scale {{ scaleFactor 1.5 1.5 1.5 }}\n");
  put_primitives(out, "    ");
  put(out, "  }}\n");
  put(out,
      "  DEF Link WWWAnchor {{\n"
      "    name \"https://example.org/lodforge/\"\n"
      "    description \"The lodforge project\"\n"
      "    map NONE\n"
      "    Separator {{\n"
      "      MatrixTransform {{ matrix 1 0 0 0  0 1 0 0  0 0 1 0  -35 12 -35 1 }}\n"
      "      Material {{ diffuseColor 0.9 0.9 0.2  emissiveColor 0.3 0.3 0 }}\n"
      "      Sphere {{ radius 2 }}\n"
      "    }}\n"
      "  }}\n"
      "  Switch {{\n"
      "    whichChild 1\n"
      "    Separator {{ Translation {{ translation 0 20 0 }} Cube {{ }} }}\n"
      "    Separator {{ Translation {{ translation 0 20 0 }} Sphere {{ radius 0.5 }} }}\n"
      "    USE House\n"
      "  }}\n"
      "  TransformSeparator {{\n"
      "    Translation {{ translation -10 15 30 }}\n"
      "    FontStyle {{ size 4  family SANS  style BOLD }}\n"
      "    AsciiText {{ string [ \"lodforge\", \"example\" ]  spacing 1.2"
      "  justification CENTER  width [ 0, 0 ] }}\n"
      "  }}\n"
      "  Group {{\n"
      "    Translation {{ translation 0 0 0 }}\n"
      "  }}\n");
  put_lines_and_points(out);
  put(out, "}}\n");
}

void put_primitives_scene(std::string& out) {
  put(out,
      "#VRML V1.0 ascii\n"
      "# lodforge example: the four primitives, written by "
      "examples/generator/make_examples.cpp.\n"
      "\n"
      "Separator {{\n"
      "  PerspectiveCamera {{ position 2 4 16  orientation 1 0 0 -0.25 }}\n"
      "  DirectionalLight {{ direction -0.3 -0.6 -1 }}\n");
  put_primitives(out, "  ");
  put(out, "}}\n");
}

void write(const std::string& dir, const char* name, void (*build)(std::string&)) {
  std::string text;
  build(text);
  const std::string path = dir + "/" + name;
  auto file = fmt::output_file(path);
  file.print("{}", text);
  fmt::print("{}: {} bytes\n", path, text.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  try {
    write(dir, "scene.wrl", put_scene);
    write(dir, "primitives.wrl", put_primitives_scene);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_examples: %s\n", e.what());
    return 1;
  }
  return 0;
}
