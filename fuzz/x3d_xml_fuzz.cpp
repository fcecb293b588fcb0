// libFuzzer target: the X3D XML reader, and the X3D XML writer on whatever
// it reads. Bad input may only raise DataError. It does not yet require the
// written text to read back (vrml97_fuzz does, for the classic encoding):
// fuzzed XML still finds names the writer passes through unchecked, which
// the corpus round trips (tests/x3dxml) do not have. The scenes are the
// classic reader's, whose LOD pipeline vrml97_fuzz covers; this target
// links the reader's module only.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "lodforge/core/error.h"
#include "lodforge/io/x3dxml/read_x3d_xml.h"
#include "lodforge/io/x3dxml/write_x3d_xml.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto read =
        lodforge::x3dxml::read_x3d_xml(text, {.source_name = "fuzz", .max_depth = 200});
    (void)lodforge::x3dxml::write_x3d_xml(read.scene);
  } catch (const lodforge::DataError&) {
  }
  return 0;
}
