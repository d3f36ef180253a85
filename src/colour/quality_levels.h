// Imaging guidelines' colour-accuracy levels reached by a chart's colour differences:
// FADGI (Technical Guidelines for Digitizing Cultural Heritage Materials, 3rd edition, 2023)
// star levels and Metamorfoze (Preservation Imaging Guidelines, version 2.0) levels, each with
// the limits it sets. quality_levels.cpp names the documents and the limits.
//
//   ChartFigures f = chartFigures(deltaE2000s, deltaE2000UnitSLs);  // mean, max, p90...
//   std::vector<LevelVerdict> v = qualityLevels(f);     // FADGI 4 star: met/not met...
//   std::string best = bestLevel(v, "FADGI 2023");      // "3 star"
#pragma once

#include <string>
#include <vector>

namespace surrogate::colour {

struct ChartFigures {
  double mean = 0, max = 0, p90 = 0;  // of the patches' dE2000
  int patches = 0;
  // Added for Metamorfoze 2.0, which judges by CIEDE2000 with S_L = 1 (deltaE2000UnitSL):
  // the mean and max of that variant, when the caller gave it (unitSL true).
  double meanUnitSL = 0, maxUnitSL = 0;
  bool unitSL = false;
};
// p90: the 90th percentile, interpolated linearly between the sorted values (rank 0.9 (n-1),
// as a spreadsheet's PERCENTILE.INC). Empty lists give zeros.
ChartFigures chartFigures(const std::vector<double>& deltaE2000s);
// The same with the S_L = 1 differences of the same patches (same length).
ChartFigures chartFigures(const std::vector<double>& deltaE2000s,
                          const std::vector<double>& deltaE2000UnitSLs);

struct LevelVerdict {
  std::string guideline;  // "FADGI 2023", "Metamorfoze 2.0"
  std::string level;      // "4 star", "Full"...
  std::string limits;     // what the level asks, in words ("mean dE2000 <= 2.0, max <= ...")
  bool met = false;
};
// Every level of every guideline, best first within each, with whether the figures meet it.
// Without the S_L = 1 figures Metamorfoze is judged on the standard CIEDE2000 ones, which are
// never larger (a "not met" is certain, a "met" may not hold); its limits text then says so.
std::vector<LevelVerdict> qualityLevels(const ChartFigures& figures);
// The best level met of one guideline ("" when none).
std::string bestLevel(const std::vector<LevelVerdict>& verdicts, const std::string& guideline);

}  // namespace surrogate::colour
