#include "cli/commands.h"

namespace surrogate::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"run", "run the HRTI pipeline on a capture folder, recording everything", runCommandRun},
      {"pack", "write the archival package (BagIt folder, .tar or .zip) of a capture", runCommandPack},
      {"lights", "estimate the light directions of a capture and write an .lp file", runCommandLights},
      {"fit", "fit a PTM or HSH model to the images of an .lp file", runCommandFit},
      {"render", "relight a .ptm or .rti under a chosen light and save a PNG", runCommandRender},
      {"info", "describe a carrier, capture, image, .ptm, .rti or .lp file", runCommandInfo},
      {"report", "write the HTML report of a capture or package", runCommandReport},
      {"verify", "check a package: fixity, schemas, metadata; --reexecute re-runs its steps", runCommandVerify},
  };
  return list;
}

std::string usageHeader(const std::string& synopsis, const std::string& description) {
  return "usage: " + synopsis + "\n\n" + description + "\n\noptions:\n";
}

}  // namespace surrogate::cli
