// sim's output files: one CSV row per mass per frame, or one JSON document.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <springlab/recorder.hpp>

#include "test_systems.hpp"

namespace springlab {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Recorder, WritesOneCsvRowPerMassPerFrame) {
  testing::AnchoredOscillators sim(3, 1.0, 1.0);
  const std::string path = ::testing::TempDir() + "run.csv";
  Recorder r(path, SceneSettings{}, sim);
  r.record(sim);
  sim.operate(0.01);
  r.record(sim);
  r.close("ok");
  const std::string text = slurp(path);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + 2 * 3);
  EXPECT_EQ(text.rfind("frame,time,mass,x,y,z,vx,vy,vz,kinetic", 0), 0u);
}

TEST(Recorder, WritesJsonFramesWithEnergies) {
  testing::AnchoredOscillators sim(2, 1.0, 1.0);
  const std::string path = ::testing::TempDir() + "run.json";
  Recorder r(path, SceneSettings{}, sim);
  r.record(sim);
  r.close("ok");
  const auto doc = nlohmann::json::parse(slurp(path));
  EXPECT_EQ(doc["masses"], 2);
  EXPECT_EQ(doc["status"], "ok");
  ASSERT_EQ(doc["frames"].size(), 1u);
  EXPECT_EQ(doc["frames"][0]["pos"].size(), 2u);
  EXPECT_TRUE(doc["frames"][0]["energy"].contains("total"));
}

// Frames go to the file as they are recorded: a long run does not hold them in memory, and a
// run stopped midway leaves the frames it made. The status closes the document (escaped).
TEST(Recorder, JsonFramesAreOnDiskBeforeTheRunEnds) {
  testing::AnchoredOscillators sim(2, 1.0, 1.0);
  const std::string path = ::testing::TempDir() + "streamed.json";
  Recorder r(path, SceneSettings{}, sim);
  for (int k = 0; k < 3; ++k) {
    r.record(sim);
    sim.operate(0.01);
  }
  const std::string before = slurp(path);
  std::size_t frames = 0;
  for (std::size_t at = before.find("\"time\""); at != std::string::npos; at = before.find("\"time\"", at + 1)) ++frames;
  EXPECT_EQ(frames, 3u) << before;
  r.close("blew up: \"energy\" rose");
  const auto doc = nlohmann::json::parse(slurp(path));
  EXPECT_EQ(doc["frames"].size(), 3u);
  EXPECT_EQ(doc["status"], "blew up: \"energy\" rose");
  EXPECT_EQ(doc["integrator"], sim.integrator().name());
  EXPECT_DOUBLE_EQ(doc["frames"][2]["time"].get<double>(), 0.02);
}

TEST(Recorder, AJsonRunLeftByAnExceptionIsStillADocument) {
  testing::AnchoredOscillators sim(1, 1.0, 1.0);
  const std::string path = ::testing::TempDir() + "unfinished.json";
  {
    Recorder r(path, SceneSettings{}, sim);
    r.record(sim);
  }
  const auto doc = nlohmann::json::parse(slurp(path));
  EXPECT_EQ(doc["frames"].size(), 1u);
  EXPECT_NE(doc["status"].get<std::string>().find("stopped before its last step"), std::string::npos);
}

TEST(Recorder, AJsonRunWithNoFrameIsAnEmptyList) {
  testing::AnchoredOscillators sim(1, 1.0, 1.0);
  const std::string path = ::testing::TempDir() + "empty.json";
  Recorder r(path, SceneSettings{}, sim);
  r.close("ok");
  const auto doc = nlohmann::json::parse(slurp(path));
  EXPECT_TRUE(doc["frames"].is_array());
  EXPECT_EQ(doc["frames"].size(), 0u);
}

TEST(Recorder, RejectsAnUnknownExtension) {
  testing::AnchoredOscillators sim(1, 1.0, 1.0);
  EXPECT_THROW(Recorder(::testing::TempDir() + "run.txt", SceneSettings{}, sim), std::invalid_argument);
}

}  // namespace
}  // namespace springlab
