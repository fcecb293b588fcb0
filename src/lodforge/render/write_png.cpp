// PNG encoding through stb_image_write, linked from Debian's libstb (so no
// translation unit here defines STB_IMAGE_WRITE_IMPLEMENTATION and no other
// module can end up with a second copy of the encoder).
#include "lodforge/render/write_png.h"

#include <stb_image_write.h>

#include "lodforge/core/error.h"
#include "lodforge/core/file_io.h"

namespace lodforge {

std::string encode_png(const Image& image) {
  if (image.empty() ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    throw DataError("PNG: the image is empty or its pixel array has the wrong size");
  std::string bytes;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.pixels.data(),
                              image.width * 4))
    throw DataError("PNG: the encoder failed");
  return bytes;
}

void write_png(const Image& image, const std::string& path) {
  write_file_atomic(path, encode_png(image));
}

}  // namespace lodforge
