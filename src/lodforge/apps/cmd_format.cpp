// `lodforge format SCENE -o OUT`: read a VRML 1.0 scene and write it back
// cleanly formatted with the writer options, or as VRML97 / X3D classic or
// glTF (OUT.glb / .gltf); a VRML97 or X3D classic scene is written back as
// VRML97, X3D classic or glTF; a glTF scene as GLB, glTF JSON, VRML97 or X3D.
#include <fmt/core.h>

#include <array>
#include <filesystem>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/lod_gltf.h"
#include "lodforge/apps/lod_vrml97.h"
#include "lodforge/apps/write_scene_gltf.h"
#include "lodforge/apps/write_scene_vrml97.h"
#include "lodforge/core/error.h"
#include "lodforge/core/output_path.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/io/vrml97/write_vrml97.h"

namespace lodforge::apps {

void add_format_command(CLI::App& app, Runner& run) {
  struct Settings {
    std::string input;
    std::string output;
    SceneReadSettings read;
    vrml1::WriteOptions write;
    std::string format;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "format",
      "Read a VRML 1.0 or Inventor scene and write it back formatted, or as VRML97, X3D classic "
      "or glTF; a VRML97 or X3D scene as VRML97, X3D or glTF; a glTF scene as GLB, glTF JSON, "
      "VRML97 or X3D");
  cmd->add_option("SCENE", s->input,
                  "VRML 1.0, Inventor, VRML97, X3D or glTF file (.wrl, .iv, .x3dv, .x3d, .gltf, "
                  ".glb, optionally .gz; - = stdin for VRML 1.0 / Inventor)")
      ->required();
  cmd->add_option("-o,--output", s->output,
                  "Output file (- = stdout; .gz: gzip-compressed; .glb / .gltf: converted to glTF; "
                  ".x3dv: to X3D classic; .x3d: to X3D XML)")
      ->required();
  cmd->add_option(
         "--format", s->format,
         "Convert to vrml97 (VRML97), x3dv (X3D classic), x3d (X3D XML), glb (glTF binary) or "
         "gltf (glTF JSON) (default: from the output name, .wrl VRML97 for a glTF scene, else as "
         "read)")
      ->check(CLI::IsMember({"vrml97", "x3dv", "x3d", "glb", "gltf"}));
  add_scene_read_options(*cmd, s->read);
  add_writer_options(*cmd, s->write);
  cmd->callback([s, &run] {
    run = [s] {
      check_output_paths(std::array{OutputPath{s->output, "the formatted scene"}},
                         std::array{s->input});
      make_output_folder(s->output);
      Log unused;
      warn_unused_writer_options(s->write, s->input, s->output, s->format, unused);
      if (!s->read.quiet) print_diagnostics(unused.entries());
      const bool gltf_in = is_gltf_input(s->input);
      if (gltf_in && !writes_vrml97_family(s->output, s->format)) {
        Log log;
        format_gltf_file(s->input, s->output, s->format, log);
        if (!s->read.quiet) print_diagnostics(log.entries());
        return 0;
      }
      if (gltf_in || is_vrml97_input(s->input)) {
        vrml97::ReadResult r = read_vrml97_as(s->input, s->output, s->format);
        // A glTF output takes its images from the input's folder instead.
        if (!writes_gltf(s->output, s->format))
          relocate_to_output(r.scene, s->input, s->output, s->read.quiet);
        write_vrml97_as(r.scene, s->input, s->output, s->format, 0, r.log, s->write);
        if (!s->read.quiet) print_diagnostics(r.log.entries());
        return 0;
      }
      vrml1::ReadResult r = read_scene(s->input, s->read);
      const bool as_gltf = writes_gltf(s->output, s->format);
      const std::string as_vrml97 = vrml97_format_of(s->format, s->output);
      // A glTF output takes its images from the input's folder instead.
      if (!as_gltf) relocate_to_output(r.scene, s->input, s->output, s->read.quiet);
      if (!as_vrml97.empty()) {
        write_scene_vrml97(r.scene, s->output, as_vrml97, s->read.quiet, s->write);
      } else if (as_gltf) {
        const std::filesystem::path in(s->input);
        write_scene_gltf(r.scene, s->output,
                         s->input == "-" || !in.has_parent_path() ? "." : in.parent_path().string(),
                         0, s->format.empty() ? gltf_binary_name(s->output) : s->format == "glb",
                         s->read.quiet);
      } else {
        vrml1::write_vrml1_file(r.scene, s->output, s->write);
      }
      return 0;
    };
  });
}

}  // namespace lodforge::apps
