#pragma once
/// Options shared by several subcommands: reading scenes, the writer options,
/// and printing the library's diagnostics.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "lodforge/core/log.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"
#include "lodforge/render/image.h"
#include "lodforge/scene/node.h"

namespace lodforge::apps {

struct SceneReadSettings {
  bool read_inlines = false;
  bool quiet = false;      ///< no warnings on stderr (-q, --quiet)
  bool silent = false;     ///< nothing on stderr but errors (--quiet=all)
  std::string quiet_mode;  ///< the value given to --quiet ("warnings" or "all")
  /// vrml1::ReadOptions::max_instances and max_triangles.
  std::uint64_t max_instances = vrml1::ReadOptions{}.max_instances;
  std::uint64_t max_triangles = vrml1::ReadOptions{}.max_triangles;
};

/// --inline, -q/--quiet[=all], and the expansion limits below.
void add_scene_read_options(CLI::App& cmd, SceneReadSettings& s);
/// --max-instances, --max-triangles: for every command that reads scenes.
void add_expansion_options(CLI::App& cmd, SceneReadSettings& s);

/// Refuses a number that is not finite ("nan", "inf", 1e999): CLI11's range
/// checks compare, and NaN passes every comparison. Chained before them.
extern const CLI::Validator kFiniteNumber;
/// --floats-per-line, --ints-per-line, --no-tabs, --minimize.
void add_writer_options(CLI::App& cmd, vrml1::WriteOptions& w);

/// Prints a diagnostic on stderr as "warning: text".
void print_diagnostic(const Diagnostic& d);
/// Prints diagnostics on stderr, the same message repeated at several places
/// once: "warning: MESSAGE (210 times, first at FILE:LINE:COLUMN)". Messages
/// are compared without their leading "FILE:LINE[:COLUMN]: " location, and
/// printed in the order of their first occurrence.
void print_diagnostics(const std::vector<Diagnostic>& diagnostics);

/// Reads a VRML 1.0 or Open Inventor scene, printing warnings on stderr unless quiet.
vrml1::ReadResult read_scene(const std::string& path, const SceneReadSettings& s);

/// Creates the folder of `target` if it is missing (nothing for "-");
/// DataError naming the folder when it cannot.
void make_output_folder(const std::string& target);

/// True if the file name `path` ends in `suffix` (lower case), in any case
/// and with an optional ".gz" after it.
bool name_ends_with(std::string path, std::string_view suffix);

/// Makes the relative file references of `scene`, read from `input`, relative
/// to the folder of `output` (scene::relocate_references) and says how many
/// changed on stderr unless `quiet`. Nothing for standard input or output.
void relocate_to_output(scene::Scene& scene, const std::string& input, const std::string& output,
                        bool quiet);

/// The same for a file's contents already read (`path` names it in messages
/// and gives the folder of its inlines).
vrml1::ReadResult read_scene_data(std::string_view data, const std::string& path,
                                  const SceneReadSettings& s);

/// `picture` with the deviation colour scale of `compare --colored` (blue 0,
/// green max / 2, red max) and its numbers beside it (render --color-bar,
/// compare --colored OUT.png).
Image add_deviation_bar(const Image& picture, double max);

}  // namespace lodforge::apps
