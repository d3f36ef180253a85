#include "stages/registry.h"

#include "fit/fit.h"
#include "hrti/highlight_detection.h"
#include "hrti/sphere_detection.h"
#include "stages/fit_stages.h"
#include "stages/light_stages.h"
#include "stages/plan.h"
#include "stages/preprocess.h"
#include "stages/preprocess_stages.h"

namespace surrogate::stages {

void registerAnalysisStages(pipeline::StageRegistry& r) {
  r.add("SphereDetection", [] { return std::make_unique<SphereDetectionStage>(); });
  r.add("HighlightDetection", [] { return std::make_unique<HighlightDetectionStage>(); });
  r.add("LightDirections", [] { return std::make_unique<LightDirectionsStage>(); });
  r.add("LightsFromFile", [] { return std::make_unique<LightsFromFileStage>(); });
  r.add("WhiteBalance", [] { return std::make_unique<WhiteBalanceStage>(); });
  r.add("Crop", [] { return std::make_unique<CropStage>(); });
  r.add("Resize", [] { return std::make_unique<ResizeStage>(); });
  r.add("RtiFit", [] { return std::make_unique<RtiFitStage>(); });
  r.add("DerivedMaps", [] { return std::make_unique<DerivedMapsStage>(); });
}

std::vector<std::pair<std::string, std::string>> defaultParameters(const std::string& component) {
  if (component == "SphereDetection") return hrti::SphereDetectionOptions().toParameters();
  if (component == "HighlightDetection") return hrti::HighlightOptions().toParameters();
  if (component == "LightDirections")
    return {{"model", "orthographic"}, {"focalLengthMm", "0"}, {"pixelPitchMm", "0"},
            {"sphereDiameterMm", "0"}};
  if (component == "RtiFit") return fit::FitOptions().toParameters();
  // Crop and Resize have no defaults: their plan gives every parameter.
  if (component == "WhiteBalance") return WhiteBalanceOptions().toParameters();
  if (component == "DerivedMaps") return {{"model", "ptm-lrgb"}};
  return {};
}

std::string describeStage(const std::string& component) {
  if (component == "SphereDetection")
    return "Find the reflective spheres: per-pixel median of the stack, circle Hough transform on "
           "the gradient, sub-pixel circle fit";
  if (component == "HighlightDetection")
    return "Find the specular highlight on each sphere in each image: threshold, 8-connected "
           "components, value-weighted centroid nearest the sphere centre";
  if (component == "LightDirections")
    return "Light direction of each image from its highlights by the law of reflection";
  if (component == "LightsFromFile") return "Light directions given by the capture's .lp file";
  if (component == "WhiteBalance")
    return "White balance of the images the fit reads: per-channel gains in linear light (as "
           "shot, from a grey region, or given), and the encoding the fit reads (sRGB or linear)";
  if (component == "Crop")
    return "Crop the images the fit reads to a rectangle (given, or the largest clear of the "
           "spheres); light estimation keeps the full frame";
  if (component == "Resize")
    return "Reduce the images the fit reads: area-weighted mean in linear light, exact integer "
           "weights";
  if (component == "RtiFit")
    return "Least-squares fit of a per-pixel reflectance model over the light directions";
  if (component == "DerivedMaps") return "Surface normals, albedo and relit previews from a model";
  return "";
}

std::vector<PlannedStage> analysisStages(bool captureHasLp, const RunRequest& request) {
  std::vector<PlannedStage> out;
  if (captureHasLp) {
    out.push_back({"LightsFromFile", {}});
  } else {
    out.push_back({"SphereDetection", {}});
    out.push_back({"HighlightDetection", {}});
    out.push_back({"LightDirections", {}});
  }
  for (const PlannedStage& p : request.preprocessing) out.push_back(p);
  const std::vector<std::string> bases = request.bases.value_or(std::vector<std::string>{"ptm-lrgb", "hsh2"});
  for (const std::string& basis : bases) {
    const fit::Basis b = fit::parseBasis(basis);
    out.push_back({"RtiFit", {{"basis", fit::basisName(b)}, {"output", defaultFitOutput(basis)}}});
  }
  if (!bases.empty()) out.push_back({"DerivedMaps", {{"model", fit::basisName(fit::parseBasis(bases.front()))}}});
  return out;
}

}  // namespace surrogate::stages
