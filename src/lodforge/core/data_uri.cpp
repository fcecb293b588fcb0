#include "lodforge/core/data_uri.h"

#include <cstdint>
#include <cstring>

namespace lodforge {

std::string data_uri(std::string_view mime, const std::vector<unsigned char>& data) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out = "data:";
  out.append(mime).append(";base64,");
  out.reserve(out.size() + (data.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < data.size(); i += 3) {
    const std::uint32_t b0 = data[i], b1 = i + 1 < data.size() ? data[i + 1] : 0,
                        b2 = i + 2 < data.size() ? data[i + 2] : 0;
    const std::uint32_t v = b0 << 16 | b1 << 8 | b2;
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += i + 1 < data.size() ? kDigits[v >> 6 & 63] : '=';
    out += i + 2 < data.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

std::optional<std::vector<unsigned char>> decode_data_uri(std::string_view uri) {
  if (!uri.starts_with("data:")) return std::nullopt;
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) return std::nullopt;
  const std::string_view header = uri.substr(5, comma - 5), body = uri.substr(comma + 1);
  std::vector<unsigned char> out;
  if (header.ends_with(";base64")) {
    std::uint32_t bits = 0;
    int held = 0;
    for (const char c : body) {
      int v;
      if (c >= 'A' && c <= 'Z')
        v = c - 'A';
      else if (c >= 'a' && c <= 'z')
        v = c - 'a' + 26;
      else if (c >= '0' && c <= '9')
        v = c - '0' + 52;
      else if (c == '+' || c == '-')
        v = 62;
      else if (c == '/' || c == '_')
        v = 63;
      else if (c == '=' || c == ' ' || c == '\n' || c == '\r' || c == '\t')
        continue;
      else
        return std::nullopt;
      bits = bits << 6 | std::uint32_t(v);
      held += 6;
      if (held >= 8) {
        held -= 8;
        out.push_back(static_cast<unsigned char>(bits >> held & 0xFF));
      }
    }
    return out;
  }
  const std::string text = percent_decoded(body);
  return std::vector<unsigned char>(text.begin(), text.end());
}

std::string percent_decoded(std::string_view text) {
  auto hex = [](char c) {
    return c >= '0' && c <= '9'   ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                  : -1;
  };
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size() && hex(text[i + 1]) >= 0 && hex(text[i + 2]) >= 0) {
      out.push_back(char(hex(text[i + 1]) * 16 + hex(text[i + 2])));
      i += 2;
    } else {
      out.push_back(text[i]);
    }
  }
  return out;
}

std::string image_mime_type(const std::vector<unsigned char>& bytes) {
  auto starts = [&](std::string_view magic, std::size_t at = 0) {
    return bytes.size() >= at + magic.size() &&
           std::memcmp(bytes.data() + at, magic.data(), magic.size()) == 0;
  };
  if (starts("\x89PNG")) return "image/png";
  if (starts("\xFF\xD8\xFF")) return "image/jpeg";
  if (starts("RIFF") && starts("WEBP", 8)) return "image/webp";
  if (starts("GIF8")) return "image/gif";
  if (starts("\xABKTX 20")) return "image/ktx2";
  return "application/octet-stream";
}

}  // namespace lodforge
