#include "core/advice.h"

namespace surrogate {
namespace {

// A part as a sentence's body: no trailing full stop or space (the joiner adds its own).
std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '.' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

const char* usableWords(Usable usable) {
  switch (usable) {
    case Usable::Yes: return "Usable";
    case Usable::WithCare: return "Usable with care";
    case Usable::No: return "Not usable";
  }
  return "Usable with care";
}

std::string adviceText(const Advice& advice) {
  std::string text = trimmed(advice.what) + ". " + usableWords(advice.usable);
  const std::string why = trimmed(advice.why);
  text += why.empty() ? "." : ": " + why + ".";
  text += " What to do: " + trimmed(advice.todo) + ".";
  const std::string detail = trimmed(advice.detail);
  if (!detail.empty()) text += " (" + detail + ")";
  return text;
}

}  // namespace surrogate
