// Bad scene files get an error that names the file and the key.
#include <gtest/gtest.h>

#include <springlab/rope_simulation.hpp>
#include <springlab/scene_reader.hpp>

namespace springlab {
namespace {

// The message of the SceneError that reading the rope section of `json` raises.
std::string ropeError(const std::string& json) {
  try {
    SceneReader r = SceneReader::fromText(json, "scenes/bad.json");
    SceneReader rope = r.object("rope");
    readRopeParameters(rope, Vec3(0, -9.81, 0), 3);
    rope.rejectUnknownKeys();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "no error";
}

const std::string kGround = R"("ground": {"height": -1.5, "repulsion": 100, "friction": 0.2, "absorption": 2})";

std::string rope(const std::string& massKey) {
  return R"({"rope": {"masses": 80, )" + massKey + R"(, "spring_constant": 10000, "rest_length": 0.05,
    "spring_friction": 0.2, "connection": [0, 0, 0], "connection_velocity": [0, 0, 0],
    "direction": [1, 0, 0], "air_friction": 0.02, )" + kGround + "}}";
}

TEST(SceneReader, AcceptsAValidRope) { EXPECT_EQ(ropeError(rope(R"("mass": 0.05)")), "no error"); }

TEST(SceneReader, MalformedJsonNamesTheFile) {
  const std::string e = ropeError(R"({"rope": {"masses": 80,})");
  EXPECT_NE(e.find("scenes/bad.json: malformed JSON"), std::string::npos) << e;
}

TEST(SceneReader, NaNIsRejectedAsMalformed) {
  const std::string e = ropeError(rope(R"("mass": NaN)"));
  EXPECT_NE(e.find("scenes/bad.json: malformed JSON"), std::string::npos) << e;
}

TEST(SceneReader, MissingKeyIsNamed) {
  const std::string e = ropeError(rope(R"("masss_typo_free": 1)").replace(0, 0, ""));
  EXPECT_NE(e.find("scenes/bad.json: rope.mass: missing key"), std::string::npos) << e;
}

TEST(SceneReader, UnknownKeyIsNamed) {
  const std::string e = ropeError(rope(R"("mass": 0.05, "colour": 3)"));
  EXPECT_NE(e.find("scenes/bad.json: rope.colour: unknown key"), std::string::npos) << e;
}

TEST(SceneReader, WrongTypeIsNamed) {
  const std::string e = ropeError(rope(R"("mass": "heavy")"));
  EXPECT_NE(e.find("scenes/bad.json: rope.mass: must be a number"), std::string::npos) << e;
}

TEST(SceneReader, ZeroOrNegativeMassIsRejected) {
  EXPECT_NE(ropeError(rope(R"("mass": 0)")).find("rope.mass: must be > 0"), std::string::npos);
  EXPECT_NE(ropeError(rope(R"("mass": -1)")).find("rope.mass: must be > 0"), std::string::npos);
}

TEST(SceneReader, NonPositiveStiffnessIsRejected) {
  std::string j = rope(R"("mass": 0.05)");
  j.replace(j.find("10000"), 5, "-5");
  EXPECT_NE(ropeError(j).find("rope.spring_constant: must be > 0"), std::string::npos) << ropeError(j);
}

TEST(SceneReader, NestedKeysShowTheirPath) {
  std::string j = rope(R"("mass": 0.05)");
  j.replace(j.find("\"friction\": 0.2"), 15, "\"friction\": -1");
  EXPECT_NE(ropeError(j).find("rope.ground.friction: must be >= 0"), std::string::npos) << ropeError(j);
}

TEST(SceneReader, MissingFileIsNamed) {
  try {
    SceneReader::fromFile("/nonexistent/scene.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
  }
}

// A document parsed once (a scene after its --set edits) reads as its text would: the same
// values, the same messages naming the file.
TEST(SceneReader, ParsedDocumentReadsAsItsText) {
  const std::string text = rope(R"("mass": 0.05)");
  SceneReader fromJson = SceneReader::fromJson(nlohmann::json::parse(text), "scenes/edited.json");
  SceneReader ropeSection = fromJson.object("rope");
  EXPECT_EQ(ropeSection.number("mass"), 0.05);
  try {
    ropeSection.positive("spring_friction_missing");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scenes/edited.json: rope.spring_friction_missing: missing key"), std::string::npos)
        << e.what();
  }
  try {
    SceneReader::fromJson(nlohmann::json::array(), "scenes/list.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scenes/list.json: the scene must be a JSON object"), std::string::npos) << e.what();
  }
}

TEST(SceneReader, ArraysOfObjectsNameEachElement) {
  SceneReader r = SceneReader::fromText(R"({"body": {"obstacles": [{"radius": 1}, {"radius": -2}], "none": []}})", "scenes/x.json");
  SceneReader body = r.object("body");
  EXPECT_TRUE(body.objects("none").empty());
  std::vector<SceneReader> items = body.objects("obstacles");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].positive("radius"), 1.0);
  try {
    items[1].positive("radius");
    FAIL() << "a negative radius was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scenes/x.json: body.obstacles[1].radius: must be > 0"), std::string::npos) << e.what();
  }
  SceneReader notArray = SceneReader::fromText(R"({"obstacles": {"radius": 1}})", "scenes/y.json");
  EXPECT_THROW(notArray.objects("obstacles"), SceneError);
}

}  // namespace
}  // namespace springlab
