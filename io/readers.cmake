# The Cartesian volume readers (raw, NRRD, NIfTI-1: sources read on demand, DenseSource.h) and their
# shared byte/sample helpers, relative to io/.
# Needs glm and ZLIB::ZLIB.
set(FCC_IO_READER_SOURCES
  ByteSource.cpp
  DenseSource.cpp
  DenseVolume.cpp
  NiftiReader.cpp
  NrrdReader.cpp
  RawReader.cpp
  SampleDecoding.cpp
  StoredVoxels.cpp)
