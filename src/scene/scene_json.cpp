#include "scene/scene_json.h"

namespace scour {

using nlohmann::json;

namespace {
json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
}  // namespace

json paramsToJson(const SimParams& p) {
  json out = json::object();
  for (const ParamInfo& i : paramTable()) {
    std::string key = i.key;
    auto dot = key.find('.');
    json& group = out[key.substr(0, dot)];
    const std::string name = key.substr(dot + 1);
    if (i.choices)
      group[name] = i.choices[p.*i.imember];
    else if (i.imember)
      group[name] = p.*i.imember;
    else
      group[name] = p.*i.dmember;
  }
  return out;
}

json sceneToJson(const Scene& scene) {
  const SceneSpec& s = scene.spec;
  json j;
  j["version"] = 1;
  j["name"] = s.name;
  j["description"] = s.description;
  j["params"] = paramsToJson(s.params);
  const TerrainSpec& t = s.terrain;
  j["terrain"] = {{"kind", t.kind},
                  {"length_x", t.length_x},
                  {"length_z", t.length_z},
                  {"cell", t.cell},
                  {"slope", t.slope},
                  {"side_rise", t.side_rise},
                  {"amplitude", t.amplitude},
                  {"base", t.base}};
  j["domain"] = {{"walls", s.domain.walls}};
  const Effects& e = s.effects;
  j["effects"] = {{"fluid_motion", e.fluid_motion}, {"surface_tension", e.surface_tension},
                  {"no_slip", e.no_slip},           {"settling", e.settling},
                  {"diffusion", e.diffusion},       {"deposition", e.deposition},
                  {"erosion", e.erosion}};
  json blocks = json::array();
  for (const WaterBlock& b : s.blocks) blocks.push_back({{"min", vec(b.min)}, {"max", vec(b.max)}});
  json marks = json::array();
  for (const SedimentMark& m : s.sediment) marks.push_back({{"position", vec(m.position)}, {"c", m.c}});
  j["water"] = {{"blocks", blocks}, {"sediment", marks}};
  json sources = json::array();
  for (const Source& src : s.sources)
    sources.push_back({{"position", vec(src.center)},
                       {"radius", src.radius},
                       {"direction", vec(src.direction)},
                       {"rate", src.rate},
                       {"start", src.start},
                       {"stop", std::isfinite(src.stop) ? json(src.stop) : json(nullptr)}});
  j["sources"] = sources;
  json sinks = json::array();
  for (const Sink& k : s.sinks) sinks.push_back({{"min", vec(k.lo)}, {"max", vec(k.hi)}});
  j["sinks"] = sinks;
  // What the spec built to (not read back): the grid and the particle count.
  const Heightfield& hf = scene.desc.terrain;
  j["built"] = {{"particles", scene.desc.particles.size()},
                {"support_m", s.params.support()},
                {"particle_mass_kg", s.params.particleMass()},
                {"terrain_nx", hf.nx()},
                {"terrain_nz", hf.nz()},
                {"terrain_dx", hf.dx()},
                {"terrain_dz", hf.dz()},
                {"height_min", hf.minHeight()},
                {"height_max", hf.maxHeight()}};
  return j;
}

}  // namespace scour
