// headingd-calibrate and headingd-replay --calib end to end, on files the simulator library
// writes: an uncalibrated magnetometer (Kok & Schön Table 2) calibrated on a hand-held
// recording, then a walk replayed with and without the calibration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "calib_test_support.hpp"
#include "headingd/core/angles.hpp"
#include "headingd/core/imu_calibration_toml.hpp"
#include "headingd/sim/output.hpp"

namespace headingd::calib_test {
namespace {

namespace fs = std::filesystem;

fs::path tempDir() {
  const fs::path d = fs::temp_directory_path() / ("headingd-calib-test-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

void writeCsv(const sim::SimResult& r, const fs::path& path) {
  std::ofstream f(path);
  sim::writeImuCsv(f, r);
}

int run(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readText(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// Heading RMSE of a replay against the simulator's truth, after removing the mean offset
// (the estimator gives magnetic heading, the truth is geographic: the declination is a
// constant). Error about the vertical: 2 atan(|z/w|) of q_est ⊗ q_true⁻¹, signed by z.
double headingRmseDeg(const fs::path& estimates, const sim::SimResult& truth) {
  std::ifstream f(estimates);
  std::string line;
  std::getline(f, line);
  std::vector<double> errors;
  for (std::size_t k = 0; std::getline(f, line) && k < truth.imu.size(); ++k) {
    double t, w, x, y, z;
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &t, &w, &x, &y, &z) != 5 || !std::isfinite(w)) continue;
    if (t < 20.0) continue;  // let the estimator settle
    const core::Quat e = core::Quat(w, x, y, z) * truth.imu[k].q_ns.conjugate();
    errors.push_back(2.0 * std::atan(e.z() / e.w()));
  }
  double mean_sin = 0, mean_cos = 0;
  for (const double e : errors) mean_sin += std::sin(e), mean_cos += std::cos(e);
  const double offset = std::atan2(mean_sin, mean_cos);
  double sum2 = 0;
  for (const double e : errors) sum2 += std::pow(core::wrapAngle(e - offset), 2);
  return std::sqrt(sum2 / static_cast<double>(errors.size())) * core::kDegPerRad;
}

TEST(CalibrateTool, EllipsoidCalibrationMakesHeadingsBetter) {
  const fs::path dir = tempDir();
  const sim::SimResult& calibration_run = simulated("calib-rotation-long", 7);
  // The same seed draws the same magnetometer D and o in every scenario (own random stream).
  const sim::SimResult& walk = simulated("thesis-declination", 7);
  ASSERT_EQ(calibration_run.mag.distortion, walk.mag.distortion);
  writeCsv(calibration_run, dir / "calib.csv");
  writeCsv(walk, dir / "walk.csv");
  ASSERT_EQ(run(std::string(HEADINGD_CALIBRATE_TOOL) + " --imu-csv " + (dir / "calib.csv").string() +
                " --method ellipsoid --lat 59.33 --lon 18.07 --date 2026-06-01 --out " + (dir / "c.toml").string() +
                " --report " + (dir / "report").string()),
            0);
  const core::ImuCalibration c = core::parseImuCalibration(readText(dir / "c.toml"), "c.toml");
  EXPECT_EQ(c.mag.field_norm_source, core::FieldNormSource::kWmm);
  const core::Mat3 dd = c.mag.D * c.mag.D.transpose(), dd_true = walk.mag.distortion * walk.mag.distortion.transpose();
  EXPECT_LT((dd - dd_true).norm() / dd_true.norm(), 0.02);
  EXPECT_LT((c.mag.offset_uT - walk.mag.offset).norm(), 0.5);
  EXPECT_TRUE(fs::exists(dir / "report" / "index.html"));
  EXPECT_NE(readText(dir / "report" / "index.html").find("<svg"), std::string::npos);

  const std::string replay = std::string(HEADINGD_REPLAY_TOOL) + " --imu-csv " + (dir / "walk.csv").string();
  ASSERT_EQ(run(replay + " --out " + (dir / "raw.csv").string()), 0);
  ASSERT_EQ(run(replay + " --calib " + (dir / "c.toml").string() + " --out " + (dir / "cal.csv").string()), 0);
  const double before = headingRmseDeg(dir / "raw.csv", walk), after = headingRmseDeg(dir / "cal.csv", walk);
  RecordProperty("heading_rmse_before_deg", std::to_string(before));
  RecordProperty("heading_rmse_after_deg", std::to_string(after));
  std::printf("heading RMSE (offset removed): uncalibrated %.2f deg, calibrated %.2f deg\n", before, after);
  // The ellipsoid fixes D only up to a rotation (K&S eq. 25); --method ellipsoid turns it
  // onto the inertial axes with the misalignment step (§6.2), which Table 2's ±10° rotations
  // and ±30° skews need: measured for this seed 99° uncalibrated, 34° with the symmetric D
  // alone, 2.5° with the misalignment.
  EXPECT_LT(after, 5.0);
  EXPECT_LT((c.mag.D - walk.mag.distortion).norm() / walk.mag.distortion.norm(), 0.05);
  fs::remove_all(dir);
}

TEST(CalibrateTool, ThesisMethodOnSixPositions) {
  const fs::path dir = tempDir();
  writeCsv(simulated("calib-six-position", 8, sim::ImuGrade::kConsumer), dir / "six.csv");
  ASSERT_EQ(run(std::string(HEADINGD_CALIBRATE_TOOL) + " --imu-csv " + (dir / "six.csv").string() +
                " --method thesis --field-uT 51.88 --out " + (dir / "t.toml").string()),
            0);
  const core::ImuCalibration c = core::parseImuCalibration(readText(dir / "t.toml"), "t.toml");
  EXPECT_EQ(c.provenance.method, "thesis");
  EXPECT_EQ(c.mag.field_norm_source, core::FieldNormSource::kArgument);
  EXPECT_NE(c.gyro.scale, core::Vec3::Ones());  // turns were found
  fs::remove_all(dir);
}

TEST(CalibrateTool, TooLittleRotationExitsWithThree) {
  const fs::path dir = tempDir();
  // Standing still for two minutes: no ellipsoid to fit, no faces.
  writeCsv(simulated("static-disturbed", 1), dir / "still.csv");
  for (const char* method : {"ellipsoid", "thesis"}) {
    EXPECT_EQ(run(std::string(HEADINGD_CALIBRATE_TOOL) + " --imu-csv " + (dir / "still.csv").string() +
                  " --field-uT 50 --method " + method + " --out " + (dir / "x.toml").string()),
              3)
        << method;
  }
  EXPECT_EQ(run(std::string(HEADINGD_CALIBRATE_TOOL) + " --imu-csv " + (dir / "still.csv").string() +
                " --method magic --out " + (dir / "x.toml").string()),
            2);
  // Options the command-line parser refuses exit with 2 as well.
  EXPECT_EQ(run(std::string(HEADINGD_CALIBRATE_TOOL) + " --imu-csv " + (dir / "still.csv").string() +
                " --method ml --ml-gradient guess --out " + (dir / "x.toml").string()),
            2);
  EXPECT_EQ(run(std::string(HEADINGD_CALIBRATE_TOOL) + " --out " + (dir / "x.toml").string()), 2);  // no --imu-csv
  fs::remove_all(dir);
}

// The dip's sign comes from the WMM at the place or from --hemisphere, not both; with
// --hemisphere north the K&S misalignment step keeps the minimum that dips down.
TEST(CalibrateTool, HemisphereGivesTheDipSign) {
  const fs::path dir = tempDir();
  writeCsv(simulated("calib-rotation-long", 7), dir / "calib.csv");
  const std::string tool = std::string(HEADINGD_CALIBRATE_TOOL) + " --imu-csv " + (dir / "calib.csv").string();
  EXPECT_EQ(run(tool + " --method ellipsoid --hemisphere north --lat 59.33 --lon 18.07 --date 2026-06-01 --out " +
                (dir / "x.toml").string()),
            2);
  EXPECT_EQ(run(tool + " --method ellipsoid --hemisphere west --out " + (dir / "x.toml").string()), 2);
  ASSERT_EQ(run(tool + " --method ellipsoid --field-uT 51.9 --hemisphere north --out " + (dir / "n.toml").string()), 0);
  const core::ImuCalibration c = core::parseImuCalibration(readText(dir / "n.toml"), "n.toml");
  ASSERT_TRUE(c.mag.dip_rad.has_value());
  EXPECT_GT(*c.mag.dip_rad, 0.0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace headingd::calib_test
