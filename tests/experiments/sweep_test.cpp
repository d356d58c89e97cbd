// The sweep (experiments/sweep.h) on the Cornell box at 12x12: results.csv has the documented
// columns; its error columns match errors recomputed here from the images it wrote; tolerance 0 has
// no error; no exact pixel leaves its certified bound (counted here independently); the charts and
// heat maps are PNGs of the expected size with more than one colour.
#include "experiments/sweep.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "formats/image_io.h"
#include "localpass/local_pass.h"
#include "scene/ray_caster.h"
#include "tests/coarse_solution.h"
#include "tests/viz/png_inspect.h"
#include "viz/charts.h"
#include "viz/sweep_figures.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kColumns{"method",
                                        "tolerance",
                                        "samples",
                                        "seconds",
                                        "projected_mean",
                                        "projected_max",
                                        "error_max",
                                        "error_mean",
                                        "error_rms",
                                        "bound_violations",
                                        "error_over_bound_max",
                                        "pixels",
                                        "image"};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// results.csv as rows of column name -> text.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file,
                                                         std::vector<std::string>* header) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  *header = split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto fields = split(line);
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < header->size() && i < fields.size(); ++i) row[(*header)[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

/// Relative error statistics recomputed from two image files, written out here on purpose
/// (not through error_map.h): max, mean and RMS of max_c|I - R| / max_c R over R > 0.
struct Recomputed {
  double max = 0, mean = 0, rms = 0;
  size_t pixels = 0;
};
Recomputed recompute(const fs::path& image_file, const fs::path& reference_file) {
  const Image image = read_exr(image_file), reference = read_exr(reference_file);
  Recomputed r;
  double sum = 0, squares = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const double ref =
        std::max({reference.pixels[i].x(), reference.pixels[i].y(), reference.pixels[i].z()});
    if (!(ref > 0)) continue;
    double e = 0;
    for (int c = 0; c < 3; ++c)
      e = std::max(e, std::abs(image.pixels[i][c] - reference.pixels[i][c]));
    e /= ref;
    r.max = std::max(r.max, e);
    sum += e;
    squares += e * e;
    ++r.pixels;
  }
  r.mean = sum / r.pixels;
  r.rms = std::sqrt(squares / r.pixels);
  return r;
}

class SweepOnCornell : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: ctest runs each of these tests in its own process, in parallel.
    folder_ = fs::temp_directory_path() / ("rad_sweep_test_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
    const auto& cornell = test::coarse_cornell();
    CameraSpec spec = *cornell.scene.camera;
    spec.width = spec.height = 12;
    SweepSettings settings;
    settings.methods = {Method::hemisphere, Method::vertex, Method::montecarlo};
    settings.tolerances = {0, 0.1, 0.4};
    settings.samples = {4, 16};
    const SweepResult sweep =
        run_sweep(cornell.scene, cornell.faces, Camera(spec), settings, folder_);
    write_sweep_figures(folder_, sweep);
    rows_ = sweep.rows;
  }
  static void TearDownTestSuite() { fs::remove_all(folder_); }
  static fs::path folder_;
  static std::vector<SweepRow> rows_;
};
fs::path SweepOnCornell::folder_;
std::vector<SweepRow> SweepOnCornell::rows_;

TEST_F(SweepOnCornell, CsvHasTheDocumentedColumnsAndOneRowPerSetting) {
  std::vector<std::string> header;
  const auto rows = read_csv(folder_ / "results.csv", &header);
  EXPECT_EQ(header, kColumns);
  ASSERT_EQ(rows.size(), 8u);  // 2 exact methods x 3 tolerances + 2 sample counts
  for (const auto& row : rows) {
    const bool exact = row.at("method") != "montecarlo";
    EXPECT_EQ(row.at("tolerance").empty(), !exact);
    EXPECT_EQ(row.at("samples").empty(), exact);
    EXPECT_EQ(row.at("bound_violations").empty(), !exact);
    EXPECT_EQ(row.at("projected_mean").empty(), !exact);
    EXPECT_GT(std::stod(row.at("seconds")), 0.0);
    EXPECT_GT(std::stoul(row.at("pixels")), 50u);
    EXPECT_TRUE(fs::exists(folder_ / row.at("image"))) << row.at("image");
  }
}

TEST_F(SweepOnCornell, ErrorColumnsMatchErrorsRecomputedFromTheWrittenImages) {
  std::vector<std::string> header;
  for (const auto& row : read_csv(folder_ / "results.csv", &header)) {
    const Recomputed r = recompute(folder_ / row.at("image"), folder_ / "reference.exr");
    const std::string what = row.at("method") + " " + row.at("tolerance") + row.at("samples");
    // The files hold floats; the CSV was computed in double before writing them.
    const auto near = [](double v) { return 1e-6 + 1e-5 * v; };
    EXPECT_NEAR(std::stod(row.at("error_max")), r.max, near(r.max)) << what;
    EXPECT_NEAR(std::stod(row.at("error_mean")), r.mean, near(r.mean)) << what;
    EXPECT_NEAR(std::stod(row.at("error_rms")), r.rms, near(r.rms)) << what;
    EXPECT_EQ(std::stoul(row.at("pixels")), r.pixels) << what;
  }
}

TEST_F(SweepOnCornell, ToleranceZeroHasNoErrorAndNoPixelLeavesItsBound) {
  const auto& cornell = test::coarse_cornell();
  CameraSpec spec = *cornell.scene.camera;
  spec.width = spec.height = 12;
  const Camera camera(spec);
  const RayCaster caster(cornell.scene);
  const LocalPass reference_pass(cornell.scene, cornell.faces, Method::hemisphere);
  const IrradianceImage reference =
      render_local_pass(cornell.scene, caster, camera, reference_pass, 0);
  for (const SweepRow& row : rows_) {
    if (!row.exact()) {
      EXPECT_EQ(row.violations, -1);
      continue;
    }
    if (row.tolerance == 0) {
      // The hemisphere row is the reference itself; vertex tracing agrees to rounding.
      EXPECT_LE(row.error.max, row.method == Method::hemisphere ? 0.0 : 1e-9) << row.label();
    }
    // The estimate is within T of itself, so within T / (1 - T) of the exact value.
    EXPECT_LE(row.error.max, row.tolerance / (1 - row.tolerance) + 1e-9) << row.label();
    // Count violations here, from a render of our own (bitwise the same image).
    const LocalPass pass(cornell.scene, cornell.faces, row.method);
    const IrradianceImage image =
        render_local_pass(cornell.scene, caster, camera, pass, row.tolerance);
    long outside = 0;
    for (size_t i = 0; i < image.radiosity.pixels.size(); ++i) {
      const Rgb excess = (image.radiosity.pixels[i] - reference.radiosity.pixels[i]).cwiseAbs() -
                         image.bound.pixels[i];
      if (excess.maxCoeff() > 1e-8 * reference.radiosity.pixels[i].maxCoeff()) ++outside;
    }
    EXPECT_EQ(outside, 0) << row.label();
    EXPECT_EQ(row.violations, outside) << row.label();
    EXPECT_GT(row.projected_mean, 0) << row.label();
  }
}

TEST(SweepCompare, CountsPixelsOutsideTheirBound) {
  // A synthetic pair: 3 pixels off by 0.1; bounds 0.2 (inside), 0.05 (outside), 0 (outside).
  IrradianceImage reference, image;
  reference.radiosity = Image(3, 1);
  image.radiosity = Image(3, 1);
  image.bound = Image(3, 1);
  for (int i = 0; i < 3; ++i) {
    reference.radiosity.pixels[i] = Rgb::Constant(1.0);
    image.radiosity.pixels[i] = Rgb::Constant(1.1);
  }
  image.bound.pixels = {Rgb::Constant(0.2), Rgb::Constant(0.05), Rgb::Zero()};
  SweepRow row;
  row.method = Method::hemisphere;
  row.tolerance = 0.1;
  compare_to_reference(image, reference, row);
  EXPECT_EQ(row.violations, 2);
  EXPECT_NEAR(row.error_over_bound_max, 2.0, 1e-12);  // 0.1 / 0.05; bound 0 is not a ratio
  EXPECT_NEAR(row.error.max, 0.1, 1e-12);
}

TEST_F(SweepOnCornell, ChartsAndHeatMapsArePngsOfTheirSizeWithMoreThanOneColour) {
  for (const char* chart :
       {"error_vs_tolerance.png", "time_vs_tolerance.png", "error_vs_time.png"}) {
    const test::PngSummary png = test::inspect_png(folder_ / chart);
    EXPECT_EQ(png.width, LineChart{}.width) << chart;
    EXPECT_EQ(png.height, LineChart{}.height) << chart;
    EXPECT_GT(png.colours, 1u) << chart;
  }
  HeatMap heat;
  heat.width = heat.height = 12;
  const auto [width, height] = heat_map_png_size(heat);
  for (const SweepRow& row : rows_) {
    const test::PngSummary png = test::inspect_png(folder_ / "error_maps" / (row.slug() + ".png"));
    EXPECT_EQ(png.width, width) << row.label();
    EXPECT_EQ(png.height, height) << row.label();
    EXPECT_GT(png.colours, 1u) << row.label();
    EXPECT_EQ(read_exr(folder_ / "error_maps" / (row.slug() + ".exr")).width, 12) << row.label();
    EXPECT_EQ(test::inspect_png(folder_ / "images" / (row.slug() + ".png")).width, 12)
        << row.label();
  }
}

}  // namespace
}  // namespace rad
