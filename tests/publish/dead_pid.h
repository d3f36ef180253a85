// Test support of the publish tests: a process id that no longer runs, as a killed publish
// leaves in the name of its temporary folder.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

namespace publishtest {

// A child that has exited and been reaped: its id is free (and not reused this soon).
inline pid_t deadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

}  // namespace publishtest
