// Reading the agent's configuration sections: unknown keys refused with the known ones, absent
// sections and keys leaving the defaults, choices out of a few words.
#include "vehicle_agent/node/config_reading.h"

#include <gtest/gtest.h>

namespace fleetmap::vehicle_agent::node {
namespace {

core::YamlReader Reader(const std::string& text) {
  auto r = core::YamlReader::FromString(text, "c.yaml");
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  return std::move(r).value();
}

bool Says(const core::Status& s, const std::string& text) {
  return !s.ok() && s.ToString().find(text) != std::string::npos;
}

TEST(ConfigReadingTest, UnknownKeysAreRefusedNamingTheLineAndTheKnownKeys) {
  const core::YamlReader r = Reader("a: 1\nsec: {x: 1, y: 2, z: 3}\n");
  const YAML::Node sec = Section(r.root(), "sec");
  ASSERT_TRUE(sec.IsDefined());
  EXPECT_TRUE(CheckKeys(r, sec, "sec", {"x", "y", "z"}).ok());
  const core::Status missing_z = CheckKeys(r, sec, "sec", {"x", "y"});
  EXPECT_TRUE(Says(missing_z, "c.yaml:2: sec.z: unknown key (known: x, y)"))
      << missing_z.ToString();
  // At the top, keys are named without a section.
  EXPECT_TRUE(Says(CheckKeys(r, r.root(), "", {"sec"}), "a: unknown key (known: sec)"));
  EXPECT_TRUE(Says(CheckKeys(r, r.root()["a"], "a", {}), "a: must be a map"));
  EXPECT_FALSE(Section(r.root(), "other").IsDefined());
}

enum class Mode { kSlow, kFast };

core::Status ReadMode(const core::YamlReader& r, Mode& mode) {
  return ReadChoice<Mode>(r, r.root(), "mode", "mode",
                          {{"slow", Mode::kSlow}, {"fast", Mode::kFast}}, mode);
}

TEST(ConfigReadingTest, AChoiceIsOneOfItsWordsAndStaysWhenAbsent) {
  Mode mode = Mode::kFast;
  EXPECT_TRUE(ReadMode(Reader("other: 1\n"), mode).ok());
  EXPECT_EQ(mode, Mode::kFast);
  EXPECT_TRUE(ReadMode(Reader("mode: slow\n"), mode).ok());
  EXPECT_EQ(mode, Mode::kSlow);
  const core::Status wrong = ReadMode(Reader("mode: quick\n"), mode);
  EXPECT_TRUE(Says(wrong, "mode: must be one of slow, fast")) << wrong.ToString();
  EXPECT_EQ(mode, Mode::kSlow);
}

struct Settings {
  double period_s = 1.5;
  int count = 3;
};

core::Status ReadSettings(const core::YamlReader& r, Settings& s) {
  const YAML::Node n = Section(r.root(), "settings");
  if (!n) return core::OkStatus();
  FLEETMAP_READ_NUMBER(r, n, "period_s", "settings.", s.period_s);
  FLEETMAP_READ_AS(r, int, n, "count", "settings.", s.count);
  return core::OkStatus();
}

TEST(ConfigReadingTest, ValuesAreReadWhenPresentAndErrorsNameTheirDottedKey) {
  Settings s;
  ASSERT_TRUE(ReadSettings(Reader("other: 1\n"), s).ok());
  EXPECT_DOUBLE_EQ(s.period_s, 1.5);
  EXPECT_EQ(s.count, 3);
  ASSERT_TRUE(ReadSettings(Reader("settings: {count: 7}\n"), s).ok());
  EXPECT_DOUBLE_EQ(s.period_s, 1.5);
  EXPECT_EQ(s.count, 7);
  ASSERT_TRUE(ReadSettings(Reader("settings: {period_s: 0.25, count: 2}\n"), s).ok());
  EXPECT_DOUBLE_EQ(s.period_s, 0.25);
  EXPECT_EQ(s.count, 2);
  EXPECT_TRUE(Says(ReadSettings(Reader("settings: {count: many}\n"), s), "settings.count"));
  EXPECT_TRUE(Says(ReadSettings(Reader("settings: {period_s: .nan}\n"), s), "settings.period_s"));
  EXPECT_EQ(s.count, 2);
}

}  // namespace
}  // namespace fleetmap::vehicle_agent::node
