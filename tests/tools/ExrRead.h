// Reading one float channel of an EXR that `fccvdb render` or the viewer wrote.
#pragma once

#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <string>
#include <vector>

namespace fcc::test {

// One float channel of an EXR, row 0 at the top.
inline std::vector<float> readExrChannel(const std::string& path, const char* channel, int& width, int& height) {
  Imf::InputFile file(path.c_str());
  const auto dw = file.header().dataWindow();
  width = dw.max.x - dw.min.x + 1;
  height = dw.max.y - dw.min.y + 1;
  std::vector<float> values(std::size_t(width) * height);
  Imf::FrameBuffer fb;
  fb.insert(channel, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data() - dw.min.x - dw.min.y * width),
                                sizeof(float), sizeof(float) * width));
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return values;
}

}  // namespace fcc::test
