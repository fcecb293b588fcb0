#pragma once
/// `lod` for VRML97 and X3D classic scenes: which inputs they are, the output
/// encoding (from --format or the output name), and the run from file to file.
#include <string>

#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/io/vrml97/read_vrml97.h"
#include "lodforge/lod/generate_lod.h"

namespace lodforge::apps {

/// True if `path` (not "-") starts with a VRML97 or X3D classic header or
/// is an XML document with an <X3D> element, or ends in .x3dv / .x3d.
bool is_vrml97_input(const std::string& path);

/// True if `output` is to be written in the X3D XML encoding: `format` is
/// "x3d", or it is empty and the name ends in .x3d, .x3d.gz or .x3dz.
bool writes_x3d_xml(const std::string& output, const std::string& format);

/// Reads `input` (VRML97, X3D classic or X3D XML) and sets the scene's
/// encoding for `output` (`format`: "vrml97", "x3dv", "x3d", or empty: from
/// `output`'s name, .x3dv = X3D classic, .x3d = X3D XML, otherwise the
/// input's). Throws DataError for a parse error. X3D written as VRML97
/// (`format` "vrml97") loses the statements VRML97 has not, with a warning
/// in the result's log; VRML97 written as X3D gets X3D's header and names.
vrml97::ReadResult read_vrml97_as(const std::string& input, const std::string& output,
                                  const std::string& format);

/// True if a glTF scene is to be written to `output` as VRML97 or X3D:
/// `format` is "vrml97", "x3dv" or "x3d", or it is empty and the name ends
/// in .wrl, .wrz, .x3dv, .x3dvz, .x3d or .x3dz (optionally .gz). It is then
/// read as read_vrml97_input makes it a VRML97 scene.
bool writes_vrml97_family(const std::string& output, const std::string& format);

/// True if `output` is to be written as glTF: `format` is "gltf" or "glb",
/// or it is empty and the name ends in .gltf or .glb (optionally .gz).
bool writes_gltf(const std::string& output, const std::string& format);

/// A warning in `log` naming the writer options given (those of `write` not
/// at their defaults) when the scene read from `input` is written to
/// `output` as glTF or X3D XML, which they do not lay out.
void warn_unused_writer_options(const vrml1::WriteOptions& write, const std::string& input,
                                const std::string& output, const std::string& format, Log& log);

/// Writes a scene read by read_vrml97_as (from `input`) to `output`
/// atomically: as glTF when writes_gltf (every Shape drawn a primitive in
/// world space, each LOD node a node with MSFT_lod, screen coverages for
/// `camera_angle`, or the first Viewpoint's fieldOfView when it is <= 0;
/// ImageTexture files resolved from the input's folder; what is not drawn
/// named in a warning in `log`), in X3D XML when writes_x3d_xml, else in the
/// classic encoding its header names, laid out by `write` there. Throws
/// DataError.
void write_vrml97_as(const scene::Scene& scene, const std::string& input, const std::string& output,
                     const std::string& format, double camera_angle, Log& log,
                     const vrml1::WriteOptions& write = {});

/// Reads `input` and sets the output encoding as read_vrml97_as, runs
/// generate_lod_vrml97 and writes `output` atomically (write_vrml97_as), its
/// relative file references made relative to the output's folder
/// (relocate_to_output; said on stderr unless `quiet`). Throws DataError
/// (nothing written) for a parse error or a scene the output encoding
/// cannot hold.
LodResult lod_vrml97_file(const std::string& input, const std::string& output,
                          const std::string& format, const LodOptions& options, bool quiet = false,
                          const vrml1::WriteOptions& write = {});

}  // namespace lodforge::apps
