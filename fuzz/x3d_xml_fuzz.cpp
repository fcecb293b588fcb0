// libFuzzer target: the X3D XML reader, and the XML writer on whatever it
// reads: the written document must read back, to a scene that writes the
// same document again. Bad input may only raise DataError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/io/vrml97/read_x3d_xml.h"
#include "lodforge/io/vrml97/write_x3d_xml.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  lodforge::vrml97::ReadResult r;
  try {
    r = lodforge::vrml97::read_x3d_xml(text, {.source_name = "fuzz", .max_depth = 200});
  } catch (const lodforge::DataError&) {
    return 0;
  }
  std::string out;
  try {
    out = lodforge::vrml97::write_x3d_xml(r.scene);
  } catch (const lodforge::DataError&) {
    return 0;  // a PROTO whose kept text does not read
  }
  // What the writer wrote, the reader reads, and it writes the same again.
  auto back = lodforge::vrml97::read_x3d_xml(out, {.source_name = "fuzz-out", .max_depth = 200});
  if (lodforge::vrml97::write_x3d_xml(back.scene) != out) __builtin_trap();
  return 0;
}
