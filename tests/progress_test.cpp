// Progress of long stages (mesh/base/progress.h) and the stages' times (mesh/base/stage_times.h).
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/base/progress.h"
#include "mesh/base/stage_times.h"

namespace rad {
namespace {

/// A stage says nothing before kProgressDelay, then one line with its name, how far it has got
/// and its seconds; the sink installed before comes back when the scope ends.
TEST(ProgressTest, ALongStageSaysHowFarItHasGot) {
  std::vector<std::string> lines;
  {
    const ProgressScope scope([&](const std::string& line) { lines.push_back(line); });
    StageProgress progress("contact lines: pieces", 40);
    progress.update(1);
    EXPECT_TRUE(lines.empty());  // too soon
    std::this_thread::sleep_for(std::chrono::duration<double>(kProgressDelay + 0.1));
    progress.update(12);
    progress.update(13);  // within kProgressInterval of the last line: silent
    ASSERT_EQ(lines.size(), 1u);
    // Its seconds are the clock's (2 on a quiet machine; more under load or a sanitizer).
    const std::string head = "contact lines: pieces 12/40 (";
    EXPECT_EQ(lines[0].compare(0, head.size(), head), 0) << lines[0];
    EXPECT_EQ(lines[0].substr(lines[0].size() - 3), " s)") << lines[0];
  }
  StageProgress silent("after the scope", 1);  // no sink: nothing to say, nothing said
  silent.update(0);
  EXPECT_EQ(lines.size(), 1u);
}

/// Spells of one stage add up, in the order the stages first ran, with the peak memory.
TEST(StageTimesTest, SpellsOfAStageAddUp) {
  StageTimes stages;
  stages.add("contact lines", 1.5);
  stages.add("contact cuts", 0.25);
  stages.add("contact lines", 0.5);
  ASSERT_EQ(stages.list().size(), 2u);
  EXPECT_EQ(stages.list()[0].name, "contact lines");
  EXPECT_DOUBLE_EQ(stages.list()[0].seconds, 2.0);
  EXPECT_DOUBLE_EQ(stages.total(), 2.25);
  EXPECT_GT(stages.list()[0].peakMiB, 0.0);
  StageTimes more;
  more.add("contact cuts", 1.0);
  more.add("elements", 3.0);
  stages.add(more);
  EXPECT_DOUBLE_EQ(stages.list()[1].seconds, 1.25);
  EXPECT_EQ(stages.list()[2].name, "elements");
  EXPECT_DOUBLE_EQ(stages.total(), 6.25);
}

}  // namespace
}  // namespace rad
