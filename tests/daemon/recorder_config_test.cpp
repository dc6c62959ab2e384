// [recorder]: defaults, ranges, unknown keys, and where it writes when dir is "" (the state
// directory systemd gives the unit, else nowhere).
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>

#include "config_errors.hpp"
#include "daemon_test_support.hpp"
#include "headingd/daemon/config/config.hpp"

namespace headingd::daemon {
namespace {

using test::configErrorOf;
using test::TempDir;

// Sets (or, with nullopt, unsets) STATE_DIRECTORY while it lives.
class StateDirectory {
 public:
  explicit StateDirectory(const std::optional<std::string>& value) {
    if (const char* old = std::getenv("STATE_DIRECTORY")) old_ = old;
    if (value) {
      setenv("STATE_DIRECTORY", value->c_str(), 1);
    } else {
      unsetenv("STATE_DIRECTORY");
    }
  }
  ~StateDirectory() {
    if (old_) {
      setenv("STATE_DIRECTORY", old_->c_str(), 1);
    } else {
      unsetenv("STATE_DIRECTORY");
    }
  }

 private:
  std::optional<std::string> old_;
};

TEST(RecorderConfig, WithoutTableOrStateDirectoryNothingIsRecordedAndTheReasonSaysWhy) {
  TempDir dir;
  StateDirectory none(std::nullopt);
  const RecorderConfig c = loadDaemonConfig(dir.write("empty.toml", "")).recorder;
  EXPECT_FALSE(c.enabled);
  EXPECT_EQ(c.dir, "");
  EXPECT_NE(c.off_reason.find("STATE_DIRECTORY is not set"), std::string::npos) << c.off_reason;
  const RecorderConfig d;
  EXPECT_EQ(c.segment_max_bytes, d.segment_max_bytes);
  EXPECT_EQ(c.segment_max_age_s, d.segment_max_age_s);
  EXPECT_EQ(c.total_max_bytes, d.total_max_bytes);
  EXPECT_EQ(c.ring_lines, d.ring_lines);
  EXPECT_EQ(d.segment_max_bytes, 16u << 20);
  EXPECT_EQ(d.total_max_bytes, 1u << 30);
}

TEST(RecorderConfig, UnderSystemdItRecordsInTheStateDirectory) {
  TempDir dir;
  {
    StateDirectory state("/var/lib/headingd");
    const RecorderConfig c = loadDaemonConfig(dir.write("empty.toml", "")).recorder;
    EXPECT_TRUE(c.enabled);
    EXPECT_EQ(c.dir, "/var/lib/headingd/recordings");
    EXPECT_EQ(c.off_reason, "");
  }
  {
    StateDirectory several("/var/lib/headingd:/var/lib/other");
    EXPECT_EQ(loadDaemonConfig(dir.write("empty.toml", "")).recorder.dir, "/var/lib/headingd/recordings");
  }
  {
    StateDirectory state("/var/lib/headingd");
    const RecorderConfig off = loadDaemonConfig(dir.write("off.toml", "[recorder]\nenabled = false\n")).recorder;
    EXPECT_FALSE(off.enabled);
    EXPECT_EQ(off.off_reason, "[recorder] enabled = false");
    const RecorderConfig own = loadDaemonConfig(dir.write("own.toml", "[recorder]\ndir = \"rec\"\n")).recorder;
    EXPECT_EQ(own.dir, dir.path() + "/rec") << "a relative dir is taken from the configuration's folder";
  }
}

TEST(RecorderConfig, KeysAreReadWithTheirRanges) {
  TempDir dir;
  StateDirectory none(std::nullopt);
  const RecorderConfig c =
      loadDaemonConfig(dir.write("r.toml",
                                 "[recorder]\ndir = \"/srv/rec\"\nsegment_max_bytes = 1048576\n"
                                 "segment_max_age_s = 60\ntotal_max_bytes = 104857600\nring_lines = 1024\n"))
          .recorder;
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.dir, "/srv/rec");
  EXPECT_EQ(c.segment_max_bytes, 1048576u);
  EXPECT_EQ(c.segment_max_age_s, 60.0);
  EXPECT_EQ(c.total_max_bytes, 104857600u);
  EXPECT_EQ(c.ring_lines, 1024u);

  const std::string at = dir.file("bad.toml");
  std::string e = configErrorOf(dir, "[recorder]\nsegment_max_bytes = 100\n");
  EXPECT_NE(e.find(at + ":2: [recorder] segment_max_bytes: 100 is out of range"), std::string::npos) << e;
  e = configErrorOf(dir, "[recorder]\nsegment_max_age_s = 0.5\n");
  EXPECT_NE(e.find(at + ":2: [recorder] segment_max_age_s: 0.5 is out of range"), std::string::npos) << e;
  e = configErrorOf(dir, "[recorder]\nring_lines = 8\n");
  EXPECT_NE(e.find(at + ":2: [recorder] ring_lines: 8 is out of range"), std::string::npos) << e;
  e = configErrorOf(dir, "[recorder]\nsegment_max_bytes = 1048576\ntotal_max_bytes = 2097152\n");
  EXPECT_NE(e.find(at + ":3: [recorder] total_max_bytes (2097152) must be at least 4 x segment_max_bytes (1048576)"),
            std::string::npos)
      << e;
  e = configErrorOf(dir, "[recorder]\nenabled = true\nfolder = \"x\"\n");
  EXPECT_NE(e.find(at + ":3: [recorder] folder: unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("segment_max_age_s"), std::string::npos) << e;
  e = configErrorOf(dir, "[recorder]\nenabled = \"yes\"\n");
  EXPECT_NE(e.find(at + ":2: [recorder] enabled: expected true or false"), std::string::npos) << e;
}

TEST(RecorderConfig, ShippedFilesDocumentTheDefaultsAndTheDemoDoesNotRecord) {
  StateDirectory state("/var/lib/headingd");
  const RecorderConfig shipped = loadDaemonConfig(HEADINGD_CONFIG_DIR "/headingd.toml").recorder;
  const RecorderConfig d;
  EXPECT_TRUE(shipped.enabled);
  EXPECT_EQ(shipped.dir, "/var/lib/headingd/recordings");
  EXPECT_EQ(shipped.segment_max_bytes, d.segment_max_bytes);
  EXPECT_EQ(shipped.segment_max_age_s, d.segment_max_age_s);
  EXPECT_EQ(shipped.total_max_bytes, d.total_max_bytes);
  EXPECT_EQ(shipped.ring_lines, d.ring_lines);
  const RecorderConfig demo = loadDaemonConfig(HEADINGD_CONFIG_DIR "/demo.toml").recorder;
  EXPECT_FALSE(demo.enabled) << "the demo plays files: recording them would only copy them";
}

}  // namespace
}  // namespace headingd::daemon
