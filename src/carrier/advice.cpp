#include "carrier/advice.h"

namespace surrogate::carrier {

void addWarning(Carrier& carrier, const std::string& step, const Advice& advice, const std::string& who) {
  carrier.addLog("warning", step, adviceText(advice), who);
}

}  // namespace surrogate::carrier
