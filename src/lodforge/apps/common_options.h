#pragma once
/// Options shared by several subcommands: reading scenes, the writer options,
/// and printing the library's diagnostics.
#include <CLI/CLI.hpp>
#include <string>

#include "lodforge/core/log.h"
#include "lodforge/io/vrml1/read_vrml1.h"
#include "lodforge/io/vrml1/write_vrml1.h"

namespace lodforge::apps {

struct SceneReadSettings {
  bool read_inlines = false;
  bool quiet = false;  ///< no warnings on stderr
};

/// --inline, --quiet.
void add_scene_read_options(CLI::App& cmd, SceneReadSettings& s);

/// Refuses a number that is not finite ("nan", "inf", 1e999): CLI11's range
/// checks compare, and NaN passes every comparison. Chained before them.
extern const CLI::Validator kFiniteNumber;
/// --floats-per-line, --ints-per-line, --no-tabs, --minimize.
void add_writer_options(CLI::App& cmd, vrml1::WriteOptions& w);

/// Prints a diagnostic on stderr as "warning: text".
void print_diagnostic(const Diagnostic& d);

/// Reads a VRML 1.0 or Open Inventor scene, printing warnings on stderr unless quiet.
vrml1::ReadResult read_scene(const std::string& path, const SceneReadSettings& s);

/// The same for a file's contents already read (`path` names it in messages
/// and gives the folder of its inlines).
vrml1::ReadResult read_scene_data(std::string_view data, const std::string& path,
                                  const SceneReadSettings& s);

}  // namespace lodforge::apps
