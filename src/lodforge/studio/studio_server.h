#pragma once
/// `lodforge studio`: a local HTTP server (cpp-httplib) that serves the
/// studio's page and a JSON API over the scenes given to it.
///
/// API (JSON bodies and answers; an error is {"error": text} with status
/// 400 bad request, 403 a path outside the allowed folders, 404 a scene not
/// loaded, 409 a run already going on):
///   GET  /api/files                  the loaded scenes: path, size, shape
///                                    counts per type, triangles, parse error
///                                    ("file:line:column: ..."), warnings
///   POST /api/open  {path}           loads one more scene
///   GET  /api/tree?path=P            scene_tree.h
///   GET  /api/geometry?path=P[&which=output]
///                                    level_geometry.h of the scene, or of
///                                    its last LOD result
///   POST /api/lod   {path, options}  starts `lod` on the scene (options as
///                                    lod_request.h reads them)
///   GET  /api/lod?path=P             the run: state (idle, running, done,
///                                    failed), progress, command line, and
///                                    when done the statistics and messages
///   POST /api/save  {path, output}   writes the last result through the
///                                    CLI's atomic writer, in the language
///                                    and with the writer options of its run
///                                    (--format, else the output's name, as
///                                    `lodforge lod`): {written, format,
///                                    bytes, messages of the conversion}
///   GET  /api/texture?path=P&file=F  the image file F of a Texture2 of
///                                    scene P (relative to its folder)
///   GET  /api/text?path=P            {path, text, edited}: the scene's text
///                                    (the re-parsed text if there is one)
///   POST /api/parse {path, text}     parses the text in place of the file,
///                                    writing nothing: {parsed: true, the
///                                    /api/files entry} or {parsed: false,
///                                    error, line, column} (the loaded scene
///                                    stays as it was)
///   POST /api/upload {name, text}    writes the scene into the server's own
///                                    temporary folder (removed at the end;
///                                    the name must be a plain file name) and
///                                    loads it; that folder is allowed from
///                                    then on
/// Every path the API takes must lie under the folders of the scenes given
/// at start (symbolic links resolved); anything else is refused. The page
/// and three.js are served from their folders only (no path leaves them).
#include <memory>
#include <string>
#include <vector>

namespace lodforge::studio {

struct StudioOptions {
  std::vector<std::string> scenes;  ///< loaded at start; their folders are the allowed ones
  std::string host = "127.0.0.1";
  int port = 8765;              ///< 0: any free port
  std::string web_root;         ///< the page's files (index.html, studio.js, studio.css)
  std::string three_root;       ///< the `three` npm package (build/, examples/jsm/)
  std::string codemirror_root;  ///< the `codemirror` 5 npm package (lib/, addon/mode/)
  int threads = 0;              ///< LodOptions::threads of the runs
};

class StudioServer {
 public:
  /// Reads the scenes (a scene that does not parse is listed with its
  /// error). Throws DataError when no scene is given or one does not exist.
  explicit StudioServer(StudioOptions options);
  ~StudioServer();
  StudioServer(const StudioServer&) = delete;
  StudioServer& operator=(const StudioServer&) = delete;

  /// Binds to host:port; returns the port. Throws DataError if it cannot.
  int bind();
  /// Serves until stop() (bind() first).
  void serve();
  /// Ends serve() and waits for a running LOD job.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lodforge::studio
