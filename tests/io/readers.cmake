# Tests of the Cartesian volume readers, relative to tests/io/. Needs fcc::io, GTest::gtest_main,
# GTest::gmock, ZLIB::ZLIB (it writes gzip files itself) and the FCC_SHARED_DATA_DIR definition.
set(FCC_IO_READER_TEST_SOURCES
  test_readers.cpp)
