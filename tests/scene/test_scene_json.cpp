// Scene files: every preset serialises and parses back to the identical scene, a scene file runs
// the same as its preset, and the reader refuses what it does not know with the field's path.
#include <catch2/catch.hpp>

#include "scene/scene_json.h"

using namespace scour;
using nlohmann::json;

TEST_CASE("every preset round-trips through its JSON", "[scene]") {
  for (const PresetInfo& p : presetList()) {
    INFO(p.name);
    Scene a = makePreset(p.name, 0.5);
    json ja = sceneToJson(a);
    json spec = ja;
    spec.erase("built");
    Scene b = buildScene(specFromJson(spec, std::string(p.name) + ".json"));
    json jb = sceneToJson(b);
    CHECK(ja == jb);
    CHECK(a.desc.particles == b.desc.particles);
    CHECK(a.desc.terrain.heights() == b.desc.terrain.heights());
    CHECK(a.desc.concentration == b.desc.concentration);
    // The same state after a few steps.
    World wa(a.desc), wb(b.desc);
    for (int k = 0; k < 5; ++k) wa.step(), wb.step();
    CHECK(wa.stateHash() == wb.stateHash());
  }
}

TEST_CASE("the reader names the field, what it expected and what it found", "[scene]") {
  json base = sceneToJson(makePreset("valley", 0.3));
  base.erase("built");
  auto error = [&](const std::function<void(json&)>& edit) {
    json j = base;
    edit(j);
    try {
      specFromJson(j, "x.json");
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  CHECK(error([](json& j) { j["sources"][0]["rate"] = -1; }) ==
        "x.json: sources[0].rate: expected a finite number in [1e-12, 1e+06], found -1");
  CHECK(error([](json& j) { j["sources"][0]["rate"] = "fast"; }) ==
        "x.json: sources[0].rate: expected a number, found \"fast\"");
  CHECK_THAT(error([](json& j) { j["sources"][0]["raet"] = 1; }),
             Catch::Contains("sources[0].raet: unknown key (did you mean 'rate'?)"));
  CHECK_THAT(error([](json& j) { j["params"]["erosion"]["k_esp"] = 1; }),
             Catch::Contains("params.erosion.k_esp: unknown key (did you mean 'k_eps'?)"));
  CHECK_THAT(error([](json& j) { j["params"]["fluid"]["spacing"] = -0.1; }),
             Catch::Contains("params.fluid.spacing") && Catch::Contains("outside the valid range"));
  CHECK_THAT(error([](json& j) { j["effects"].push_back("erosoin"); }),
             Catch::Contains("effects[9]: unknown effect 'erosoin' (did you mean 'erosion'?)"));
  CHECK_THAT(error([](json& j) { j["terrain"]["kind"] = "volcano"; }),
             Catch::Contains("terrain.kind: expected one of flat, slope, valley, bowl, terraces, rolling, fbm, heightmap, found \"volcano\""));
  CHECK_THAT(error([](json& j) { j["water"]["blocks"][0]["max"] = json::array({1, 2}); }),
             Catch::Contains("water.blocks[0].max: expected an array of 3 numbers"));
  CHECK_THAT(error([](json& j) { j["water"]["blocks"][0]["max"][1] = -5; }),
             Catch::Contains("water.blocks[0]: max must exceed min on every axis"));
  CHECK_THAT(error([](json& j) { j.erase("version"); }),
             Catch::Contains("version: required field is missing"));
  CHECK_THAT(error([](json& j) { j["version"] = 2; }), Catch::Contains("version: expected"));
  CHECK_THAT(error([](json& j) { j["params"]["fluid"]["spacing"] = 1e-4; }),
             Catch::Contains("sources[0].radius: a disk of radius 0.05 m holds about 1e+06 particle slots"));
  // A block filled above the terrain is counted once the terrain is built (buildScene).
  CHECK(error([](json& j) { j["params"]["fluid"]["spacing"] = 1e-4, j["sources"] = json::array(); }) ==
        "(accepted)");
  SceneSpec fine = presetSpec("valley", 0.3);
  fine.params.spacing = 1e-4, fine.sources.clear();
  CHECK_THROWS_WITH(buildScene(fine), Catch::Contains("water.blocks: ") &&
                                          Catch::Contains("particles at spacing 0.0001 m") &&
                                          Catch::Contains("the memory limit of 16 GB allows"));
  CHECK_THAT(error([](json& j) { j["params"]["fluid"]["spacing"] = 1e-4, j["sources"] = json::array(),
                                 j["water"]["blocks"][0]["above_terrain"] = false; }),
             Catch::Contains("water.blocks: ") && Catch::Contains("the memory limit of 16 GB allows"));
  CHECK_THAT(error([](json& j) { j["sources"][0]["rate"] = 1e4; }),
             Catch::Contains("sources[0].rate: 10000 m³/s is") && Catch::Contains("more than the 2e+05 one step may place"));
  CHECK_THAT(error([](json& j) { j["sources"][0]["direction"] = json::array({0, 0, 0}); }),
             Catch::Contains("sources[0].direction: must not be the zero vector"));
  // How --scale resizes the scene, and how `scour stress` runs it.
  CHECK_THAT(error([](json& j) { j["scaling"] = {{"rule", "double"}}; }),
             Catch::Contains("scaling.rule: expected one of spacing, fixed, column, pool, found \"double\""));
  CHECK(error([](json& j) { j["scaling"] = {{"rule", "column"}}; }) ==
        "x.json: scaling.width: required field is missing");
  CHECK_THAT(error([](json& j) { j["scaling"] = {{"rule", "column"}, {"width", 0.1}, {"cells", 2}}; }),
             Catch::Contains("scaling.cells: expected a whole number in [4, 100000], found 2"));
  CHECK_THAT(error([](json& j) { j["scaling"] = {{"rule", "spacing"}, {"layers", 3}}; }),
             Catch::Contains("scaling.layers: unknown key"));
  CHECK(error([](json& j) { j["stress"] = {{"jumps", json::array()}}; }) ==
        "x.json: stress.duration: required field is missing");
  CHECK(error([](json& j) {
          j["stress"] = {{"duration", 1}, {"jumps", {{{"time", 0.3}, {"param", "erosion.k_esp"}, {"factor", 2}}}}};
        }) == "x.json: stress.jumps[0].param: expected the key of a real-valued parameter "
              "(docs/parameters.md), found \"erosion.k_esp\"");
  CHECK(error([](json& j) { j["stress"] = {{"duration", 1}, {"jumps", {{{"time", 0.3}, {"factor", 2}}}}}; }) ==
        "x.json: stress.jumps[0].param: required field is missing");
  CHECK(error([](json&) {}) == "(accepted)");
}

TEST_CASE("scene files may hold // and /* */ comments", "[scene][json]") {
  const std::string text = R"(// a comment before the object
{
  "version": 1, /* inside */ "name": "commented",
  "terrain": {"kind": "slope", "slope": 0.2}  // after a value
})";
  const SceneSpec s = specFromJson(parseJsonText(text, "commented.json"), "commented.json");
  CHECK(s.name == "commented");
  CHECK(s.terrain.slope == 0.2);
  // A comment left open is still an error that names the file.
  REQUIRE_THROWS_WITH(parseJsonText("{\"version\": 1 /* open", "bad.json"),
                      Catch::StartsWith("bad.json: not valid JSON"));
}
