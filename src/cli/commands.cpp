#include "cli/commands.h"

namespace surrogate::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"run", "run the HRTI pipeline on a capture folder, recording everything", runCommandRun},
      {"info", "describe a carrier, capture, image, .ptm, .rti or .lp file", runCommandInfo},
  };
  return list;
}

std::string usageHeader(const std::string& synopsis, const std::string& description) {
  return "usage: " + synopsis + "\n\n" + description + "\n\noptions:\n";
}

}  // namespace surrogate::cli
