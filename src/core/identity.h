// Who and where: the user a decision or a lock is recorded under, and the host a batch job
// ran on.
#pragma once

#include <string>

namespace surrogate {

// $USER when set; else the account of the effective user id (a cron job, a container or a
// Slurm task often has no $USER); "unknown" when neither says.
std::string currentUserName();

// This machine's host name; "" when it cannot be read.
std::string hostName();

}  // namespace surrogate
