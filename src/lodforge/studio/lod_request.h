#pragma once
/// The options of `lodforge lod` as the studio's page sends them: a JSON
/// object whose keys are the command's long option names without the dashes
/// ("method", "error-range", "quality": ["polygon=3"], "join": true, ...),
/// turned into the pipeline's LodOptions and into the command line that
/// asks for the same run, so a user can copy what the page did.
#include <nlohmann/json.hpp>
#include <string>

#include "lodforge/core/log.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/lod/generate_lod.h"

namespace lodforge::studio {

struct LodRequest {
  LodOptions options;
  /// --inline, --max-instances, --max-triangles: how the scene is read for
  /// the run. `reread`: one of them was given, so the run reads the scene
  /// again with them instead of taking the scene the studio loaded (with
  /// the defaults, as `lodforge lod` without them reads it).
  vrml1::ReadOptions read;
  bool reread = false;
  /// --format: "vrml97", "x3dv", "gltf", "glb", or empty: from the output's
  /// name on Save (.x3dv X3D classic, .glb / .gltf glTF, else VRML 1.0), as
  /// `lodforge lod` decides for a VRML 1.0 scene.
  std::string format;
  /// --floats-per-line, --ints-per-line, --no-tabs, --minimize: the VRML 1.0
  /// writer's options on Save.
  vrml1::WriteOptions write;
  /// --verbose: the categories whose messages (LogLevel::kMessage) the run
  /// reports besides its warnings and errors, as `lodforge lod` prints them.
  /// Not given (`verbose_given` false): every message is reported and the
  /// page's own filter picks.
  std::vector<LogCategory> verbose;
  bool verbose_given = false;
  /// `lodforge lod 'SCENE' -o 'OUTPUT' --method qem ...`: the options given,
  /// in the alphabetical order of their keys; options not given left out.
  std::string command_line;
};

/// Reads the options; `scene` and `output` name the files on the command
/// line. Throws DataError naming the option for an unknown key, a value of
/// the wrong type or out of the range `lodforge lod` accepts (whole numbers
/// where it takes integers; --format x3d, the XML encoding, which `lod` does
/// not write from VRML 1.0, the only language the studio reads).
LodRequest lod_request(const nlohmann::json& options, const std::string& scene,
                       const std::string& output);

}  // namespace lodforge::studio
