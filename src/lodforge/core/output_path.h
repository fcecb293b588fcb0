#pragma once
/// Which paths a command may write its outputs to. write_file_atomic replaces
/// a file by renaming a temporary file onto it, which must only ever happen to
/// a regular file or a new path: renaming onto a device node, FIFO or socket
/// would replace the node itself, and onto a directory fails late. A symbolic
/// link stays a link: the file at the end of its chain is replaced.
///
/// Commands call check_output_paths with all their outputs and inputs before
/// doing any work, so a refused output leaves every file as it was.
#include <filesystem>
#include <span>
#include <string>

namespace lodforge {

/// The file write_file_atomic replaces for `path`: `path` itself, or for a
/// symbolic link the path its chain of links ends at (which may not exist
/// yet). Relative link targets are taken from the link's folder.
/// Throws DataError if that path is a directory, device node, FIFO or socket
/// (nothing is opened: a FIFO never blocks), or the links form a loop.
/// Precondition: path != "-".
std::filesystem::path resolve_output_path(const std::string& path);

/// One output of a command.
struct OutputPath {
  std::string path;                 ///< "-" is standard output
  std::string what = "the output";  ///< what is written there, for messages
};

/// Checks the outputs of one command against each other and its inputs.
/// Throws DataError, naming the files involved, if
///  * an output is refused by resolve_output_path;
///  * an output is, or resolves to (links, hard links, "./" prefixes), one of
///    `inputs`;
///  * two outputs are the same file, or both standard output ("-").
/// "-" inputs are standard input and never equal a file.
void check_output_paths(std::span<const OutputPath> outputs, std::span<const std::string> inputs);

}  // namespace lodforge
