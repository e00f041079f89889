// Scene documents and `--set KEY=VALUE`: a known key changes, an unknown one is an error
// that names the assignment, so a typo never runs a different scene than the one asked for.
#include <gtest/gtest.h>

#include <springlab/scene_document.hpp>
#include <springlab/scene_reader.hpp>

namespace springlab {
namespace {

SceneDocument document() {
  SceneDocument d;
  d.file = "x.json";
  d.json = nlohmann::json::parse(R"({"dt": 0.01, "integrator": "rk4", "rope": {"masses": 80, "ground": {"height": -1}}})");
  return d;
}

TEST(SceneDocument, SetChangesNestedKeysWithJsonValues) {
  SceneDocument d = document();
  d.set("rope.masses=40");
  d.set("rope.ground.height=-2.5");
  d.set("integrator=midpoint");
  EXPECT_EQ(d.json["rope"]["masses"], 40);
  EXPECT_EQ(d.json["rope"]["ground"]["height"], -2.5);
  EXPECT_EQ(d.json["integrator"], "midpoint");
}

TEST(SceneDocument, SetRejectsUnknownKeysNamingThem) {
  SceneDocument d = document();
  try {
    d.set("rope.mases=40");
    FAIL() << "a misspelt key must be an error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("x.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("rope.mases"), std::string::npos) << e.what();
  }
  EXPECT_THROW(d.set("rope.masses"), SceneError) << "an assignment needs '='";
}

TEST(SceneDocument, ReadNamesAMissingFile) {
  try {
    SceneDocument::read("no/such/scene.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/scene.json"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace springlab
