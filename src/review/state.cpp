#include "review/state.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>

#include <nlohmann/json.hpp>

#include "capture/capture.h"
#include "carrier/carrier.h"
#include "carrier/summary.h"
#include "core/digest.h"
#include "core/error.h"
#include "hrti/light_checks.h"
#include "image/decode.h"
#include "report/embed.h"
#include "report/hemisphere.h"
#include "report/lights_section.h"
#include "report/sections.h"
#include "review/review.h"

namespace surrogate::review {

namespace fs = std::filesystem;
using nlohmann::json;

std::string captureRevision(const fs::path& capture) {
  const fs::path file = capture / capture::kCarrierPath;
  if (!fs::exists(file)) return "none";
  return "sha256:" + digestFile(file).sha256;
}

void requireRevision(const fs::path& capture, const std::string& revision) {
  if (captureRevision(capture) != revision)
    throw Error(ErrorKind::Usage, capture.string(), kStaleStep,
                "the capture's record changed since this page was loaded (another command or page ran); "
                "nothing was applied. The page now shows the new record: look at it, then apply again");
}

namespace {

// The shot of a path or name, as the run compares them (run/decisions.cpp shotOf).
std::string shotOf(const std::string& name) {
  const auto slash = name.find_last_of('/');
  const std::string base = slash == std::string::npos ? name : name.substr(slash + 1);
  const std::string stem = fs::path(base).stem().string();
  return stem.empty() ? base : stem;
}

std::optional<double> numberOf(const carrier::DataItem& d, const char* name) {
  try {
    if (d.get(name)) return d.number(name);
  } catch (const Error&) {
    // not a number: left out of the page
  }
  return std::nullopt;
}

json intervention(const carrier::Intervention& i) {
  return {{"kind", i.kind}, {"target", i.target}, {"value", i.value}, {"who", i.who}, {"time", i.time}, {"reason", i.reason}};
}

// The image of a data item (its `image` attribute is a file id) as the shot it belongs to.
std::string shotOfItem(const carrier::Carrier& c, const carrier::DataItem& d) {
  const std::string id = d.get("image").value_or("");
  const carrier::FileRecord* f = c.findFile(id);
  return shotOf(f ? f->path : id);
}

// The checks whose failure stopped the last run: its note lists each as "- NAME: ..." (the
// stages' wording, stages/recorded_checks.cpp).
std::vector<std::string> checksThatStopped(const carrier::RunRecord& run) {
  std::vector<std::string> out;
  if (run.outcome != "failed") return out;
  for (const std::string& note : run.notes)
    for (const std::string& name : hrti::lightCheckNames())
      if (note.find("- " + name + ":") != std::string::npos &&
          std::find(out.begin(), out.end(), name) == out.end())
        out.push_back(name);
  return out;
}

// The chart as the last ColourCorrection step recorded it (stages/colour_chart_stage.cpp):
// what was asked (chart, corners given), what came of it (outcome, method), where it is (the
// four corners in the image it was found or given in) and how well it corrected; null when no
// such step ran. The page draws the outline on that frame and offers to mark it by hand.
json chartState(const carrier::Carrier& c, const carrier::Step* step) {
  if (!step) return nullptr;
  json chart = {{"step", step->id}, {"asked", step->param("chart", "auto")}, {"cornersGiven", step->param("corners", "")},
                {"chart", nullptr}, {"outcome", nullptr}, {"method", nullptr}, {"corners", nullptr},
                {"image", nullptr}, {"imagePath", nullptr}, {"searched", nullptr}};
  const carrier::Result* r = c.findResult(step->id);
  if (!r) return chart;
  for (const carrier::DataItem* v : r->itemsOf("value")) {
    const std::string name = v->get("name").value_or(""), value = v->get("value").value_or("");
    if (name == "chart" || name == "outcome" || name == "method") chart[name] = value;
    if (name == "deltaE2000Mean" || name == "deltaE2000Max" || name == "deltaE2000MeanBefore")
      if (const auto x = numberOf(*v, "value")) chart[name] = *x;
    if (name == "corners") {
      json corners = json::array();
      double x[8];
      if (std::sscanf(value.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &x[0], &x[1], &x[2], &x[3], &x[4], &x[5], &x[6],
                      &x[7]) == 8)
        for (double k : x) corners.push_back(k);
      if (corners.size() == 8) chart["corners"] = corners;
    }
  }
  for (const carrier::DataItem* i : r->itemsOf("input")) {
    const std::string kind = i->get("kind").value_or("");
    const carrier::FileRecord* f = c.findFile(i->get("file").value_or(""));
    if (!f) continue;
    if (kind == "chart") {
      chart["image"] = shotOf(f->path);
      chart["imagePath"] = f->path;
    }
    if (kind == "chart-search") chart["searched"] = shotOf(f->path);
  }
  return chart;
}

}  // namespace

CaptureState readCaptureState(const fs::path& captureArg, const std::string& who, int threads) {
  const fs::path capture = fs::absolute(captureArg).lexically_normal();
  capture::requireCaptureFolder(capture);
  CaptureState out;
  // The revision before the carrier is read: a run that commits in between makes the page's
  // revision stale, never the other way round.
  out.revision = captureRevision(capture);
  std::optional<carrier::Carrier> c;
  if (out.revision != "none") c = carrier::loadCarrier(capture / capture::kCarrierPath);

  std::string source = "auto", lp;
  const carrier::Step* sphereStep = nullptr;
  const carrier::Step* chartStep = nullptr;
  if (c)
    for (const carrier::Step& s : c->process) {
      if (s.component == "CaptureIngest") {
        source = s.param("source", "auto");
        lp = s.param("lp", "");
      }
      if (s.component == "ImageDecode")
        for (const carrier::Param& p : s.params) out.decodeSettings.emplace_back(p.name, p.value);
      if (s.component == "SphereDetection") sphereStep = &s;
      if (s.component == "ColourCorrection") chartStep = &s;
    }
  const capture::CaptureLayout layout = capture::scanCapture(capture, threads, lp);
  for (const capture::ImageFile& f : capture::selectImages(layout, capture::parseSource(source)))
    out.frames.push_back({shotOf(f.relativePath), f.relativePath});
  const auto [width, height] = layout.frameSize();
  out.frameWidth = width;
  out.frameHeight = height;

  json state;
  state["revision"] = out.revision;
  state["capture"] = capture.string();
  state["who"] = who;
  state["frameWidth"] = width;
  state["frameHeight"] = height;
  state["dome"] = !lp.empty();
  state["checkNames"] = hrti::lightCheckNames();

  std::map<std::string, json> byShot;
  for (std::size_t n = 0; n < out.frames.size(); ++n) {
    json f;
    f["index"] = n;
    f["name"] = out.frames[n].name;
    f["path"] = out.frames[n].path;
    f["preview"] = "/frame/" + std::to_string(n) + ".jpg";
    f["highlights"] = json::array();
    f["excluded"] = nullptr;
    f["light"] = nullptr;
    byShot[out.frames[n].name] = f;
  }

  json header = {{"title", ""}, {"creators", json::array()}, {"rights", ""}, {"license", ""}, {"meta", json::array()}};
  json spheres = json::array(), checks = json::array(), decisions = json::array(), runs = json::array();
  std::string hemisphere;
  if (c) {
    header["title"] = c->header.title;
    for (const carrier::Creator& k : c->header.creators) header["creators"].push_back({{"name", k.name}, {"role", k.role}});
    header["rights"] = c->header.rights;
    header["license"] = c->header.license;
    for (const auto& [key, value] : c->header.meta) header["meta"].push_back({{"key", key}, {"value", value}});

    // The circles of the last sphere detection that ran; without one, those given by hand.
    const carrier::Result* sphereResult = sphereStep ? c->findResult(sphereStep->id) : nullptr;
    if (sphereResult)
      for (const carrier::DataItem* d : sphereResult->itemsOf("sphere")) {
        const auto cx = numberOf(*d, "cx"), cy = numberOf(*d, "cy"), r = numberOf(*d, "r");
        if (!cx || !cy || !r) continue;
        spheres.push_back({{"index", spheres.size()}, {"cx", *cx}, {"cy", *cy}, {"r", *r},
                           {"source", d->get("source").value_or("detected")}});
      }
    if (spheres.empty() && sphereStep)
      for (const carrier::Intervention* i : sphereStep->interventionsOfKind("manual-sphere")) {
        double v[3] = {0, 0, 0};
        if (std::sscanf(i->value.c_str(), "%lf,%lf,%lf", &v[0], &v[1], &v[2]) != 3) continue;
        spheres.push_back({{"index", spheres.size()}, {"cx", v[0]}, {"cy", v[1]}, {"r", v[2]}, {"source", "manual"}});
      }

    for (const carrier::Result& r : c->data) {
      const carrier::Step* step = c->findStep(r.step);
      for (const carrier::DataItem* h : r.itemsOf("highlight")) {
        const auto it = byShot.find(shotOfItem(*c, *h));
        if (it == byShot.end()) continue;
        json item = {{"sphere", std::atoi(h->get("sphere").value_or("0").c_str())},
                     {"flag", h->get("flag").value_or("")},
                     {"reason", h->get("reason").value_or("")}};
        for (const char* name : {"x", "y", "confidence"})
          if (const auto v = numberOf(*h, name)) item[name] = *v;
        it->second["highlights"].push_back(item);
      }
      for (const carrier::DataItem* k : r.itemsOf("check"))
        checks.push_back({{"name", k->get("name").value_or("")},
                          {"status", k->get("status").value_or("")},
                          {"detail", k->get("detail").value_or("")},
                          {"step", r.step},
                          {"component", step ? step->component : ""},
                          // What it checked, so that one check run after two fits reads as two.
                          {"on", step ? report::stepTitle(*step) : ""}});
    }

    std::string fitLabel;
    const std::vector<report::LightPoint> lights = report::collectLights(*c, &fitLabel);
    for (const report::LightPoint& l : lights) {
      const auto it = byShot.find(shotOf(l.image));
      if (it == byShot.end()) continue;
      json light = {{"elevation", l.elevationDeg}, {"azimuth", l.azimuthDeg}};
      if (l.rmse) light["rmse"] = *l.rmse;
      if (l.highlightConfidence) light["confidence"] = *l.highlightConfidence;
      if (l.uncertaintyDeg) light["uncertaintyDegrees"] = *l.uncertaintyDeg;
      it->second["light"] = light;
    }
    state["fitLabel"] = fitLabel;
    if (!lights.empty()) hemisphere = report::hemisphereSvg(lights, report::analyseCoverage(lights));

    const carrier::CarrierSummary summary = carrier::describeCarrier(*c);
    for (const carrier::DecisionSummary& d : summary.decisions) {
      json j = intervention(d.intervention);
      j["step"] = d.step;
      j["component"] = d.component;
      j["what"] = d.what;  // spheres from 1, as carrier::interventionText words them
      decisions.push_back(j);
      if (d.intervention.kind == "exclude-image") {
        const auto it = byShot.find(shotOf(d.intervention.target));
        if (it != byShot.end()) it->second["excluded"] = intervention(d.intervention);
      }
    }
    for (const carrier::RunRecord& r : c->header.runs)
      runs.push_back({{"id", r.id}, {"command", r.command}, {"who", r.who}, {"started", r.started},
                      {"ended", r.ended}, {"outcome", r.outcome}, {"arguments", r.arguments}, {"notes", r.notes}});
    if (!c->header.runs.empty()) state["stoppedBy"] = checksThatStopped(c->header.runs.back());
  }
  state["chart"] = c ? chartState(*c, chartStep) : json(nullptr);
  if (!state.contains("stoppedBy")) state["stoppedBy"] = json::array();
  json frames = json::array();
  for (const Frame& f : out.frames) frames.push_back(byShot[f.name]);
  state["header"] = header;
  state["frames"] = frames;
  state["spheres"] = spheres;
  state["checks"] = checks;
  state["decisions"] = decisions;
  state["runs"] = runs;
  state["hemisphere"] = hemisphere;
  // Text from the carrier and the file names may hold anything: replaced where not UTF-8
  // rather than refusing the page.
  out.json = state.dump(-1, ' ', false, json::error_handler_t::replace);
  return out;
}

std::string framePreview(const fs::path& capture, const Frame& frame,
                         const std::vector<std::pair<std::string, std::string>>& decodeSettings, int maxSide,
                         int frameLongSide) {
  image::RawDecodeSettings settings = image::RawDecodeSettings::fromParameters(decodeSettings);
  if (frameLongSide >= 2 * maxSide) settings.halfSize = true;  // only camera raw decoding reads it
  image::DecodeOptions options;
  options.acceptDamage = true;  // only shown: a damaged frame is what the user may want to see
  Image picture = image::decodeImage(capture / fs::u8path(frame.path), settings, nullptr, options);
  if (picture.transfer == Transfer::Linear) picture = image::srgbEncode(picture);
  const report::DisplayPicture display = report::displayPicture(picture, maxSide);
  return image::encodeJpeg(display.rgb, 88, frame.path);
}

}  // namespace surrogate::review
