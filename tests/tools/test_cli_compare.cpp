// `fccvdb compare` as other tools read it: --json rows with the contract's keys, the table's figures
// (the convergence slope) recomputed from the JSON, -o DIR's files, the fps of the rendered lattices,
// and one-line errors. Only FpsOfTheLatticesTheRendererStores times the renderer (the rest: --no-fps).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <vector>

#include "RunCommand.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

// The rows of compare's --json: each a flat object of numbers, strings and nulls.
std::vector<std::map<std::string, std::string>> parseRows(const std::string& json) {
  std::vector<std::map<std::string, std::string>> rows;
  const std::regex object(R"(\{([^{}]*)\})"), member(R"re("([a-z0-9_]+)": ("[^"]*"|[^,}]+))re");
  for (auto o = std::sregex_iterator(json.begin(), json.end(), object); o != std::sregex_iterator(); ++o) {
    const std::string body = (*o)[1];
    std::map<std::string, std::string> row;
    for (auto m = std::sregex_iterator(body.begin(), body.end(), member); m != std::sregex_iterator(); ++m)
      row[(*m)[1]] = (*m)[2];
    rows.push_back(row);
  }
  return rows;
}

TEST(CliCompare, JsonRowsCarryTheContractAndTheTableRecomputesFromThem) {
  const std::string flags = "compare --field marschner-lobb --budget 3000,24000 --points 400 --res 16x16 --no-fps";
  const auto json = runFccvdb(flags + " --json");
  ASSERT_EQ(json.status, 0) << json.err;
  const auto rows = parseRows(json.out);
  ASSERT_EQ(rows.size(), 18u) << json.out;
  std::map<std::string, int> lattices;
  for (const auto& row : rows) {
    for (const char* key : {"lattice", "reconstruction", "budget", "samples", "value_rms_error", "value_max_error",
                            "normal_error_mean_deg", "normal_error_p95_deg", "fps"})
      ASSERT_TRUE(row.count(key)) << "missing " << key;
    EXPECT_EQ(row.at("fps"), "null");
    ++lattices[row.at("lattice")];
  }
  EXPECT_EQ(lattices["\"cc\""], 8);
  EXPECT_EQ(lattices["\"bcc\""], 8);
  EXPECT_EQ(lattices["\"fcc\""], 2);

  // The table's slope column: log-log least squares of value_rms_error against samples, from the JSON.
  const auto table = runFccvdb(flags);
  ASSERT_EQ(table.status, 0) << table.err;
  for (const auto& row : rows) {
    if (row.at("budget") != "3000") continue;
    const auto& other = *std::find_if(rows.begin(), rows.end(), [&](const auto& r) {
      return r.at("reconstruction") == row.at("reconstruction") && r.at("budget") == "24000";
    });
    const double slope = (std::log(std::stod(other.at("value_rms_error"))) - std::log(std::stod(row.at("value_rms_error")))) /
                         (std::log(std::stod(other.at("samples"))) - std::log(std::stod(row.at("samples"))));
    const std::string name = row.at("reconstruction").substr(1, row.at("reconstruction").size() - 2);
    const std::regex line("\\n[a-z]+ +" + name + " +3000 .* (-?[0-9]+\\.[0-9]+) +- *\\n");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(table.out, m, line)) << name << " not in\n" << table.out;
    EXPECT_NEAR(std::stod(m[1]), slope, 0.006) << name;
  }
}

TEST(CliCompare, OutputDirectoryHoldsTheReport) {
  TempDir dir;
  const auto r = runFccvdb("compare --field random-waves --budget 2000,8000 --points 300 --res 12x12 --no-fps "
                           "--reconstruction trilinear,boxspline -o " + dir.path.string());
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"compare.json", "compare.md", "convergence.svg", "compare_2000.png", "compare_8000.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  EXPECT_EQ(parseRows(readText(dir / "compare.json")).size(), 4u);
  EXPECT_THAT(readText(dir / "convergence.svg"), HasSubstr("fcc boxspline (slope"));
  // Existing files are not overwritten without --force.
  const auto again = runFccvdb("compare --field random-waves --budget 2000 --points 300 --res 0x0 -o " + dir.path.string());
  EXPECT_EQ(again.status, 1);
  EXPECT_EQ(lineCount(again.err), 1) << again.err;
}

TEST(CliCompare, ACartesianVolumeIsTheTruthWithInput) {
  // A 20^3 f32 raw volume of a smooth bump: compare samples its interpolating spline.
  TempDir dir;
  const std::string raw = dir / "bump.raw";
  {
    std::ofstream out(raw, std::ios::binary);
    for (int z = 0; z < 20; ++z)
      for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
          const float v = std::exp(-((x - 9.5f) * (x - 9.5f) + (y - 9.5f) * (y - 9.5f) + (z - 9.5f) * (z - 9.5f)) / 30.0f);
          out.write(reinterpret_cast<const char*>(&v), sizeof v);
        }
  }
  const auto r = runFccvdb("compare --input " + raw + " --dims 20,20,20 --type f32 --budget 4000,16000 --points 300 "
                           "--res 16x16 --reconstruction tricubic,boxspline --json --no-fps");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = parseRows(r.out);
  ASSERT_EQ(rows.size(), 4u) << r.out;
  for (const auto& row : rows) EXPECT_LT(std::stod(row.at("value_rms_error")), 0.05) << row.at("reconstruction");
  // Without the raw layout, with both truths, or a .vdb: one line each.
  const auto noLayout = runFccvdb("compare --input " + raw + " --budget 4000");
  EXPECT_EQ(noLayout.status, 1);
  EXPECT_THAT(noLayout.err, HasSubstr("--dims"));
  const auto both = runFccvdb("compare --input " + raw + " --field marschner-lobb --budget 4000");
  EXPECT_EQ(both.status, 2);
  EXPECT_EQ(lineCount(both.err), 1) << both.err;
  const auto neither = runFccvdb("compare --budget 4000");
  EXPECT_EQ(neither.status, 1);
  EXPECT_THAT(neither.err, HasSubstr("--field"));
}

// The renderer timed on each row's data: a positive fps for every row (cc, bcc and fcc: the renderer
// stores all three lattices); the report names the renderer. A measurement, not a benchmark: no
// figure is asserted beyond being there.
TEST(CliCompare, FpsOfEveryLattice) {
  TempDir dir;
  const auto r = runFccvdb("compare --field marschner-lobb --budget 2000 --points 200 --res 16x16 --json -o " +
                           dir.path.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string report = readText(dir / "compare.md");
  if (report.find("fps: not timed (no usable EGL") != std::string::npos) {
    if (std::getenv("CI")) FAIL() << "EGL/OpenGL 4.5 is required when CI is set:\n" << report;
    GTEST_SKIP() << report;
  }
  EXPECT_THAT(report, HasSubstr("fps: 1 / the median frame time"));
  EXPECT_THAT(report, HasSubstr("brick-paged raycaster on "));
  EXPECT_THAT(report, ::testing::Not(HasSubstr("not timed"))) << report;
  const auto rows = parseRows(r.out);
  ASSERT_EQ(rows.size(), 9u) << r.out;
  int timed = 0;
  for (const auto& row : rows) {
    const std::string& lattice = row.at("lattice");
    ASSERT_NE(row.at("fps"), "null") << lattice << " " << row.at("reconstruction");
    EXPECT_GT(std::stod(row.at("fps")), 0.0) << lattice << " " << row.at("reconstruction");
    ++timed;
  }
  EXPECT_EQ(timed, 9);  // cc trilinear, tricubic, tricubic-bspline, type6; bcc's four; fcc boxspline
  EXPECT_EQ(parseRows(readText(dir / "compare.json")), rows);
}

TEST(CliCompare, BadInputGivesOneLineListingTheValidValues) {
  struct Case {
    const char* args;
    int status;
    const char* says;
  };
  for (const Case& c : {Case{"compare --field sphere --budget 1000", 2, "marschner-lobb"},
                        Case{"compare --field marschner-lobb --budget 10", 1, "integers from 64"},
                        Case{"compare --field marschner-lobb --budget 1000,x", 1, "'x' is not a sample count"},
                        Case{"compare --field marschner-lobb --budget 1000 --reconstruction tricubc", 1, "valid: trilinear"},
                        Case{"compare --field marschner-lobb --budget 1000 --res 10", 1, "is not WxH"}}) {
    const auto r = runFccvdb(c.args);
    EXPECT_EQ(r.status, c.status) << c.args << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says)) << c.args;
  }
}

}  // namespace
}  // namespace fcc::test
