// The scene reader on any bytes: it must refuse (SceneError) or accept, never crash, leak, hang or
// allocate without bound. An accepted scene small enough to build is built and its World made,
// so the reader's checks and the World's stay one set (a scene the reader accepts, the World
// accepts), and written out and read back to the same scene.
#include <cstdint>
#include <string>

#include "engine/limits.h"
#include "scene/presets.h"
#include "scene/scene_json.h"

using namespace scour;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  SceneSpec spec;
  try {
    spec = specFromJson(parseJsonText(text, "fuzz.json"), "fuzz.json");
  } catch (const SceneError&) {
    return 0;
  }
  // What the reader accepted, the writer writes and the reader reads back to the same scene: the
  // two go through the same field tables and cannot drift apart.
  const nlohmann::json written = specToJson(spec);
  if (specToJson(specFromJson(written, "fuzz.json")) != written) __builtin_trap();
  // Only scenes that take milliseconds: the fuzzer measures the reader, not the engine. (At
  // 2·10⁴ particles a block of 16,000 took more than libFuzzer's 10 s for one step under the
  // sanitizers on a loaded machine.)
  if (spec.terrain.kind == "heightmap") return 0;  // no files from fuzzed paths
  const Footprint f = estimateFootprint(spec);
  if (f.unknown || f.vertices > 2e4 || f.particles > 2e3) return 0;
  // Nor sources or rain that may place thousands of particles in a step (a source 2 m wide has
  // 31,000 slots: a timeout too), counted as the limits count them (engine/limits.h).
  const double ds = spec.params.spacing, dt = longestStep(spec.params);
  for (const Source& src : spec.sources)
    if (sourcePlacedPerStep(src, ds, sourceSlotBound(src.radius, ds), dt) > 2e3) return 0;
  for (const Rain& r : spec.rain) {
    const double area = rainArea(r, 0.0, spec.terrain.length_x, 0.0, spec.terrain.length_z);
    if (rainPlacedPerStep(r, area, ds, dt) > 2e3) return 0;
  }
  try {
    World w(buildScene(spec).desc);
    w.step();
  } catch (const SceneError&) {
  } catch (const TerrainError&) {
  } catch (const InvariantViolation&) {
  } catch (const LimitExceeded&) {
  }
  // std::invalid_argument from the World is not caught: the reader should have refused it.
  return 0;
}
