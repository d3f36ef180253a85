// Imaging guidelines' colour-accuracy levels reached by a chart's CIEDE2000 figures:
// FADGI (Technical Guidelines for Digitizing Cultural Heritage Materials) star levels and
// Metamorfoze levels, each with the limits it sets.
//
//   ChartFigures f = chartFigures(deltaEs);              // mean, max, 90th percentile...
//   std::vector<LevelVerdict> v = qualityLevels(f);     // FADGI 4-star: met/not met...
#pragma once

#include <string>
#include <vector>

namespace surrogate::colour {

struct ChartFigures {
  double mean = 0, max = 0, p90 = 0;  // of the patches' dE2000
  int patches = 0;
};
ChartFigures chartFigures(const std::vector<double>& deltaE2000s);

struct LevelVerdict {
  std::string guideline;  // "FADGI 2023", "Metamorfoze 2019"
  std::string level;      // "4 star", "Full"...
  std::string limits;     // what the level asks, in words ("mean dE2000 <= 2.0, max <= ...")
  bool met = false;
};
// Every level of every guideline, best first within each, with whether the figures meet it.
std::vector<LevelVerdict> qualityLevels(const ChartFigures& figures);
// The best level met of one guideline ("" when none).
std::string bestLevel(const std::vector<LevelVerdict>& verdicts, const std::string& guideline);

}  // namespace surrogate::colour
