#pragma once
/// VRML 1.0 writer. Writes everything the reader keeps, including unknown
/// nodes and fields (verbatim) and DEF/USE sharing (a node shared without a
/// name gets a generated one). Numbers are written in their shortest form that
/// reads back to the same float, so parse -> write -> parse is exact.
#include <string>

#include "lodforge/scene/node.h"

namespace lodforge::vrml1 {

struct WriteOptions {
  int floats_per_line = 6;  ///< values of float-multi fields: floats per line
  int ints_per_line = 8;    ///< values of MFLong fields: integers per line
  bool no_tabs = false;     ///< no indentation
  bool minimize = false;    ///< no indentation, no line breaks, no optional spaces
};

/// The scene as VRML 1.0 text.
std::string write_vrml1(const scene::Scene& scene, const WriteOptions& options = {});

/// Writes the scene to `path` ("-" = standard output) through a temporary
/// file that is renamed into place; a path ending in ".gz" is written
/// gzip-compressed. Throws DataError if it cannot be written.
void write_vrml1_file(const scene::Scene& scene, const std::string& path,
                      const WriteOptions& options = {});

}  // namespace lodforge::vrml1
