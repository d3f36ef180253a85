#include "core/error.h"

namespace surrogate {

namespace {
std::string compose(const std::string& file, const std::string& message) {
  return file.empty() ? message : file + ": " + message;
}
}  // namespace

Error::Error(ErrorKind kind, std::string file, std::string step, std::string message)
    : std::runtime_error(compose(file, message)),
      kind_(kind),
      file_(std::move(file)),
      step_(std::move(step)),
      message_(std::move(message)) {}

std::string Error::text() const { return compose(file_, message_); }

void throwInputError(const std::string& file, const std::string& step,
                     const std::string& message) {
  throw Error(ErrorKind::Input, file, step, message);
}

}  // namespace surrogate
