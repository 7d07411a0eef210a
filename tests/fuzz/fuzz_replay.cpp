// Replay scripts on any bytes: refused (std::invalid_argument) or read, nothing else.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "app/replay.h"

using namespace scour;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    scour::parseReplay(std::string(reinterpret_cast<const char*>(data), size), "fuzz.txt");
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
