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

json sceneToJson(const Scene& s) {
  const WorldDesc& d = s.desc;
  json j;
  j["version"] = 1;
  j["name"] = s.name;
  j["description"] = s.description;
  j["params"] = paramsToJson(d.params);
  j["derived"] = {{"support_m", d.params.support()}, {"particle_mass_kg", d.params.particleMass()}};
  const Heightfield& hf = d.terrain;
  j["terrain"] = {{"kind", s.terrain_kind},
                  {"nx", hf.nx()},
                  {"nz", hf.nz()},
                  {"dx", hf.dx()},
                  {"dz", hf.dz()},
                  {"origin", {hf.x0(), hf.z0()}},
                  {"extent_m", {hf.xMax() - hf.x0(), hf.zMax() - hf.z0()}},
                  {"height_min", hf.minHeight()},
                  {"height_max", hf.maxHeight()}};
  j["domain"] = {{"walls", d.domain.walls}};
  const Effects& e = d.effects;
  j["effects"] = {{"fluid_motion", e.fluid_motion}, {"surface_tension", e.surface_tension},
                  {"no_slip", e.no_slip},           {"settling", e.settling},
                  {"diffusion", e.diffusion},       {"deposition", e.deposition},
                  {"erosion", e.erosion}};
  json blocks = json::array();
  for (const auto& [lo, hi] : s.water_blocks) blocks.push_back({{"min", vec(lo)}, {"max", vec(hi)}});
  j["water"] = {{"blocks", blocks}, {"particles", d.particles.size()}};
  json sources = json::array();
  for (const Source& src : d.sources)
    sources.push_back({{"position", vec(src.center)},
                       {"radius", src.radius},
                       {"direction", vec(src.direction)},
                       {"rate", src.rate},
                       {"start", src.start},
                       {"stop", std::isfinite(src.stop) ? json(src.stop) : json(nullptr)}});
  j["sources"] = sources;
  json sinks = json::array();
  for (const Sink& k : d.sinks) sinks.push_back({{"min", vec(k.lo)}, {"max", vec(k.hi)}});
  j["sinks"] = sinks;
  return j;
}

}  // namespace scour
