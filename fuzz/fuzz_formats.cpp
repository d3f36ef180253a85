// libFuzzer target: the .ptm and .rti (HSH) readers on arbitrary bytes held in memory.
#include <cstdint>

#include "core/error.h"
#include "formats/ptm.h"
#include "formats/rti_hsh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace surrogate;
  try {
    formats::PtmFile ptm = formats::parsePtm(data, size, "fuzz.ptm");
    formats::validatePtm(ptm, "fuzz.ptm");
    (void)formats::serializePtm(ptm);
  } catch (const Error&) {
  }
  try {
    formats::HshFile hsh = formats::parseRti(data, size, "fuzz.rti");
    formats::validateHsh(hsh, "fuzz.rti");
    (void)formats::serializeRti(hsh);
  } catch (const Error&) {
  }
  return 0;
}
