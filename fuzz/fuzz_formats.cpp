// libFuzzer target: the .ptm (raw and JPEG-compressed), .rti (HSH) and .lp readers, and the
// PRONOM identification, on arbitrary bytes held in memory.
#include <cstdint>

#include "core/error.h"
#include <string>
#include <string_view>
#include <vector>

#include "formats/lp.h"
#include "formats/pronom.h"
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
  try {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::vector<formats::LightEntry> lines = formats::parseLp(text, "fuzz.lp");
    (void)formats::formatLp(lines, "fuzz.lp");
    (void)formats::matchLpLines("fuzz.lp", lines, {"IMG_0001.JPG", "img_0002.jpg", "IMG_0002.CR2"});
  } catch (const Error&) {
  }
  (void)formats::identifyPronom(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
