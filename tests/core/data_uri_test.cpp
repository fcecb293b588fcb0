// data: URIs: what data_uri writes decode_data_uri reads back, byte for byte;
// image types by their signatures.
#include "lodforge/core/data_uri.h"

#include <gtest/gtest.h>

namespace lodforge {
namespace {

TEST(DataUri, WrittenBytesReadBack) {
  for (std::size_t n = 0; n < 70; ++n) {
    std::vector<unsigned char> bytes(n);
    for (std::size_t i = 0; i < n; ++i) bytes[i] = static_cast<unsigned char>(i * 37 + 11);
    const std::string uri = data_uri("image/png", bytes);
    EXPECT_TRUE(uri.starts_with("data:image/png;base64,"));
    EXPECT_EQ(decode_data_uri(uri), bytes) << n;
  }
  EXPECT_EQ(data_uri("a/b", {'M', 'a', 'n'}), "data:a/b;base64,TWFu");
  EXPECT_EQ(data_uri("a/b", {'M', 'a'}), "data:a/b;base64,TWE=");
}

TEST(DataUri, PercentEscapesAndBadUris) {
  EXPECT_EQ(decode_data_uri("data:,a%20b"), (std::vector<unsigned char>{'a', ' ', 'b'}));
  EXPECT_EQ(decode_data_uri("data:text/plain;base64,TW Fu\n"),
            (std::vector<unsigned char>{'M', 'a', 'n'}));
  EXPECT_FALSE(decode_data_uri("texture.png"));
  EXPECT_FALSE(decode_data_uri("data:image/png;base64"));       // no comma
  EXPECT_FALSE(decode_data_uri("data:image/png;base64,TW*u"));  // not base64
}

TEST(DataUri, ImageTypesByTheirSignatures) {
  EXPECT_EQ(image_mime_type({0x89, 'P', 'N', 'G', 13, 10}), "image/png");
  EXPECT_EQ(image_mime_type({0xFF, 0xD8, 0xFF, 0xE0}), "image/jpeg");
  EXPECT_EQ(image_mime_type({'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P'}), "image/webp");
  EXPECT_EQ(image_mime_type({'G', 'I', 'F', '8', '9', 'a'}), "image/gif");
  EXPECT_EQ(image_mime_type({1, 2, 3}), "application/octet-stream");
}

}  // namespace
}  // namespace lodforge
