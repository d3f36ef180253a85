// surrogate::Error: the one error type of the project.
//
// Users are photographers and archivists, not programmers. Every error says
//   - which file (or option) is at fault,
//   - which step found it,
//   - a sentence saying what is wrong and, where possible, what to do.
// The CLI prints it as "surrogate: <file>: <message>" and exits with exitCode().
//
//   throw Error(ErrorKind::Input, path, "ingest",
//               "the JPEG is truncated (no end-of-image marker); copy it from the card again");
#pragma once

#include <stdexcept>
#include <string>

namespace surrogate {

// Exit codes are a documented contract (docs/, README): keep the numbers stable.
enum class ErrorKind {
  Input = 1,          // bad or unreadable input data (capture, image, file)
  Usage = 2,          // bad command line, or an invalid package
  Fixity = 3,         // a hash does not match (verify)
  NotReproduced = 4,  // re-execution gave other results (verify)
  Internal = 5,       // a bug or an environment failure (disk full, missing schema)
};

class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, std::string file, std::string step, std::string message);

  ErrorKind kind() const { return kind_; }
  int exitCode() const { return static_cast<int>(kind_); }
  const std::string& file() const { return file_; }
  const std::string& step() const { return step_; }
  const std::string& message() const { return message_; }
  // "<file>: <message>", as what() but whole: a message quoting a file's bytes may hold a NUL,
  // where what()'s C string would end.
  std::string text() const;

 private:
  ErrorKind kind_;
  std::string file_;
  std::string step_;
  std::string message_;
};

// Shorthand for the most common case: bad input data in a named file.
[[noreturn]] void throwInputError(const std::string& file, const std::string& step,
                                  const std::string& message);

}  // namespace surrogate
