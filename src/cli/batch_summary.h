// `surrogate batch --summary`: where each item of a ledger stands, in words or as JSON. Each
// step's last attempt decides, as for the batch itself (batch/standing.h), so that the summary
// and the batch agree; earlier failed attempts are mentioned as history. Items are named as
// what they are: a capture, or a package (verify --batch, a package in a batch's list).
#pragma once

#include <string>

namespace surrogate::cli {

// Prints the summary of the ledger; returns the exit code: 0 when every item is done, else 1.
int printBatchSummary(const std::string& ledgerPath, bool json);

}  // namespace surrogate::cli
