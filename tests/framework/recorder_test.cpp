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

TEST(Recorder, RejectsAnUnknownExtension) {
  testing::AnchoredOscillators sim(1, 1.0, 1.0);
  EXPECT_THROW(Recorder(::testing::TempDir() + "run.txt", SceneSettings{}, sim), std::invalid_argument);
}

}  // namespace
}  // namespace springlab
