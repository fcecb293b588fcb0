#pragma once
/// `data:` URIs (RFC 2397) holding an image's bytes in base64, as glTF
/// writes an embedded image and VRML97 / X3D browsers read an inline url.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lodforge {

/// "data:MIME;base64,..." of `bytes`.
std::string data_uri(std::string_view mime, const std::vector<unsigned char>& bytes);

/// The bytes a `data:` URI holds (base64 with ";base64", else
/// percent-escaped text); nullopt for another URI or a malformed one.
std::optional<std::vector<unsigned char>> decode_data_uri(std::string_view uri);

/// `text` with its URI escapes ("%20" and the like) decoded; a '%' not
/// followed by two hexadecimal digits stays as it is.
std::string percent_decoded(std::string_view text);

/// The MIME type of an image file's bytes by their signature: image/png,
/// image/jpeg, image/webp, image/gif, image/ktx2; else
/// application/octet-stream.
std::string image_mime_type(const std::vector<unsigned char>& bytes);

}  // namespace lodforge
