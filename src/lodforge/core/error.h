#pragma once
/// Exceptions for bad input. Caller bugs are asserts; bad files and bad data
/// throw these, and the command line turns them into a message and exit code 1.
#include <stdexcept>
#include <string>

namespace lodforge {

/// A file or data set that cannot be used (unreadable, inconsistent, empty).
class DataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A syntax error at a position in a text file. what() reads
/// "file:line:col: message" (line and column 1-based).
class ParseError : public DataError {
 public:
  ParseError(std::string file, int line, int col, const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return col_; }

 private:
  std::string file_;
  int line_;
  int col_;
};

}  // namespace lodforge
