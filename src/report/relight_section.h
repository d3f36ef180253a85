// Private to src/report: the interactive relighting section, "Relight it yourself": every
// fitted model the carrier lists, read and converted for the page's script (embed.h,
// relightJson), and the section that holds them.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "carrier/carrier.h"
#include "report/hemisphere.h"
#include "report/report.h"

namespace surrogate::report {

// A fitted model as the interactive view shows it: its JSON (relightJson), or why it cannot
// be shown.
struct RelightModel {
  const carrier::FileRecord* file = nullptr;
  bool found = false;      // the source holds the file
  std::string made;        // its JSON, made here from the file
  const std::string* copied = nullptr;  // or the copy ReportOptions::relightCopies holds
  std::string problem;     // why, when found but not shown
  // Empty when it cannot be shown.
  const std::string& json() const { return copied ? *copied : made; }
};

// Every fitted model the carrier lists, read and converted for the page, each on a thread of
// its own. Reading a model and reducing it to the page's size is most of a report's time (the
// models of 36 x 3000x2000 are 54 and 72 MB: 0.13 s each), so buildReport does it while the
// pictures are made. Each model's JSON depends on its file alone: the page is the same at any
// thread count.
std::vector<RelightModel> relightModels(const carrier::Carrier& c, const ReportSource& source,
                                        const ReportOptions& options);

// The interactive view: every fitted model the source holds, as JSON for the page's script,
// drawn at the model's resolution (or options.relightMaxSide); the first model is shown first.
// The models' JSON is tens of megabytes: the section keeps pointers to it, and the page copies
// it once, where it belongs (appendTo).
struct RelightSection {
  std::string before;                       // the section up to the models' JSON array
  std::vector<const std::string*> models;   // the array's elements
  std::string after;                        // the rest of the section
  std::size_t size() const {
    std::size_t n = before.size() + after.size() + models.size();
    for (const std::string* m : models) n += m->size();
    return n;
  }
  void appendTo(std::string& page) const {
    page.append(before);
    for (std::size_t k = 0; k < models.size(); ++k) (k ? page.append(1, ',') : page).append(*models[k]);
    page.append(after);
  }
};

// The light the view opens with: the normalised mean of the captured lights' directions (x
// right, y up, z to the camera, from each light's azimuth and elevation), the middle of the
// range the model was fitted on. A fixed light (it was 45 degrees azimuth and elevation) could
// lie outside that range, where a model extrapolates and the picture starts dark. nullopt when
// there is no light or the directions cancel out.
std::optional<std::array<double, 3>> meanLightDirection(const std::vector<LightPoint>& lights);

// The section of `models` (those found and readable get a button each; the others a note), and
// report.relightable when any can be shown; the view opens at meanLightDirection(lights)
// (data-start-light="x,y,z" on the canvas) unless the page's address names a light.
RelightSection relightSection(const carrier::Carrier& c, const std::vector<RelightModel>& models,
                              const std::vector<LightPoint>& lights, Report& report);

}  // namespace surrogate::report
