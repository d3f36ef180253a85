#include "stages/recorded_checks.h"

#include "carrier/advice.h"

#include "core/error.h"

namespace surrogate::stages {

void recordChecks(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result,
                  const std::vector<hrti::LightCheck>& checks, const CheckWording& wording,
                  const std::function<std::string(const hrti::LightCheck&)>& fixFor) {
  std::vector<std::string> failures;
  for (const hrti::LightCheck& c : checks) {
    const carrier::Intervention* accepted = nullptr;
    for (const carrier::Intervention* i : step.interventionsOfKind(kAcceptCheck))
      if (i->target == c.name) accepted = i;
    const char* status = !c.failed ? "passed" : accepted ? "accepted" : "failed";
    result.add("check").set("name", c.name).set("status", status).set("detail", c.detail);
    if (!c.failed) continue;
    if (accepted) {
      ctx.carrier.addLog("intervention", step.id, "check " + c.name + " accepted: " + accepted->reason, accepted->who);
      carrier::addWarning(ctx.carrier, step.id,
                          {"the check " + c.name + " failed, and " + (accepted->who.empty() ? std::string("someone")
                                                                                               : accepted->who) +
                               " accepted the result on the record",
                           carrier::Usable::WithCare,
                           "the result stands on that person's judgement, which the record keeps with their reason",
                           "nothing if the reason holds; otherwise withdraw it with --forget-accept " + c.name +
                               " --reason \"...\" and follow the check's advice",
                           c.detail},
                          accepted->who);
      continue;
    }
    failures.push_back(c.name + ": " + c.detail + ". To fix: " + fixFor(c) + ". If the result is right, accept it with "
                       "--accept " + c.name + " --reason \"...\"");
  }
  if (failures.empty()) return;
  std::string text;
  for (const std::string& f : failures) text += "\n  - " + f;
  throw Error(ErrorKind::Input, "", wording.step,
              std::string(failures.size() == 1 ? "a check" : std::to_string(failures.size()) + " checks") + " on " +
                  wording.subject + " failed, so " + wording.consequence + ":" + text);
}

std::string excludeImagesFix(const hrti::LightCheck& check, const std::vector<std::string>& names) {
  std::string commands;
  for (int i : check.images)
    commands += (commands.empty() ? "" : "; ") + std::string("--exclude ") + names[static_cast<std::size_t>(i)] +
                " --reason \"...\"";
  return "leave the image(s) out: " + commands;
}

}  // namespace surrogate::stages
