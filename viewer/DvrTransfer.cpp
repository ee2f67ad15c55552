#include "DvrTransfer.h"

#include <glm/glm.hpp>

#include <cmath>

namespace fcc::render {

TransferFunction fitTransferFunction(const TransferFunction& tf, const BrickSource& source) {
  if (!tf.normalized()) return tf;
  // From empty space (transparent under every preset's opacity ramp) to the largest value, when the
  // background lies below the data; else (a level set's outside, for one) the whole range.
  const float lo = source.valueMin(), hi = source.valueMax(), background = source.background();
  const bool fromBackground = background > lo && background < hi && background - lo < 0.1f * (hi - lo);
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
