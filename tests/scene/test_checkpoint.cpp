// Checkpoints: a run resumed from a checkpoint reaches the state hash of the uninterrupted run,
// for moving water with erosion, sources and sinks, for rain, and for a frozen sediment-only
// lattice. Damaged files are refused with a message that says what is wrong.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "scene/checkpoint.h"

using namespace scour;
namespace fs = std::filesystem;

namespace {

fs::path tempDir() {
  fs::path d = fs::temp_directory_path() / ("scour_ckpt_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Runs `total` steps, writing a checkpoint at `at`; returns the final hash.
uint64_t runWithCheckpoint(const SceneSpec& spec, int at, int total, const fs::path& file) {
  Scene scene = buildScene(spec);
  World w(scene.desc);
  for (int k = 0; k < total; ++k) {
    w.step();
    if (w.steps() == at) writeCheckpoint(file.string(), scene.spec, w);
  }
  return w.stateHash();
}

uint64_t resume(const fs::path& file, int total) {
  Scene scene;
  World w = resumeWorld(readCheckpoint(file.string()), scene);
  while (w.steps() < total) w.step();
  return w.stateHash();
}

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void writeAll(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

}  // namespace

TEST_CASE("a resumed run reaches the same state hash as the uninterrupted one", "[checkpoint]") {
  const fs::path dir = tempDir();
  struct Case {
    const char* preset;
    double scale;
    int at, total;
  };
  // default: water, source, sink, friction, every erosion pass, a Z-order reorder after the
  // checkpoint (every 16 steps); rain: drops still to come; settling: the frozen lattice.
  for (Case c : {Case{"valley", 0.3, 37, 90}, Case{"rain", 0.5, 25, 60}, Case{"settling", 1.0, 20, 50}}) {
    INFO(c.preset);
    const SceneSpec spec = presetSpec(c.preset, c.scale);
    const fs::path file = dir / (std::string(c.preset) + ".ckpt");
    const uint64_t straight = runWithCheckpoint(spec, c.at, c.total, file);
    REQUIRE(fs::exists(file));
    CHECK(resume(file, c.total) == straight);
    // The hash does see the difference one step makes.
    CHECK(resume(file, c.total - 1) != straight);
  }
  fs::remove_all(dir);
}

TEST_CASE("damaged checkpoints are refused with the reason", "[checkpoint]") {
  const fs::path dir = tempDir();
  const fs::path good = dir / "good.ckpt";
  runWithCheckpoint(presetSpec("valley", 0.2), 5, 5, good);
  const std::string bytes = readAll(good);
  auto refuse = [&](const std::string& content) {
    const fs::path bad = dir / "bad.ckpt";
    writeAll(bad, content);
    try {
      readCheckpoint(bad.string());
    } catch (const CheckpointError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refuse(bytes.substr(0, bytes.size() / 2)), Catch::Contains("truncated checkpoint"));
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  CHECK_THAT(refuse(flipped), Catch::Contains("corrupted checkpoint (checksum mismatch)"));
  std::string other = bytes;
  other[8] = 7;  // the version field
  CHECK_THAT(refuse(other), Catch::Contains("checkpoint format version 7, this build reads version 1"));
  CHECK_THAT(refuse("{\"version\": 1}"), Catch::Contains("not a Scour checkpoint"));
  CHECK_THAT(refuse(""), Catch::Contains("not a Scour checkpoint"));
  fs::remove_all(dir);
}
