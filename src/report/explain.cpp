#include "report/explain.h"

#include <cmath>

#include "report/html.h"

namespace surrogate::report {

namespace {

// The RMSE (8-bit levels) at a PSNR: PSNR = 20 log10(255 / RMSE).
double rmseAt(double psnrDb) { return 255 / std::pow(10.0, psnrDb / 20); }

std::string judged(const char* cls, const std::string& text) {
  return std::string("<span class=\"") + cls + " explain\">" + text + "</span>";
}

}  // namespace

std::string explainPsnr(double db) {
  const std::string scale = " (" + displayNumber(kGoodPsnrDb, 0) + " dB and above is good, below " +
                            displayNumber(kPoorPsnrDb, 0) + " dB worrying).";
  if (db >= kGoodPsnrDb)
    return judged("ok", "Good: the model reproduces the photographs closely; higher is closer" + scale);
  if (db >= kPoorPsnrDb)
    return judged("warning", "Fair: the model reproduces the photographs with visible differences, mostly in "
                             "shadows and on glossy parts; check the relit previews" + scale);
  return judged("bad", "Worrying: the model misses much of the photographs (a moved object, wrong lights, "
                       "strong gloss or shadows); check the lights plot for the images it reproduces worst" +
                           scale);
}

std::string judgePsnr(double db) {
  const char* cls = db >= kGoodPsnrDb ? "ok" : db >= kPoorPsnrDb ? "warning" : "bad";
  const char* word = db >= kGoodPsnrDb ? "good" : db >= kPoorPsnrDb ? "fair" : "worrying";
  // The sentence without its markup, as the tooltip.
  std::string sentence = explainPsnr(db);
  sentence = sentence.substr(sentence.find('>') + 1);
  sentence.resize(sentence.size() - std::string("</span>").size());
  return std::string("<span class=\"") + cls + " explain\" title=\"" + escapeHtml(sentence) + "\">" + word + "</span>";
}

std::string explainRmse(double levels) {
  return judged(levels <= rmseAt(kGoodPsnrDb) ? "ok" : levels <= rmseAt(kPoorPsnrDb) ? "warning" : "bad",
                "On average a pixel of the model differs from the photograph by " + displayNumber(levels, 1) +
                    " of 255 levels (" + displayNumber(100 * levels / 255, 1) + " %); lower is better.");
}

std::string explainRimConfidence(double c) {
  const std::string text = "Rim " + displayNumber(c, 2) + ": the share of the circle's rim that is a clean edge. ";
  if (c >= kGoodRimConfidence) return judged("ok", text + "Good: the rim is whole, centre and radius are sure.");
  if (c >= kMinRimConfidence)
    return judged("warning", text + "Part of the rim is hidden or blurred: check the circle on the overlay (below " +
                                 displayNumber(kMinRimConfidence, 1) + " a circle is not taken for a sphere).");
  return judged("bad", text + "Worrying: below " + displayNumber(kMinRimConfidence, 1) +
                           ", detection would not take it for a sphere; check the overlay.");
}

std::string explainEvidence(double e) {
  const std::string text = "Moving highlight " + displayNumber(e, 2) +
                           ": the share of the photographs in which a highlight moves on the sphere. ";
  if (e >= kGoodEvidence) return judged("ok", text + "Good: nearly every photograph shows it.");
  if (e >= kMinEvidence)
    return judged("warning", text + "Some photographs show none: their lights may come from another sphere.");
  return judged("bad", text + "Worrying: fewer than half show one; is it a sphere?");
}

std::string explainNormalFallback(long long pixels, long long total) {
  const double share = total > 0 ? double(pixels) / double(total) : 0;
  const std::string text = displayNumber(double(pixels), 0) + " pixels (" + displayNumber(100 * share, 2) +
                           " %) of the normal map have an estimated normal: where the PTM has no brightest light "
                           "direction (flat, dark or shadowed spots), the normal is that of a matte surface fitted to "
                           "the same photographs. ";
  if (share <= kNormalFallbackWarning)
    return judged("ok", text + "Up to " + displayNumber(100 * kNormalFallbackWarning, 0) + " % is usual.");
  return judged("warning", text + "More than " + displayNumber(100 * kNormalFallbackWarning, 0) +
                               " %: large parts of the normal map are approximate.");
}

}  // namespace surrogate::report
