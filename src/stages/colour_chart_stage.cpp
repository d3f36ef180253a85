#include "stages/colour_chart_stage.h"

#include "carrier/advice.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "colour/chart_detection.h"
#include "colour/chart_reference.h"
#include "colour/correction_model.h"
#include "colour/delta_e.h"
#include "colour/quality_levels.h"
#include "core/error.h"
#include "core/text.h"
#include "pipeline/context.h"
#include "stages/chart_measurement.h"
#include "stages/colour_chart_options.h"
#include "stages/colour_stack.h"
#include "stages/inputs.h"
#include "stages/light_estimation.h"
#include "stages/outputs.h"
#include "stages/preprocess_steps.h"

namespace surrogate::stages {

namespace fs = std::filesystem;
using colour::kChartPatches;

namespace {

// The neutral patches whose sum fixes the white point: white 9.5 to neutral 3.5. Black 2 is
// left out: a few levels of noise or flare are a large part of it.
const std::vector<int> kWhitePointPatches{18, 19, 20, 21, 22};
// A candidate whose patches, corrected, stay this far from the chart's values on average is not
// a ColorChecker (mcc can take a shelf of books for one): a real chart under even a strong cast
// fits a 3x3 matrix to a few units.
constexpr double kPhantomMeanDeltaE = 10;
// The after-correction mean above which the run warns (FADGI 2023's 3-star limit: below it,
// the correction reaches no more than 2 stars; colour/quality_levels.cpp).
constexpr double kWarnMeanDeltaE = 3.5;

double luminance(const colour::Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// Rows [y0, y1) of image `index`, full width, as an Image (the chart's rows only).
Image readBand(const ImageStack& s, int index, int y0, int y1) {
  Image im(s.width(), y1 - y0, s.channels());
  im.transfer = s.transfer();
  s.readRows(index, y0, y1, im.pixels.data());
  return im;
}

colour::ChartPlace shifted(colour::ChartPlace p, double dy) {
  for (auto& c : p.corners) c[1] -= dy;
  return p;
}

// The frame lit most nearly along the camera's axis: the most even light on a chart lying on
// the object, and the least shadow across it.
int mostFrontalFrame(const Lights& lights) {
  int best = 0;
  for (std::size_t i = 1; i < lights.size(); ++i)
    if (lights[i][2] > lights[best][2]) best = static_cast<int>(i);
  return best;
}

// The irradiance factor of light i at full-frame pixel (u, v) on the object's plane (a chart
// lying on it, facing the camera): the light's cosine, times the inverse-square fall-off for a
// near light (1 at the frame's centre, as the near fit counts it).
double irradianceAt(const Lights& lights, const LightPlaces* places, int i, const colour::Point& at) {
  const LightPlace* near = places && i < static_cast<int>(places->lights.size()) && places->lights[i].near
                               ? &places->lights[i] : nullptr;
  if (!near) return std::max(0.0, lights[i][2]);
  const double px = at[0] - (places->frameWidth - 1) / 2.0, py = (places->frameHeight - 1) / 2.0 - at[1];
  const auto& X = near->position;
  const double dx = X[0] - px, dy = X[1] - py, dz = X[2];
  const double d2 = dx * dx + dy * dy + dz * dz, x2 = X[0] * X[0] + X[1] * X[1] + X[2] * X[2];
  return std::max(0.0, dz / std::sqrt(d2)) * x2 / d2;
}

colour::Point centreOf(const colour::PatchRegion& r) {
  colour::Point c{0, 0};
  for (const auto& p : r.corners) c[0] += p[0] / 4, c[1] += p[1] / 4;
  return c;
}

// Why the patches read in one frame are not a ColorChecker's ("" when they may be): the bottom
// row must fall from white to black, and span a real chart's range.
std::string notAChart(const colour::ChartReading& r) {
  for (int k = colour::kFirstNeutral; k + 1 < kChartPatches; ++k)
    if (!(luminance(r.patches[k].mean) > luminance(r.patches[k + 1].mean)))
      return "its bottom row does not darken from white to black";
  if (luminance(r.patches[colour::kFirstNeutral].mean) < 4 * luminance(r.patches[kChartPatches - 1].mean))
    return "its white and black patches are too alike";
  return "";
}

std::string labText(const colour::Lab& l) {
  return fixedDecimals(l.L, 2) + " " + fixedDecimals(l.a, 2) + " " + fixedDecimals(l.b, 2);
}

}  // namespace

pipeline::StageInfo ColourChartStage::info() {
  pipeline::StageInfo info = pipeline::withOptions<ColourChartOptions>(
      {kComponent, "1",
       "Colour from a chart: a ColorChecker found (or given by its corners) and measured in linear "
       "light, a correction fitted to its reference values and applied to the images the fit reads; "
       "CIEDE2000 per patch before and after",
       pipeline::PlanSlot::Colour});
  info.reads = pipeline::alwaysReads({kRgbStack, kInputImages, kLights, kLightPlaces, kStackFrame});
  return info;
}

void ColourChartStage::run(const carrier::Step& step, pipeline::Context& ctx, carrier::Result& result) {
  const ColourChartOptions options = ColourChartOptions::fromParameters(parametersOf(step), "--colour-chart");
  recordValue(result, "chart", options.chart);
  if (options.chart == "none") {
    ctx.carrier.addLog("info", step.id, "no colour chart: the images keep the colours they were given");
    return;
  }
  const auto input = ctx.get<ImageStack>(kRgbStack);
  const auto inputs = ctx.get<InputImages>(kInputImages);
  const auto lights = ctx.get<Lights>(kLights);
  const std::shared_ptr<const LightPlaces> places =
      ctx.has(kLightPlaces) ? ctx.get<LightPlaces>(kLightPlaces) : nullptr;
  if (input->channels() != 3) {
    recordValue(result, "outcome", "grey images: no colour to correct");
    return;
  }
  if (ctx.has(kStackFrame)) {
    const StackFrame f = *ctx.get<StackFrame>(kStackFrame);
    if (f.x0 != 0 || f.y0 != 0 || f.sx != 1 || f.sy != 1 || input->width() != f.fullWidth)
      throw Error(ErrorKind::Input, "--colour-chart", step.component,
                  "the chart is measured on the full frame, but an earlier step of the process list "
                  "cropped or resized the images; put ColourCorrection before Crop and Resize");
  }
  ctx.progress("Colour chart", 0);

  // The frame the chart is found (or given) in.
  int frame = mostFrontalFrame(*lights);
  if (options.named()) {
    frame = inputIndexOf(*inputs, options.chart);
    if (frame < 0)
      throw Error(ErrorKind::Usage, "--colour-chart " + options.chart, step.component,
                  "names no image of this capture (after exclusions); give a shot name such as " +
                      (inputs->empty() ? std::string("IMG_0001") : (*inputs)[0].stem));
  }
  const InputImage& chartImage = (*inputs)[frame];
  const std::string where = chartImage.relativePath;
  // A chart that cannot be measured: refused when the user named it (they asked for a
  // correction); found by the automatic search, the run goes on without one, with a warning
  // that says why (a default must not stop a capture that ran before), and the record says so.
  auto cannotUse = [&](const std::string& why) {
    if (options.named()) throw Error(ErrorKind::Input, where, step.component, why);
    result.items.clear();
    recordValue(result, "chart", options.chart);
    recordValue(result, "outcome", "a ColorChecker found in " + where + " cannot be measured: " + why +
                                       ": the images keep their colours");
    result.add("input").set("file", chartImage.fileId).set("kind", "chart-search");
    carrier::addWarning(ctx.carrier, step.id,
                        {"A ColorChecker was found in " + where + " but cannot be measured (" + why +
                             "), so the colours are not corrected",
                         carrier::Usable::Yes,
                         "the results keep the photographs' own colours, as they would without a chart",
                         "if the chart should be used, give its corners by hand (--colour-chart " + chartImage.stem +
                             ":X1,Y1,...,X4,Y4, see the user guide); if it is not a chart to use, say "
                             "--colour-chart none",
                         ""});
    ctx.progress("Colour chart", 1);
  };
  colour::ChartPlace place;
  if (options.cornersGiven) {
    std::array<colour::Point, 4> corners;
    for (int i = 0; i < 4; ++i) corners[i] = {options.corners[i][0], options.corners[i][1]};
    place = colour::chartFromCorners(corners, "--colour-chart " + options.chart + ":" + options.cornersText());
  } else {
    const Image full = readBand(*input, frame, 0, input->height());
    // mcc's search runs on one thread: work earlier steps left for later runs beside it.
    std::optional<colour::ChartPlace> found;
    ctx.besideOneThread([&] { found = colour::findChart(full); });
    std::string rejected;
    if (found) {
      rejected = notAChart(colour::readChart(full, *found));
      if (rejected.empty()) place = *found;
    }
    if (!found || !rejected.empty()) {
      const std::string what = found ? "a chart-like pattern was found but not taken: " + rejected
                                     : "no ColorChecker found";
      if (options.named())
        throw Error(ErrorKind::Input, where, step.component,
                    what + " in this image; give the chart's corners by hand: --colour-chart " + chartImage.stem +
                        ":X1,Y1,X2,Y2,X3,Y3,X4,Y4 (the outer corners of the dark skin, bluish green, black and "
                        "white patches), or --colour-chart none");
      recordValue(result, "outcome", what + " in " + where + ": the images keep their colours");
      result.add("input").set("file", chartImage.fileId).set("kind", "chart-search");
      ctx.carrier.addLog("info", step.id, what + " in " + where + " (the frame lit most nearly along the camera's "
                                          "axis); the images keep their colours. A chart elsewhere: --colour-chart IMAGE");
      ctx.progress("Colour chart", 1);
      return;
    }
  }
  for (const auto& c : place.corners)
    if (c[0] < 0 || c[1] < 0 || c[0] > input->width() - 1 || c[1] > input->height() - 1) {
      if (options.cornersGiven)
        throw Error(ErrorKind::Usage, "--colour-chart", step.component,
                    "the chart's corners reach outside the " + sizeText(input->width(), input->height()) +
                        " frame of " + where + "; give corners inside it");
      return cannotUse("the chart reaches outside the frame");
    }
  result.add("input").set("file", chartImage.fileId).set("kind", "chart");
  recordValue(result, "method", place.method);
  std::string cornerText;
  for (const auto& c : place.corners) cornerText += (cornerText.empty() ? "" : ",") + fixedDecimals(c[0], 2) + "," + fixedDecimals(c[1], 2);
  recordValue(result, "corners", cornerText, "pixels x,y: dark skin, bluish green, black, white");
  recordValue(result, "patchSide", fixedDecimals(place.patchSide, 2), "pixels");

  // Read the chart in the frames it is measured in.
  double top = place.corners[0][1], bottom = top;
  for (const auto& c : place.corners) top = std::min(top, c[1]), bottom = std::max(bottom, c[1]);
  const int y0 = std::max(0, static_cast<int>(std::floor(top)) - 2);
  const int y1 = std::min(input->height(), static_cast<int>(std::ceil(bottom)) + 3);
  const colour::ChartPlace band = shifted(place, y0);
  const auto regions = colour::patchRegions(place);
  std::vector<int> frames;
  if (options.named()) frames.push_back(frame);
  else for (int i = 0; i < input->size(); ++i) frames.push_back(i);
  std::vector<FrameReading> readings;
  std::string chartFrameReason;
  int uneven = 0;
  for (std::size_t n = 0; n < frames.size(); ++n) {
    FrameReading f;
    f.image = frames[n];
    f.reading = colour::readChart(readBand(*input, f.image, y0, y1), band);
    for (int k = 0; k < kChartPatches; ++k) f.irradiance[k] = irradianceAt(*lights, places.get(), f.image, centreOf(regions[k]));
    // A near light's fall-off over the chart is in each patch's irradiance factor, so only a
    // frame lit from infinity must light the chart evenly; clipping is judged patch by patch
    // (a frame with a clipped white still measures the other patches).
    const bool near = places && f.image < static_cast<int>(places->lights.size()) && places->lights[f.image].near;
    f.usable = near || f.reading.lightGradient <= colour::kMaxLightGradient;
    uneven += !f.usable;
    if (f.image == frame) chartFrameReason = colour::unusableReason(place, f.reading);
    if (f.image == frame && near && f.reading.lightGradient > colour::kMaxLightGradient) {
      colour::ChartReading even = f.reading;
      even.lightGradient = 0;
      chartFrameReason = colour::unusableReason(place, even);
    }
    readings.push_back(f);
    ctx.progress("Colour chart", 0.8 * (n + 1) / frames.size());
  }
  if (place.patchSide < colour::kMinPatchSide || (options.named() && !chartFrameReason.empty()))
    return cannotUse(chartFrameReason);
  const ChartMeasurement m = measureAtNormalIncidence(readings);
  if (m.framesUsable == 0)
    return cannotUse("every frame lights it unevenly (" + chartFrameReason +
                     "); re-shoot, name a target shot with --colour-chart IMAGE, or --colour-chart none");
  for (int k = 0; k < kChartPatches; ++k)
    if (!m.patches[k].measured)
      return cannotUse("patch " + std::to_string(k + 1) + " (" + colour::chartReference(options.reference).patchNames[k] +
                       ") is clipped, or lit too obliquely, in all " + std::to_string(m.framesUsable) +
                       " usable frames: re-shoot with a lower exposure, name a target shot with --colour-chart "
                       "IMAGE, or --colour-chart none");
  if (uneven > 0)
    ctx.carrier.addLog("info", step.id, std::to_string(uneven) + " frame(s) light the chart unevenly (more than " +
                                            fixedDecimals(100 * colour::kMaxLightGradient, 0) +
                                            " % from one side to the other) and were not used to measure it");
  recordValue(result, "framesMeasured", std::to_string(m.framesUsable));

  // The fit.
  const colour::ChartReference& ref = colour::chartReference(options.reference);
  const auto refRgb = colour::referenceLinearSrgb(ref);
  std::vector<colour::Rgb> measured, reference;
  std::vector<bool> use;
  for (int k = 0; k < kChartPatches; ++k) {
    measured.push_back(m.patches[k].value);
    reference.push_back(refRgb[k]);
    use.push_back(m.patches[k].measured);
  }
  std::vector<int> neutrals;
  for (int k : kWhitePointPatches)
    if (use[k]) neutrals.push_back(k);
  if (neutrals.empty())
    return cannotUse("none of its white and grey patches can be measured (clipped in every frame); expose "
                     "lower or name a frame where they are not clipped with --colour-chart IMAGE");
  const colour::ColourModelKind kind = colour::parseModelName(options.model, "--colour-model");
  const colour::ColourModel model = colour::fitColourModel(measured, reference, kind, neutrals, use);
  const std::vector<colour::Rgb> heldOut = colour::leaveOneOut(measured, reference, kind, neutrals);

  // The figures: before (the measurement at the exposure the neutrals give), after, held out.
  double refY = 0, measuredY = 0;
  for (int k : neutrals) refY += luminance(refRgb[k]), measuredY += luminance(measured[k]);
  const double exposure = measuredY > 0 ? refY / measuredY : 1;
  std::vector<double> before, after, held, afterUnitSL;
  for (int k = 0; k < kChartPatches; ++k) {
    if (!use[k]) continue;
    colour::Rgb scaled = measured[k];
    for (double& c : scaled) c *= exposure;
    const colour::Lab b = colour::labD50FromLinearSrgb(scaled);
    const colour::Lab a = colour::labD50FromLinearSrgb(model.apply(measured[k]));
    before.push_back(colour::deltaE2000(ref.lab[k], b));
    after.push_back(colour::deltaE2000(ref.lab[k], a));
    afterUnitSL.push_back(colour::deltaE2000UnitSL(ref.lab[k], a));
    held.push_back(colour::deltaE2000(ref.lab[k], colour::labD50FromLinearSrgb(heldOut[k])));
    result.add("chartPatch").set("index", std::to_string(k)).set("name", ref.patchNames[k])
        .set("reference", labText(ref.lab[k]))
        .set("measured", formatNumber(measured[k][0]) + " " + formatNumber(measured[k][1]) + " " + formatNumber(measured[k][2]))
        .set("frames", std::to_string(m.patches[k].frames))
        .set("before", labText(b)).set("corrected", labText(a))
        .set("deltaE2000Before", fixedDecimals(before.back(), 3))
        .set("deltaE2000", fixedDecimals(after.back(), 3))
        .set("deltaE2000HeldOut", fixedDecimals(held.back(), 3));
  }
  const colour::ChartFigures fb = colour::chartFigures(before), fa = colour::chartFigures(after, afterUnitSL),
                             fh = colour::chartFigures(held);
  if (!options.cornersGiven && fa.mean > kPhantomMeanDeltaE) {
    if (options.named())
      throw Error(ErrorKind::Input, where, step.component,
                  "the chart found does not fit a ColorChecker's values (mean CIEDE2000 " + fixedDecimals(fa.mean, 1) +
                      " after correction); give its corners by hand with --colour-chart " + chartImage.stem +
                      ":X1,Y1,...,X4,Y4, or --colour-chart none");
    result.items.clear();
    recordValue(result, "chart", options.chart);
    recordValue(result, "outcome", "a chart-like pattern in " + where + " does not fit a ColorChecker's values: the images keep their colours");
    result.add("input").set("file", chartImage.fileId).set("kind", "chart-search");
    ctx.carrier.addLog("info", step.id, "a chart-like pattern in " + where + " was not taken: it does not fit a "
                                        "ColorChecker's values; the images keep their colours");
    return;
  }
  for (int k = 0; k < kChartPatches; ++k)
    if (!use[k]) result.add("chartPatch").set("index", std::to_string(k)).set("name", ref.patchNames[k])
                     .set("reference", labText(ref.lab[k])).set("frames", "0");
  recordValue(result, "reference", ref.id);
  recordValue(result, "referenceTitle", ref.title);
  recordValue(result, "referenceSource", ref.source);
  recordValue(result, "model", colour::modelName(kind));
  std::string coefficients;
  for (double c : model.coefficients) coefficients += (coefficients.empty() ? "" : " ") + formatNumber(c);
  recordValue(result, "coefficients", coefficients, "rows R, G, B over the model's terms, linear light");
  recordValue(result, "whitePointPatches", std::to_string(neutrals.size()));
  recordValue(result, "deltaE2000MeanBefore", fixedDecimals(fb.mean, 3));
  recordValue(result, "deltaE2000MaxBefore", fixedDecimals(fb.max, 3));
  recordValue(result, "deltaE2000Mean", fixedDecimals(fa.mean, 3));
  recordValue(result, "deltaE2000Max", fixedDecimals(fa.max, 3));
  recordValue(result, "deltaE2000MeanHeldOut", fixedDecimals(fh.mean, 3));
  recordValue(result, "deltaE2000MaxHeldOut", fixedDecimals(fh.max, 3));
  const auto verdicts = colour::qualityLevels(fa);
  std::vector<std::string> guidelines;
  for (const auto& v : verdicts)
    if (std::find(guidelines.begin(), guidelines.end(), v.guideline) == guidelines.end()) guidelines.push_back(v.guideline);
  std::string levels;
  for (const std::string& g : guidelines) {
    const std::string best = colour::bestLevel(verdicts, g);
    const std::string text = g + ": " + (best.empty() ? "below every level" : best);
    recordValue(result, "qualityLevel", text);
    levels += (levels.empty() ? "" : "; ") + text;
  }
  recordValue(result, "outcome", "corrected");

  ctx.put<ImageStack>(kRgbStack, std::make_shared<ColourStack>(input, model));
  ctx.carrier.addLog("info", step.id,
                     "colour chart (" + ref.title + ") " + (place.method == "given" ? "given by hand" : "found") + " in " +
                         where + ", measured in " + std::to_string(m.framesUsable) + " frame(s); " +
                         colour::modelName(kind) + " fitted: CIEDE2000 mean " + fixedDecimals(fb.mean, 2) + " -> " +
                         fixedDecimals(fa.mean, 2) + ", max " + fixedDecimals(fb.max, 2) + " -> " + fixedDecimals(fa.max, 2) +
                         " (patches held out of the fit: mean " + fixedDecimals(fh.mean, 2) + "); " + levels);
  if (fa.mean > kWarnMeanDeltaE)
    carrier::addWarning(ctx.carrier, step.id,
                        {"After correction the chart's colours are still far from what they should be",
                         carrier::Usable::WithCare,
                         "the colours are closer than before, but not close enough to be quoted as measured colour",
                         "check that the chart's edition is the one named (--chart-reference), that it is evenly lit "
                         "and not glossy in the chosen frame, or try --colour-model root-polynomial",
                         "mean CIEDE2000 " + fixedDecimals(fa.mean, 2) + " after correction"});
  ctx.progress("Colour chart", 1);
}

}  // namespace surrogate::stages
