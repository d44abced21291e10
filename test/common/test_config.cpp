#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "bmp/common/config.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

TEST(Config, ReadsTypedValuesAndNestedSections) {
  const Config c =
      Config::fromString("a: 3\nb: 2.5\nname: x\nflag: true\nlist: [1, 2]\ns:\n  k: 7\n", "t.yaml");
  EXPECT_EQ(c.get<int>("a", 0), 3);
  EXPECT_DOUBLE_EQ(c.get<double>("b", 0.0), 2.5);
  EXPECT_EQ(c.get<std::string>("name", ""), "x");
  EXPECT_TRUE(c.get<bool>("flag", false));
  EXPECT_EQ(c.get<std::vector<double>>("list", {}), (std::vector<double>{1, 2}));
  EXPECT_EQ(c.section("s").get<int>("k", 0), 7);
  EXPECT_EQ(c.get<int>("absent", 42), 42);
  EXPECT_NO_THROW(c.finish());
}

TEST(Config, UnknownKeyIsAnErrorNamingFileAndKey) {
  const Config c = Config::fromString("tracker:\n  features: 1000\n  feautres: 900\n", "config/tracker.yaml");
  c.section("tracker").get<int>("features", 0);
  try {
    c.finish();
    FAIL() << "finish() accepted an unknown key";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("config/tracker.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("tracker.feautres"), std::string::npos) << what;
  }
}

// A key given twice in one mapping was read from its first line, the second (the one a user edited last)
// silently ignored: it is an error naming the file, the line and the key. Every file we ship has none.
TEST(Config, AKeyGivenTwiceIsAnErrorNamingFileLineAndKey) {
  try {
    Config::fromString("tracker:\n  orb:\n    num_features: 500\n    num_features: 1000\n", "mine.yaml");
    FAIL() << "a key given twice was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("mine.yaml:4: key 'tracker.orb.num_features' is given twice"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(Config::fromString("list:\n  - {a: 1, a: 2}\n", "l.yaml"), ConfigError);
  EXPECT_NO_THROW(Config::fromString("a: {k: 1}\nb: {k: 1}\n", "same key in two mappings"));
  for (const auto& entry : std::filesystem::recursive_directory_iterator(test::sourceDir() + "/config")) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(Config::fromFile(entry.path().string())) << entry.path();
  }
}

TEST(Config, UnreadSectionIsReported) {
  const Config c = Config::fromString("a: 1\nextra:\n  b: 2\n", "f.yaml");
  c.get<int>("a", 0);
  EXPECT_THROW(c.finish(), ConfigError);
}

TEST(Config, WrongTypeIsAnErrorNamingKeyAndValue) {
  const Config c = Config::fromString("s:\n  n: abc\n", "f.yaml");
  try {
    c.section("s").get<int>("n", 0);
    FAIL();
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("s.n"), std::string::npos) << what;
    EXPECT_NE(what.find("integer"), std::string::npos) << what;
    EXPECT_NE(what.find("abc"), std::string::npos) << what;
  }
  EXPECT_THROW(Config::fromString("l: 3\n", "f").get<std::vector<int>>("l", {}), ConfigError);
  EXPECT_THROW(Config::fromString("m: {a: 1}\n", "f").get<std::string>("m", ""), ConfigError);
}

TEST(Config, MissingFileAndBadYamlNameTheFile) {
  try {
    Config::fromFile("/nonexistent/x.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.yaml"), std::string::npos);
  }
  EXPECT_THROW(Config::fromString("a: [1, 2\n", "broken.yaml"), ConfigError);
  EXPECT_THROW(Config::fromString("- 1\n- 2\n", "list.yaml"), ConfigError);
}

TEST(Config, IgnoredSubtreeIsAcceptedButTyposElsewhereAreNot) {
  const Config c =
      Config::fromString("model:\n  path: m.onnx\nprocess:\n  mode: every\n  queue: 3\nmodle: x\n", "d.yaml");
  c.section("model").get<std::string>("path", "");
  c.ignore("process");
  try {
    c.finish();
    FAIL();
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'modle'"), std::string::npos) << what;
    EXPECT_EQ(what.find("process"), std::string::npos) << what;
  }
}

TEST(Config, RequiredKeyMissing) {
  const Config c = Config::fromString("a: 1\n", "f.yaml");
  EXPECT_THROW(c.require<double>("fx"), ConfigError);
}

TEST(Config, EffectiveValuesListDefaults) {
  const Config c = Config::fromString("a: 1\n", "f.yaml");
  c.get<int>("a", 0);
  c.get<double>("b", 0.5);
  const auto values = c.effectiveValues();
  ASSERT_EQ(values.size(), 2u);
  EXPECT_EQ(values[0], "a = 1");
  EXPECT_EQ(values[1], "b = 0.5 (default)");
}

// Every shipped configuration file must parse (a typo in config/ must fail here, not at a user's start-up).
TEST(Config, ShippedFilesParse) {
  for (const char* f : {"capture.yaml", "run.yaml", "cameras/bonn.yaml", "cameras/tum_fr1.yaml",
                        "cameras/tum_fr2.yaml", "cameras/tum_fr3.yaml"}) {
    EXPECT_NO_THROW(Config::fromFile(test::sourceDir() + "/config/" + f)) << f;
  }
}

}  // namespace
}  // namespace bmp
