// edge/lcm_groups.h over LCM's in-process transport (memq://): links that share a URL share
// one instance when asked, a subscription is matched whole as a regular expression, a link
// with no subscription is never waited on, and a URL LCM cannot open is a clear error.
#include "edge/lcm_groups.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fleetmap::edge {
namespace {

struct Received {
  std::vector<std::string> channels;
  std::vector<Link> links;
  LcmGroups::Handler Handler() {
    return [this](Link link, const std::string& channel, const uint8_t*, int) {
      links.push_back(link);
      channels.push_back(channel);
    };
  }
};

const std::vector<uint8_t> kBytes = {1, 2, 3};

TEST(LcmGroupsTest, LinksOnOneUrlShareAnInstanceWhenAsked) {
  auto groups = LcmGroups::Open({{Link::kSensor, "memq://"}, {Link::kUplink, "memq://"}}, true);
  ASSERT_TRUE(groups.ok()) << groups.status().ToString();
  Received received;
  (*groups)->Subscribe(Link::kSensor, "SCAN_v1", 10, received.Handler());
  ASSERT_TRUE((*groups)->Publish(Link::kUplink, "SCAN_v1", kBytes));
  EXPECT_EQ(*(*groups)->Handle(0.1, 10), 1);
  ASSERT_EQ(received.channels, std::vector<std::string>{"SCAN_v1"});
  EXPECT_EQ(received.links[0], Link::kSensor);
}

TEST(LcmGroupsTest, WithoutSharingEachLinkHearsOnlyItself) {
  auto groups = LcmGroups::Open({{Link::kUplink, "memq://"}, {Link::kDownlink, "memq://"}}, false);
  ASSERT_TRUE(groups.ok()) << groups.status().ToString();
  Received received;
  (*groups)->Subscribe(Link::kUplink, "TEMPMAP_.*", 10, received.Handler());
  ASSERT_TRUE((*groups)->Publish(Link::kDownlink, "TEMPMAP_ACK", kBytes));
  EXPECT_EQ(*(*groups)->Handle(0.05, 10), 0);
  ASSERT_TRUE((*groups)->Publish(Link::kUplink, "TEMPMAP_v2", kBytes));
  ASSERT_TRUE((*groups)->Publish(Link::kUplink, "XTEMPMAP_v2", kBytes));  // matched whole
  EXPECT_EQ(*(*groups)->Handle(0.1, 10), 1);
  EXPECT_EQ(received.channels, std::vector<std::string>{"TEMPMAP_v2"});
}

TEST(LcmGroupsTest, HandleStopsAtMaxMessagesAndLeavesTheRestQueued) {
  auto groups = LcmGroups::Open({{Link::kUplink, "memq://"}}, false);
  ASSERT_TRUE(groups.ok());
  Received received;
  (*groups)->Subscribe(Link::kUplink, "MAP_REQUEST", 10, received.Handler());
  for (int i = 0; i < 3; ++i) ASSERT_TRUE((*groups)->Publish(Link::kUplink, "MAP_REQUEST", kBytes));
  EXPECT_EQ(*(*groups)->Handle(0.1, 1), 1);
  EXPECT_EQ(*(*groups)->Handle(0.1, 10), 2);
  EXPECT_EQ(received.channels.size(), 3u);
}

TEST(LcmGroupsTest, NothingSubscribedMeansNothingToWaitFor) {
  auto groups = LcmGroups::Open({{Link::kDownlink, "memq://"}}, false);
  ASSERT_TRUE(groups.ok());
  ASSERT_TRUE((*groups)->Publish(Link::kDownlink, "MAP_DELTA", kBytes));
  EXPECT_EQ(*(*groups)->Handle(0.0, 10), 0);
}

TEST(LcmGroupsTest, ALinkNotOpenedRefusesToPublish) {
  auto groups = LcmGroups::Open({{Link::kUplink, "memq://"}}, false);
  ASSERT_TRUE(groups.ok());
  EXPECT_FALSE((*groups)->Publish(Link::kSensor, "SCAN_v1", kBytes));
}

TEST(LcmGroupsTest, AUrlLcmCannotOpenNamesTheLinkAndTheUrl) {
  auto groups = LcmGroups::Open({{Link::kDownlink, "bogus://nowhere"}}, false);
  ASSERT_FALSE(groups.ok());
  EXPECT_NE(groups.status().message().find("downlink"), std::string::npos);
  EXPECT_NE(groups.status().message().find("bogus://nowhere"), std::string::npos);
}

}  // namespace
}  // namespace fleetmap::edge
