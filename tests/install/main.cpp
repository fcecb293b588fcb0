// Uses an installed lodforge as a user would: reads a tiny mesh from OFF text,
// simplifies it, writes it (gzip-compressed for a .gz name) and reads it back,
// and prints
// "triangles IN -> OUT (read back OUT)".
#include <lodforge/mesh/mesh_io.h>
#include <lodforge/simplify/quadric_collapse.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  // An n x n grid of squares on z = 0, two triangles each.
  const int n = 8;
  std::string off =
      "OFF\n" + std::to_string((n + 1) * (n + 1)) + " " + std::to_string(2 * n * n) + " 0\n";
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) off += std::to_string(x) + " " + std::to_string(y) + " 0\n";
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      off += "3 " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
      off += "3 " + std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(c) + "\n";
    }
  const lodforge::TriangleMesh mesh =
      lodforge::read_mesh_data(off, lodforge::MeshFormat::kOff, "grid.off");
  const lodforge::SimplifyResult r = lodforge::quadric_collapse(mesh, {.target = {.ratio = 0.25f}});
  const std::string out = argc > 1 ? argv[1] : "grid.ply.gz";
  lodforge::write_mesh(r.mesh, out);
  std::printf("triangles %zu -> %zu (read back %zu)\n", mesh.triangle_count(),
              r.mesh.triangle_count(), lodforge::read_mesh(out).triangle_count());
  return 0;
}
