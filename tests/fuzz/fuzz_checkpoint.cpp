// Checkpoints on any bytes, two ways: the whole file (header, length, checksum, embedded scene)
// through readCheckpoint, and the bytes as a world state through World::loadState, past the
// checksum that guards it in a file, so a crafted state is read too.
#include <unistd.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "scene/checkpoint.h"
#include "scene/presets.h"

using namespace scour;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = [] {
    char tmpl[] = "/tmp/scour_fuzz_ck_XXXXXX";
    return std::string(mkdtemp(tmpl)) + "/c.ckpt";
  }();
  // One World, put back to its saved start before every input (building one per input would be
  // a hundred times slower), so each input is read from the same state.
  static World w(makePreset("valley", 0.05).desc);
  static const std::string start = [] {
    std::ostringstream o;
    w.saveState(o);
    return o.str();
  }();
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  try {
    readCheckpoint(path);
  } catch (const CheckpointError&) {
  }
  // Only a state that loaded (and was stepped) changed the World; a refused one can have read
  // no more than counters that the next accepted state overwrites. Putting the World back only
  // then makes the harness 40 times faster (75 to 3,000 inputs a second on the malformed seeds).
  static bool loaded = false;
  if (loaded) {
    std::istringstream reset(start);
    w.loadState(reset);
    loaded = false;
  }
  std::istringstream in(bytes);
  try {
    w.loadState(in);
    loaded = true;
    w.step();
  } catch (const std::runtime_error&) {  // refused state, or an invariant it breaks
  }
  return 0;
}
