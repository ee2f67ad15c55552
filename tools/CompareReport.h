// What `fccvdb compare` prints and writes from its rows: the table, the JSON list, and the convergence
// plot (SVG: error against samples, log-log, one line per method with its fitted slope).
#pragma once

#include <string>
#include <vector>

#include "sparse/Comparison.h"

namespace fcc::cli {

// The least-squares slope of log(error) against log(samples) over a method's budgets (NaN with fewer
// than two, or an error of zero).
double convergenceSlope(const std::vector<CompareRow>& rows, const std::string& lattice, const std::string& reconstruction);

std::string compareTable(const std::vector<CompareRow>& rows);
std::string compareJson(const std::vector<CompareRow>& rows);
// One row per method at `budget`: its isosurface and its normal-error heat map (0 dark blue, 20 degrees
// and more red; magenta where only one of it and the truth hits), under a first row with the truth.
RgbImage imageGrid(const RgbImage& truth, const std::vector<CompareRow>& rows, int64_t budget);

std::string convergenceSvg(const std::vector<CompareRow>& rows, const std::string& title);

}  // namespace fcc::cli
