#include "scene/checkpoint.h"

#include <cstring>
#include <fstream>
#include <sstream>

#include "scene/input_file.h"
#include "scene/output.h"
#include "scene/scene_json.h"

namespace scour {

namespace {

constexpr char kMagic[8] = {'S', 'C', 'O', 'U', 'R', 'C', 'K', 'P'};

uint64_t fnv1a(const std::string& bytes) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ULL;
  return h;
}

template <class T>
void put(std::ostream& o, T v) {
  o.write(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

void writeCheckpoint(const std::string& path, const SceneSpec& spec, const World& world) {
  std::ostringstream payload;
  const std::string sceneText = specToJson(spec).dump();
  put(payload, uint64_t(sceneText.size()));
  payload << sceneText;
  world.saveState(payload);
  const std::string bytes = payload.str();
  writeAtomically(path, [&](std::ostream& o) {
    o.write(kMagic, sizeof kMagic);
    put(o, kCheckpointVersion);
    put(o, uint64_t(bytes.size()));
    o.write(bytes.data(), std::streamsize(bytes.size()));
    put(o, fnv1a(bytes));
  });
}

Checkpoint readCheckpoint(const std::string& path) {
  std::string file;
  try {
    file = readInputFile(path, "checkpoint", kMaxCheckpointBytes);
  } catch (const InputFileError& e) {
    throw CheckpointError(e.what());
  }
  constexpr size_t kHeader = sizeof kMagic + sizeof(uint32_t) + sizeof(uint64_t);
  if (file.size() < kHeader || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0)
    throw CheckpointError(path + ": not a Scour checkpoint (no SCOURCKP header)");
  uint32_t version = 0;
  uint64_t length = 0;
  std::memcpy(&version, file.data() + sizeof kMagic, sizeof version);
  std::memcpy(&length, file.data() + sizeof kMagic + sizeof version, sizeof length);
  if (version != kCheckpointVersion)
    throw CheckpointError(path + ": checkpoint format version " + std::to_string(version) +
                          ", this build reads version " + std::to_string(kCheckpointVersion));
  if (file.size() - kHeader < sizeof(uint64_t) || length != file.size() - kHeader - sizeof(uint64_t))
    throw CheckpointError(path + ": truncated checkpoint (" + std::to_string(file.size()) +
                          " bytes, the header announces " +
                          std::to_string(length + kHeader + sizeof(uint64_t)) + ")");
  const std::string payload = file.substr(kHeader, length);
  uint64_t sum = 0;
  std::memcpy(&sum, file.data() + kHeader + length, sizeof sum);
  if (sum != fnv1a(payload))
    throw CheckpointError(path + ": corrupted checkpoint (checksum mismatch)");
  Checkpoint c;
  uint64_t sceneLength = 0;
  std::memcpy(&sceneLength, payload.data(), std::min(payload.size(), sizeof sceneLength));
  if (payload.size() < sizeof sceneLength || sceneLength > payload.size() - sizeof sceneLength)
    throw CheckpointError(path + ": corrupted checkpoint (scene length)");
  try {
    const std::string where = path + " (scene)";
    c.spec = specFromJson(parseJsonText(payload.substr(sizeof sceneLength, sceneLength), where), where);
  } catch (const SceneError& e) {
    throw CheckpointError(std::string("corrupted checkpoint: ") + e.what());
  }
  c.state = payload.substr(sizeof sceneLength + sceneLength);
  return c;
}

World resumeWorld(const Checkpoint& c, Scene& scene) {
  scene = buildScene(c.spec);
  World w(scene.desc);
  std::istringstream in(c.state);
  try {
    w.loadState(in);
  } catch (const std::runtime_error& e) {
    throw CheckpointError(std::string("checkpoint: ") + e.what());
  }
  return w;
}

}  // namespace scour
