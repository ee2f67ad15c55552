#include "DvrTransfer.h"

#include <glm/glm.hpp>

#include <cmath>

namespace fcc::render {

TransferFunction fitTransferFunction(const TransferFunction& tf, const BrickSource& source) {
  if (!tf.normalized()) return tf;
  // From empty space (transparent under every preset's opacity ramp) to the largest value, when the
  // background lies below the data; else (a level set's outside, a signed field's zero) the whole
  // range. Where the file records its samples' range, below the data means at or below their least:
  // the reconstruction's values under it are the prefilter's undershoot (an MRI's 16 % of the range
  // below its air), not data. Without that record, in the lowest tenth of the reconstruction's range.
  const float lo = source.valueMin(), hi = source.valueMax(), background = source.background();
  const std::optional<std::pair<float, float>> samples = source.sampleRange();
  const bool fromBackground =
      background < hi && (samples ? background <= samples->first
                                  : background > lo && background - lo < 0.1f * (hi - lo));
  return tf.stretchedTo(fromBackground ? background : lo, hi);
}

double defaultUnitDistance(const BrickSource& source) {
  return std::cbrt(std::abs(glm::determinant(glm::dmat3(source.worldFromIndex()))));
}

std::shared_ptr<const TransferTable> transferTable(const TransferFunction& fitted, const OpticalScale& scale) {
  double lo = fitted.domainMin(), hi = fitted.domainMax();
  if (!(hi > lo)) {
    lo -= 0.5;
    hi += 0.5;
  }
  return std::make_shared<const TransferTable>(fitted, lo, hi, kTransferTableSize, scale);
}

}  // namespace fcc::render
