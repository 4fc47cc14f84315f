#include "eval/suite/suite_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "core/image/map_render.h"

namespace fleetmap::eval::suite {
namespace {

using ::testing::HasSubstr;

std::vector<WorldOutcome> Outcomes() {
  WorldOutcome office, blank;
  office.world.name = "g_office_3";
  office.world.group = "office";
  office.prepared.resolution_m = 0.05;
  office.agents = WorldScore{};
  office.agents->changed_f1 = 0.75;
  blank.world.name = "blank";
  blank.world.group = "public";
  blank.world.source = WorldSource::kPublic;
  blank.unusable = "nothing in the map is observed";
  return {blank, office};
}

TEST(SuiteReportTest, GeneratedWorldsComeFirstAndUnusableOnesShowTheirReason) {
  const std::vector<WorldOutcome> outcomes = Outcomes();
  const auto order = InReportOrder(outcomes);
  ASSERT_EQ(order.size(), 2u);
  EXPECT_EQ(order[0]->world.name, "g_office_3");
  const std::string md = SuiteMarkdown(outcomes, {{"suite.worlds", 1, "worlds"}});
  EXPECT_THAT(md, HasSubstr("| suite.worlds | 1 | worlds |"));
  EXPECT_THAT(md, HasSubstr("unusable: nothing in the map is observed"));
  EXPECT_THAT(md, HasSubstr("| 0.750 |"));
}

TEST(SuiteReportTest, ThePictureIsAPngWithARowPerWorld) {
  const std::string path = ::testing::TempDir() + "suite_" + std::to_string(getpid()) + ".png";
  ASSERT_TRUE(WriteSuitePng(Outcomes(), path).ok());
  auto picture = core::ReadBgrImage(path);
  ASSERT_TRUE(picture.ok()) << picture.status().ToString();
  EXPECT_GT(picture->width, 500);
  EXPECT_GT(picture->height, 4 * 18);  // title, two groups, two worlds
  EXPECT_FALSE(WriteSuitePng(Outcomes(), "/no/such/folder/suite.png").ok());
}

}  // namespace
}  // namespace fleetmap::eval::suite
