#include "lodforge/core/error.h"

#include <fmt/format.h>

namespace lodforge {

ParseError::ParseError(std::string file, int line, int col, const std::string& message)
    : DataError(fmt::format("{}:{}:{}: {}", file, line, col, message)),
      file_(std::move(file)),
      line_(line),
      col_(col) {}

}  // namespace lodforge
