#pragma once
/// `lod` for VRML97 and X3D classic scenes: which inputs they are, the output
/// encoding (from --format or the output name), and the run from file to file.
#include <string>

#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/lod/generate_lod.h"

namespace lodforge::apps {

/// True if `path` (not "-") starts with a VRML97 or X3D classic header, or
/// ends in .x3dv / .x3d.
bool is_vrml97_input(const std::string& path);

/// Reads `input` and sets the scene's encoding for `output` (`format`:
/// "vrml97", "x3dv", or empty: from `output`'s name, .x3dv = X3D classic,
/// otherwise the input's). Throws DataError for a parse error or an encoding
/// it cannot write (X3D XML). X3D written as VRML97 (`format` "vrml97") loses
/// the statements VRML97 has not, with a warning in the result's log.
vrml97::ReadResult read_vrml97_as(const std::string& input, const std::string& output,
                                  const std::string& format);

/// Reads `input`, sets the output encoding (`format`: "vrml97", "x3dv", or
/// empty: from `output`'s name, .x3dv = X3D classic, otherwise the input's),
/// runs generate_lod_vrml97 and writes `output` atomically. Throws DataError
/// (nothing written) for a parse error or an encoding it cannot write
/// (X3D XML).
LodResult lod_vrml97_file(const std::string& input, const std::string& output,
                          const std::string& format, const LodOptions& options);

}  // namespace lodforge::apps
