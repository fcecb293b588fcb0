#pragma once
/// The options of `lodforge lod` as the studio's page sends them: a JSON
/// object whose keys are the command's long option names without the dashes
/// ("method", "error-range", "quality": ["polygon=3"], "join": true, ...),
/// turned into the pipeline's LodOptions and into the command line that
/// asks for the same run, so a user can copy what the page did.
#include <nlohmann/json.hpp>
#include <string>

#include "lodforge/lod/generate_lod.h"

namespace lodforge::studio {

struct LodRequest {
  LodOptions options;
  /// `lodforge lod 'SCENE' -o 'OUTPUT' --method qem ...`: the options given,
  /// in the alphabetical order of their keys; options not given left out.
  std::string command_line;
};

/// Reads the options; `scene` and `output` name the files on the command
/// line. Throws DataError naming the option for an unknown key, a value of
/// the wrong type or out of the range `lodforge lod` accepts.
LodRequest lod_request(const nlohmann::json& options, const std::string& scene,
                       const std::string& output);

}  // namespace lodforge::studio
