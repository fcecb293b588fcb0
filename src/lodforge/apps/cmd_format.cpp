// `lodforge format SCENE -o OUT`: read a VRML 1.0 scene and write it back
// cleanly formatted with the writer options, or as glTF (OUT.glb / .gltf).
#include <fmt/core.h>

#include <array>
#include <filesystem>

#include "lodforge/apps/commands.h"
#include "lodforge/apps/common_options.h"
#include "lodforge/apps/write_scene_gltf.h"
#include "lodforge/core/output_path.h"
#include "lodforge/io/gltf/read_gltf.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"

namespace lodforge::apps {

void add_format_command(CLI::App& app, Runner& run) {
  struct Settings {
    std::string input;
    std::string output;
    SceneReadSettings read;
    vrml1::WriteOptions write;
  };
  auto s = std::make_shared<Settings>();
  CLI::App* cmd = app.add_subcommand(
      "format", "Read a VRML 1.0 or Inventor scene and write it back formatted, or as glTF");
  cmd->add_option("SCENE", s->input,
                  "VRML 1.0 or Inventor file (.wrl, .iv, optionally .gz; - = stdin)")
      ->required();
  cmd->add_option("-o,--output", s->output,
                  "Output file (- = stdout; .gz: gzip-compressed; .glb / .gltf: converted to glTF)")
      ->required();
  add_scene_read_options(*cmd, s->read);
  add_writer_options(*cmd, s->write);
  cmd->callback([s, &run] {
    run = [s] {
      check_output_paths(std::array{OutputPath{s->output, "the formatted scene"}},
                         std::array{s->input});
      vrml1::ReadResult r = read_scene(s->input, s->read);
      if (gltf::is_gltf_path(s->output)) {
        const std::filesystem::path in(s->input);
        write_scene_gltf(r.scene, s->output,
                         s->input == "-" || !in.has_parent_path() ? "." : in.parent_path().string(),
                         0, gltf_binary_name(s->output), s->read.quiet);
      } else {
        vrml1::write_vrml1_file(r.scene, s->output, s->write);
      }
      return 0;
    };
  });
}

}  // namespace lodforge::apps
