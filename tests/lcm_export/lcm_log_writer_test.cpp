// LcmLogWriter writes what LCM's own reader (lcm::LogFile) and LcmLogReader read back.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>

#include "headingd/heading_t.hpp"
#include "headingd/lcm_export/lcm_log_reader.hpp"
#include "headingd/lcm_export/lcm_log_writer.hpp"

namespace headingd::lcm_export {
namespace {

TEST(LcmLogWriter, LcmsOwnReaderAndOursReadWhatItWrites) {
  const std::string path =
      (std::filesystem::temp_directory_path() / ("writer-test-" + std::to_string(getpid()) + ".lcm")).string();
  headingd::heading_t m{};
  m.declination_source = "wmm";
  {
    LcmLogWriter writer(path);
    for (int i = 0; i < 3; ++i) {
      m.sample_utime = 1000 + i;
      m.heading_true_rad = 0.25 * i;
      writer.write(i == 1 ? "OTHER" : "HEADING", 5'000'000 + i, m);
    }
    writer.close();
  }
  lcm::LogFile lcm_log(path, "r");
  ASSERT_TRUE(lcm_log.good());
  LcmLogReader ours(path);
  LcmLogEvent event;
  for (int i = 0; i < 3; ++i) {
    const lcm::LogEvent* e = lcm_log.readNextEvent();
    ASSERT_NE(e, nullptr) << i;
    EXPECT_EQ(e->eventnum, i);
    EXPECT_EQ(e->timestamp, 5'000'000 + i);
    EXPECT_EQ(e->channel, i == 1 ? "OTHER" : "HEADING");
    headingd::heading_t back{};
    ASSERT_EQ(back.decode(e->data, 0, e->datalen), e->datalen);
    EXPECT_EQ(back.sample_utime, 1000 + i);
    EXPECT_EQ(back.heading_true_rad, 0.25 * i);
    EXPECT_EQ(back.declination_source, "wmm");

    ASSERT_TRUE(ours.next(event));
    EXPECT_EQ(event.event_number, i);
    EXPECT_EQ(event.channel, e->channel);
    EXPECT_EQ(event.data.size(), static_cast<std::size_t>(e->datalen));
  }
  EXPECT_EQ(lcm_log.readNextEvent(), nullptr);
  EXPECT_FALSE(ours.next(event));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace headingd::lcm_export
