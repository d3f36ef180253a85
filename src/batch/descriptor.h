// Private to src/batch: a file descriptor closed however the function holding it leaves (a
// flock() on it goes with it), for the readers and writers of lists and ledgers.
//
//   Descriptor d{::open(path, O_RDONLY | O_CLOEXEC)};
//   if (d.fd < 0) ...;   // d.fd = -1 hands the descriptor on without closing it
#pragma once

#include <unistd.h>

namespace surrogate::batch {

struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace surrogate::batch
