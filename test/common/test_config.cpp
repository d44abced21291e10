#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

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
  try {
    Config::fromString("channel:\n", "f.yaml").get<std::string>("channel", "X");
    FAIL() << "an empty value read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("must be a string, got nothing"), std::string::npos) << e.what();
  }
}

// .inf and .nan are YAML numbers but no setting's (a lockstep timeout of .inf waited forever in silence); a
// key with a dot is never looked up (sections are nested keys), so it was neither read nor called unknown.
TEST(Config, NonFiniteNumbersAndDottedKeysAreErrorsNamingTheKey) {
  for (const char* value : {".inf", "-.inf", ".nan"}) {
    const Config c =
        Config::fromString(std::string("s:\n  t: ") + value + "\n  l: [1, " + value + "]\n", "f.yaml");
    try {
      c.section("s").get<double>("t", 1.0);
      ADD_FAILURE() << value << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("f.yaml: key 's.t' must hold finite numbers"), std::string::npos)
          << e.what();
    }
    EXPECT_THROW(c.section("s").get<std::vector<double>>("l", {}), ConfigError) << value;
  }
  try {
    Config::fromString("capture.speed: 100\n", "run.yaml");
    FAIL() << "a dotted key accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("run.yaml:1: key 'capture.speed' has a dot in it"),
              std::string::npos)
        << e.what();
  }
}

// A file of a few hundred bytes whose aliases nest ten deep is a tree of 10^8 values: refused at once, not
// walked for minutes.
TEST(Config, AliasesNestedIntoAHugeTreeAreRefused) {
  std::string yaml = "a0: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n";
  for (int i = 1; i <= 8; ++i) {
    yaml += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) yaml += (k ? ", *a" : "*a") + std::to_string(i - 1);
    yaml += "]\n";
  }
  try {
    Config::fromString(yaml, "alias.yaml");
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("alias.yaml: more than"), std::string::npos) << e.what();
  }
}

// A folder given as the configuration read as an empty file: every value silently its default.
TEST(Config, AFolderIsNotAConfigurationFile) {
  try {
    Config::fromFile(test::sourceDir() + "/config");
    FAIL() << "a folder read as a configuration";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("a folder, not a configuration file"), std::string::npos)
        << e.what();
  }
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
