#include "studies/channels.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace turbodyn::studies {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::vector<ProbeChannel> channels() {
  auto c = [](const std::string& name, ProbeChannel::Kind k) {
    ProbeChannel p;
    p.name = name;
    p.kind = k;
    return p;
  };
  return {c("speed", ProbeChannel::Kind::Speed),           c("spin_angle", ProbeChannel::Kind::Angle),
          c("disk.turbine.x", ProbeChannel::Kind::RotorDof), c("disk.turbine.y", ProbeChannel::Kind::RotorDof),
          c("bearing.left.fx", ProbeChannel::Kind::Element), c("bearing.left.fy", ProbeChannel::Kind::Element),
          c("bearing.left.fx_only", ProbeChannel::Kind::Element)};
}

TEST(Channels, FindsByNameAndKind) {
  const std::vector<ProbeChannel> ch = channels();
  EXPECT_EQ(find_channel(ch, "disk.turbine.y"), 3);
  EXPECT_EQ(find_channel(ch, "disk.turbine.z"), -1);
  EXPECT_EQ(kind_channel(ch, ProbeChannel::Kind::Speed), 0);
  EXPECT_EQ(kind_channel(ch, ProbeChannel::Kind::Angle), 1);
  EXPECT_EQ(kind_channel({}, ProbeChannel::Kind::Speed), -1);
}

TEST(Channels, PairStemsAreDisplacementsOrForces) {
  const std::vector<ProbeChannel> ch = channels();
  EXPECT_EQ(pair_channels(ch, "disk.turbine"), std::make_pair(2, 3));
  EXPECT_EQ(pair_channels(ch, "bearing.left"), std::make_pair(4, 5));
  EXPECT_EQ(pair_channels(ch, "disk.compressor"), std::make_pair(-1, -1));
}

TEST(Channels, UnknownProbeSuggestsTheClosestOrListsAll) {
  const std::vector<std::string> names = channel_names(channels());
  ASSERT_EQ(names.size(), 7u);
  EXPECT_EQ(unknown_probe("disk.turbine.z", names),
            "the model has no probe 'disk.turbine.z'; did you mean 'disk.turbine.x'?");
  const std::string far = unknown_probe("qqqqqqqqqqqqqqqqqqqqqq", names);
  EXPECT_THAT(far, Not(HasSubstr("did you mean")));
  EXPECT_THAT(far, HasSubstr("(probes: speed spin_angle disk.turbine.x disk.turbine.y"));
}

TEST(Channels, DidYouMeanFallsBackToTheGivenText) {
  EXPECT_EQ(did_you_mean("cobila", {"cobyla", "bobyqa"}), "; did you mean 'cobyla'?");
  EXPECT_EQ(did_you_mean("zzzzzz", {"cobyla", "bobyqa"}, " (none close)"), " (none close)");
  EXPECT_EQ(did_you_mean("zzzzzz", {"cobyla"}), "");
}

}  // namespace
}  // namespace turbodyn::studies
