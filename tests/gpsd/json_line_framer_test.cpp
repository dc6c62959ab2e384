// gpsd's stream into lines, with the bound on a line's length.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "headingd/gpsd/json_line_framer.hpp"

namespace headingd::gpsd {
namespace {

std::vector<std::string> feed(JsonLineFramer& f, const std::string& s) {
  std::vector<std::string> lines;
  f.feed(std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()),
         [&](std::string_view l) { lines.emplace_back(l); });
  return lines;
}

TEST(JsonLineFramer, LinesAcrossReadsWithCrLf) {
  JsonLineFramer f(100);
  EXPECT_TRUE(feed(f, "{\"a\":").empty());
  EXPECT_EQ(feed(f, "1}\r\n{\"b\":2}\n{"), (std::vector<std::string>{"{\"a\":1}", "{\"b\":2}"}));
  EXPECT_TRUE(f.endOfStream());  // "{" cut
  EXPECT_EQ(f.counters().cut, 1u);
  EXPECT_EQ(f.counters().lines, 2u);
  EXPECT_FALSE(f.endOfStream());
}

TEST(JsonLineFramer, AnOversizedLineIsSkippedToItsEndAndCounted) {
  JsonLineFramer f(8);
  EXPECT_TRUE(feed(f, std::string(20, 'x')).empty());
  EXPECT_TRUE(feed(f, std::string(1000, 'y')).empty());  // still the same line: nothing kept
  EXPECT_EQ(feed(f, "zz\n{}\n"), (std::vector<std::string>{"{}"}));
  EXPECT_EQ(f.counters().oversized, 1u);
  EXPECT_FALSE(f.endOfStream());
}

}  // namespace
}  // namespace headingd::gpsd
