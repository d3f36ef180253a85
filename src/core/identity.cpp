#include "core/identity.h"

#include <pwd.h>
#include <unistd.h>

#include <cstdlib>

namespace surrogate {

std::string currentUserName() {
  if (const char* user = std::getenv("USER"); user && *user) return user;
  if (const passwd* entry = ::getpwuid(::geteuid()); entry && entry->pw_name && *entry->pw_name) return entry->pw_name;
  return "unknown";
}

std::string hostName() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

}  // namespace surrogate
