// The samples' distribution as an FCC file records it (metadata fcc_sample_histogram, docs/FORMAT.md):
// counts in equal bins over [fcc_sample_min, fcc_sample_max], and what is read from it without
// touching a brick: percentiles and a suggested isovalue (Otsu's threshold).
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fcc {

inline constexpr int kSampleHistogramBins = 256;

namespace meta {
inline constexpr const char* kSampleHistogram = "fcc_sample_histogram";  // histogramText of the counts
}  // namespace meta

// The samples V at the FCC sites inside the field's bounds, before the prefilter.
struct SampleSummary {
  float min = 0.0f, max = 0.0f;
  // Equal bins over [min, max] (the last one closed); empty when unknown (files written before
  // histograms existed, or a field without sites).
  std::vector<uint64_t> histogram;

  // The bin a value falls in (values outside go to the end bins; everything to bin 0 when min == max).
  int binOf(double v) const;
  double binWidth() const { return histogram.empty() ? 0.0 : (double(max) - double(min)) / double(histogram.size()); }
  uint64_t total() const;
};

// The value below which `percent` % of the samples lie, interpolated linearly inside its bin (so
// exact to within one bin width). Needs a non-empty histogram.
double samplePercentile(const SampleSummary& s, double percent);

// Otsu's threshold on the histogram without the bin that holds `background`: the value between two
// bins that maximizes the between-class variance of the samples on either side. The background is
// left out because it is not part of the object: a volume padded or masked with it (air around a
// scan, a skull-stripped brain) would otherwise be split into "background" and "everything else",
// whose boundary is the mask's or the padding's edge, not a surface of the data. Where the maximum is
// reached over empty bins (two separated clusters), the threshold is the middle of that gap. nullopt
// when fewer than two bins hold samples besides the background.
std::optional<double> otsuThreshold(const SampleSummary& s, float background);

// The FCC grid's record of its samples (setFccMetadata writes their range, fcc_sample_min/max): the
// histogram as metadata, and back. recordedSamples: nullopt without a range (files not written by
// convert or synth); an empty histogram for files written before histograms existed.
void recordSampleHistogram(openvdb::GridBase& grid, const SampleSummary& samples);
std::optional<SampleSummary> recordedSamples(const openvdb::GridBase& grid);

// The metadata text: the counts in decimal, separated by single spaces.
std::string histogramText(const std::vector<uint64_t>& counts);
// Parses histogramText's output; nullopt for anything else (then the file is treated as having none).
std::optional<std::vector<uint64_t>> parseHistogramText(const std::string& text);

}  // namespace fcc
