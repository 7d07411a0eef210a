#include "scene/scene_json.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "scene/input_file.h"

namespace scour {

using nlohmann::json;

namespace {
json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// The effects a scene can call for, by name. A scene file's list is complete: what it leaves out
// is off.
const std::vector<std::pair<std::string, bool Effects::*>>& effectTable() {
  static const std::vector<std::pair<std::string, bool Effects::*>> t = {
      {"fluid_motion", &Effects::fluid_motion}, {"surface_tension", &Effects::surface_tension},
      {"no_slip", &Effects::no_slip},           {"settling", &Effects::settling},
      {"diffusion", &Effects::diffusion},       {"deposition", &Effects::deposition},
      {"erosion", &Effects::erosion},           {"sources", &Effects::sources},
      {"sinks", &Effects::sinks},               {"rain", &Effects::rain}};
  return t;
}

std::string shown(const json& v) { return excerpt(v.dump()); }

// One JSON object being read: typed getters that say where and what, and a check that every key
// was used.
class Fields {
 public:
  Fields(const json& j, std::string path, const std::string& file) : j_(j), path_(std::move(path)), file_(file) {
    if (!j.is_object()) fail(path_, "an object", j);
  }
  [[noreturn]] void fail(const std::string& at, const std::string& expected, const json& found) const {
    throw SceneError(file_ + ": " + (at.empty() ? "(top level)" : at) + ": expected " + expected +
                     ", found " + shown(found));
  }
  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) {
    known_.push_back(key);
    return j_.contains(key);
  }
  const json& raw(const std::string& key) {
    known_.push_back(key);
    return j_.at(key);
  }
  double number(const std::string& key, double fallback, double lo, double hi, bool required = false) {
    if (!has(key)) {
      if (required) throw SceneError(file_ + ": " + at(key) + ": required field is missing");
      return fallback;
    }
    const json& v = j_.at(key);
    if (!v.is_number()) fail(at(key), "a number", v);
    const double x = v.get<double>();
    char range[96];
    std::snprintf(range, sizeof range, "a finite number in [%g, %g]", lo, hi);
    if (!std::isfinite(x) || x < lo || x > hi) fail(at(key), range, v);
    return x;
  }
  long long integer(const std::string& key, long long fallback, long long lo, long long hi) {
    if (!has(key)) return fallback;
    const json& v = j_.at(key);
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
      fail(at(key), "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", v);
    return v.get<long long>();
  }
  std::array<double, 2> vec2(const std::string& key) {
    if (!has(key)) throw SceneError(file_ + ": " + at(key) + ": required field is missing");
    const json& v = j_.at(key);
    if (!v.is_array() || v.size() != 2) fail(at(key), "an array of 2 numbers (x, z)", v);
    std::array<double, 2> out{};
    for (int a = 0; a < 2; ++a) {
      if (!v[a].is_number() || !std::isfinite(v[a].get<double>()))
        fail(at(key) + "[" + std::to_string(a) + "]", "a finite number", v[a]);
      out[size_t(a)] = v[a].get<double>();
    }
    return out;
  }
  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const json& v = j_.at(key);
    if (!v.is_boolean()) fail(at(key), "true or false", v);
    return v.get<bool>();
  }
  std::string text(const std::string& key, const std::string& fallback,
                   const std::vector<std::string>& allowed = {}) {
    if (!has(key)) return fallback;
    const json& v = j_.at(key);
    if (!v.is_string()) fail(at(key), "a string", v);
    std::string t = v.get<std::string>();
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), t) == allowed.end()) {
      std::string names;
      for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + a;
      fail(at(key), "one of " + names, v);
    }
    return t;
  }
  Eigen::Vector3d vec3(const std::string& key, bool required = true,
                       Eigen::Vector3d fallback = Eigen::Vector3d::Zero()) {
    if (!has(key)) {
      if (required) throw SceneError(file_ + ": " + at(key) + ": required field is missing");
      return fallback;
    }
    const json& v = j_.at(key);
    if (!v.is_array() || v.size() != 3) fail(at(key), "an array of 3 numbers", v);
    Eigen::Vector3d out;
    for (int a = 0; a < 3; ++a) {
      if (!v[a].is_number() || !std::isfinite(v[a].get<double>()))
        fail(at(key) + "[" + std::to_string(a) + "]", "a finite number", v[a]);
      out[a] = v[a].get<double>();
    }
    return out;
  }
  const json& array(const std::string& key) {
    static const json empty = json::array();
    if (!has(key)) return empty;
    const json& v = j_.at(key);
    if (!v.is_array()) fail(at(key), "an array", v);
    return v;
  }
  /// Every key must have been asked for; the first unknown one is refused (a long key is quoted
  /// in part, and only a short one gets a suggestion).
  void finish() const {
    for (const auto& [key, value] : j_.items()) {
      if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
      std::string names;
      for (const auto& k : known_)
        if (names.find("'" + k + "'") == std::string::npos) names += (names.empty() ? "'" : ", '") + k + "'";
      const std::string hint = key.size() <= 64 ? "did you mean '" + nearestName(key, known_) + "'?"
                                                : "valid keys here: " + names;
      throw SceneError(file_ + ": " + excerpt(at(key)) + ": unknown key (" + hint + ")");
    }
  }

 private:
  const json& j_;
  std::string path_;
  const std::string& file_;
  std::vector<std::string> known_;
};

constexpr double kBig = 1e6;  // metres: larger extents are surely a typo

// The number fields of the scene's structs, declared once: the reader and the writer both go
// through these tables, and a field left out of a file keeps its struct's default. `only`: a
// terrain field that belongs to one kind.
template <class S>
struct Real {
  const char* key;
  double S::*member;
  double lo, hi;
  bool required = false;
  const char* only = nullptr;
};
template <class S>
struct Whole {
  const char* key;
  int S::*member;
  long long lo, hi;
  const char* only = nullptr;
};

const std::vector<Real<TerrainSpec>>& terrainReals() {
  using T = TerrainSpec;
  static const std::vector<Real<T>> fields = {
      {"length_x", &T::length_x, 1e-6, kBig},   {"length_z", &T::length_z, 1e-6, kBig},
      {"cell", &T::cell, 1e-6, kBig},           {"slope", &T::slope, -100, 100},
      {"side_rise", &T::side_rise, -kBig, kBig}, {"amplitude", &T::amplitude, -kBig, kBig},
      {"base", &T::base, -kBig, kBig},          {"riser", &T::riser, 0.01, 1.0, false, "terraces"},
      {"rim", &T::rim, 0.05, 1.0, false, "bowl"}};
  return fields;
}
const std::vector<Whole<TerrainSpec>>& terrainWholes() {
  static const std::vector<Whole<TerrainSpec>> fields = {
      {"levels", &TerrainSpec::levels, 1, 1000, "terraces"}};
  return fields;
}
const std::vector<Real<NoiseSpec>>& noiseReals() {
  static const std::vector<Real<NoiseSpec>> fields = {
      {"amplitude", &NoiseSpec::amplitude, -kBig, kBig, true},
      {"feature", &NoiseSpec::feature, 1e-6, kBig}};
  return fields;
}
const std::vector<Whole<NoiseSpec>>& noiseWholes() {
  static const std::vector<Whole<NoiseSpec>> fields = {
      {"octaves", &NoiseSpec::octaves, 1, 16}, {"seed", &NoiseSpec::seed, 0, 2147483647}};
  return fields;
}
// (A source's and a rain's `stop` may be null, and comes after `start`: read apart.)
const std::vector<Real<Source>>& sourceReals() {
  static const std::vector<Real<Source>> fields = {{"radius", &Source::radius, 1e-9, kBig, true},
                                                   {"rate", &Source::rate, 1e-12, 1e6, true},
                                                   {"start", &Source::start, 0, 1e9}};
  return fields;
}
const std::vector<Real<Rain>>& rainReals() {
  static const std::vector<Real<Rain>> fields = {
      {"intensity_mm_h", &Rain::intensity_mm_h, 1e-6, 1e7, true},
      {"drop_height", &Rain::drop_height, 0, kBig},
      {"drop_speed", &Rain::drop_speed, 0, 1e3},
      {"start", &Rain::start, 0, 1e9}};
  return fields;
}

bool belongs(const char* only, const std::string& kind) { return !only || kind == only; }

template <class S>
void readFields(Fields& f, S& s, const std::vector<Real<S>>& reals,
                const std::vector<Whole<S>>& wholes = {}, const std::string& kind = "") {
  for (const Real<S>& r : reals)
    if (belongs(r.only, kind)) s.*r.member = f.number(r.key, s.*r.member, r.lo, r.hi, r.required);
  for (const Whole<S>& w : wholes)
    if (belongs(w.only, kind)) s.*w.member = int(f.integer(w.key, s.*w.member, w.lo, w.hi));
}

template <class S>
void writeFields(json& j, const S& s, const std::vector<Real<S>>& reals,
                 const std::vector<Whole<S>>& wholes = {}, const std::string& kind = "") {
  for (const Real<S>& f : reals)
    if (belongs(f.only, kind)) j[f.key] = s.*f.member;
  for (const Whole<S>& f : wholes)
    if (belongs(f.only, kind)) j[f.key] = s.*f.member;
}

const std::vector<std::string>& scalingRules() {
  static const std::vector<std::string> names = {"spacing", "fixed", "column", "pool"};
  return names;
}

json scalingToJson(const Scaling& c) {
  json j = {{"rule", scalingRules()[size_t(c.rule)]}};
  if (c.rule == Scaling::Rule::kColumn)
    j["width"] = c.width, j["cells"] = c.cells, j["slab_cells"] = c.slab_cells;
  if (c.rule == Scaling::Rule::kPool) j["particles"] = c.particles, j["layers"] = c.layers;
  return j;
}

Scaling scalingFromJson(const json& j, const std::string& file) {
  Fields f(j, "scaling", file);
  Scaling c;
  const std::string rule = f.text("rule", scalingRules()[0], scalingRules());
  c.rule = Scaling::Rule(std::find(scalingRules().begin(), scalingRules().end(), rule) -
                         scalingRules().begin());
  if (c.rule == Scaling::Rule::kColumn) {
    c.width = f.number("width", c.width, 1e-6, kBig, true);
    c.cells = int(f.integer("cells", c.cells, 4, 100000));
    c.slab_cells = int(f.integer("slab_cells", c.slab_cells, 1, 100000));
  }
  if (c.rule == Scaling::Rule::kPool) {
    c.particles = f.number("particles", c.particles, 8, 1e12, true);
    c.layers = int(f.integer("layers", c.layers, 1, 100000));
  }
  f.finish();
  return c;
}

StressPlan stressFromJson(const json& j, const std::string& file) {
  Fields f(j, "stress", file);
  StressPlan plan;
  plan.duration = f.number("duration", 0, 1e-9, 1e9, true);
  const json& jumps = f.array("jumps");
  for (size_t k = 0; k < jumps.size(); ++k) {
    Fields g(jumps[k], "stress.jumps[" + std::to_string(k) + "]", file);
    ParamJump p;
    p.time = g.number("time", 0, 0, 1e9, true);
    if (!g.has("param"))
      throw SceneError(file + ": " + g.at("param") + ": required field is missing");
    p.key = g.text("param", "");
    const ParamInfo* info = findParam(p.key);
    if (!info || !info->dmember)
      g.fail(g.at("param"), "the key of a real-valued parameter (docs/parameters.md)",
             g.raw("param"));
    p.factor = g.number("factor", 1, 0, 1e12, true);
    g.finish();
    plan.jumps.push_back(p);
  }
  f.finish();
  return plan;
}

}  // namespace

json paramsToJson(const SimParams& p) {
  json out = json::object();
  for (const ParamInfo& i : paramTable()) {
    std::string key = i.key;
    auto dot = key.find('.');
    json& group = out[key.substr(0, dot)];
    const std::string name = key.substr(dot + 1);
    if (i.choices)
      group[name] = i.choices[i.getChoice(p)];
    else if (i.imember)
      group[name] = p.*i.imember;
    else
      group[name] = p.*i.dmember;
  }
  return out;
}

json specToJson(const SceneSpec& s) {
  json j;
  j["version"] = 1;
  j["name"] = s.name;
  j["description"] = s.description;
  j["params"] = paramsToJson(s.params);
  const TerrainSpec& t = s.terrain;
  j["terrain"] = {{"kind", t.kind}};
  writeFields(j["terrain"], t, terrainReals(), terrainWholes(), t.kind);
  if (t.noise.amplitude != 0) writeFields(j["terrain"]["noise"], t.noise, noiseReals(), noiseWholes());
  if (t.kind == "heightmap") {
    j["terrain"]["file"] = t.file;
    j["terrain"]["height_min"] = t.height_min;
    j["terrain"]["height_max"] = t.height_max;
    if (t.heights != "scaled") j["terrain"]["heights"] = t.heights;
    j["terrain"]["crop"] = {t.crop_x, t.crop_z, t.crop_w, t.crop_h};
    if (t.raw_width > 0) j["terrain"]["raw_size"] = {t.raw_width, t.raw_height};
  }
  j["domain"] = {{"walls", s.domain.walls}};
  const Effects& e = s.effects;
  json effects = json::array();
  for (const auto& [name, member] : effectTable())
    if (e.*member) effects.push_back(name);
  j["effects"] = effects;
  json blocks = json::array();
  for (const WaterBlock& b : s.blocks) {
    json jb = {{"min", vec(b.min)}, {"max", vec(b.max)}, {"above_terrain", b.above_terrain}};
    if (b.flood) jb["flood_from"] = {b.flood_from.x(), b.flood_from.y()};
    blocks.push_back(jb);
  }
  json marks = json::array();
  for (const SedimentMark& m : s.sediment) marks.push_back({{"position", vec(m.position)}, {"c", m.c}});
  j["water"] = {{"blocks", blocks}, {"sediment", marks}};
  json sources = json::array();
  for (const Source& src : s.sources)
  {
    json js = {{"position", vec(src.center)},
               {"direction", vec(src.direction)},
               {"stop", std::isfinite(src.stop) ? json(src.stop) : json(nullptr)}};
    writeFields(js, src, sourceReals());
    sources.push_back(js);
  }
  j["sources"] = sources;
  json sinks = json::array();
  for (const Sink& k : s.sinks) sinks.push_back({{"min", vec(k.lo)}, {"max", vec(k.hi)}});
  j["sinks"] = sinks;
  json rain = json::array();
  for (const Rain& r : s.rain)
  {
    json jr = {{"min", {r.lo_x, r.lo_z}},
               {"max", {r.hi_x, r.hi_z}},
               {"stop", std::isfinite(r.stop) ? json(r.stop) : json(nullptr)},
               {"seed", r.seed}};
    writeFields(jr, r, rainReals());
    rain.push_back(jr);
  }
  j["rain"] = rain;
  if (s.has_camera) j["camera"] = {{"eye", vec(s.camera_eye)}, {"target", vec(s.camera_target)}};
  j["scaling"] = scalingToJson(s.scaling);
  if (s.stress.duration > 0) {
    json jumps = json::array();
    for (const ParamJump& p : s.stress.jumps)
      jumps.push_back({{"time", p.time}, {"param", p.key}, {"factor", p.factor}});
    j["stress"] = {{"duration", s.stress.duration}, {"jumps", jumps}};
  }
  return j;
}

json sceneToJson(const Scene& scene) {
  json j = specToJson(scene.spec);
  const SimParams& p = scene.spec.params;
  // What the spec built to (not read back): the grid and the particle count.
  const Heightfield& hf = scene.desc.terrain;
  j["built"] = {{"particles", scene.desc.particles.size()},
                {"support_m", p.support()},
                {"particle_mass_kg", p.particleMass()},
                {"terrain_nx", hf.nx()},
                {"terrain_nz", hf.nz()},
                {"terrain_dx", hf.dx()},
                {"terrain_dz", hf.dz()},
                {"height_min", hf.minHeight()},
                {"height_max", hf.maxHeight()}};
  return j;
}

SceneSpec specFromJson(const json& j, const std::string& file) {
  SceneSpec s;
  Fields top(j, "", file);
  const double version = top.number("version", 0, 1, 1, true);
  (void)version;
  s.name = top.text("name", "scene");  // a file without one: "scene" (SceneSpec's is empty)
  s.description = top.text("description", "");
  if (top.has("params")) {
    Fields groups(top.raw("params"), "params", file);
    std::vector<std::string> names;
    for (const ParamInfo& i : paramTable()) {
      std::string key = i.key;
      std::string g = key.substr(0, key.find('.'));
      if (std::find(names.begin(), names.end(), g) == names.end()) names.push_back(g);
    }
    for (const std::string& g : names) {
      if (!groups.has(g)) continue;
      const json& obj = groups.raw(g);
      Fields f(obj, "params." + g, file);
      for (const ParamInfo& i : paramTable()) {
        std::string key = i.key;
        if (key.substr(0, key.find('.')) != g) continue;
        std::string name = key.substr(key.find('.') + 1);
        if (!f.has(name)) continue;
        const json& v = f.raw(name);
        std::string value;
        if (i.choices) {
          if (!v.is_string()) f.fail(f.at(name), "a string", v);
          value = v.get<std::string>();
        } else {
          if (!v.is_number()) f.fail(f.at(name), "a number", v);
          char buf[64];
          std::snprintf(buf, sizeof buf, "%.17g", v.get<double>());
          value = buf;
        }
        std::string err = setParam(s.params, key, value);
        if (!err.empty()) throw SceneError(file + ": params." + key + ": " + err);
      }
      f.finish();
    }
    groups.finish();
  }
  {
    const json terrain = top.has("terrain") ? top.raw("terrain") : json::object();
    Fields t(terrain, "terrain", file);
    s.terrain.kind = t.text("kind", s.terrain.kind, terrainKinds());
    readFields(t, s.terrain, terrainReals(), terrainWholes(), s.terrain.kind);
    if (t.has("noise")) {
      Fields n(t.raw("noise"), "terrain.noise", file);
      readFields(n, s.terrain.noise, noiseReals(), noiseWholes());
      n.finish();
    }
    if (s.terrain.kind == "heightmap") {
      std::string f = t.text("file", "");
      if (f.empty()) throw SceneError(file + ": terrain.file: required for a heightmap terrain");
      // Relative to the scene file.
      if (f.rfind("builtin:", 0) == 0) {
        s.terrain.file = f;  // built into the binary
      } else {
        std::filesystem::path p(f);
        if (p.is_relative()) p = std::filesystem::path(file).parent_path() / p;
        s.terrain.file = std::filesystem::absolute(p).lexically_normal().string();
      }
      s.terrain.height_min = t.number("height_min", s.terrain.height_min, -kBig, kBig);
      s.terrain.height_max = t.number("height_max", s.terrain.height_max, s.terrain.height_min, kBig);
      s.terrain.heights = t.text("heights", s.terrain.heights, {"scaled", "metres"});
      if (t.has("crop")) {
        const json& c = t.raw("crop");
        if (!c.is_array() || c.size() != 4) t.fail("terrain.crop", "[x, z, width, height] in pixels", c);
        int* dst[4] = {&s.terrain.crop_x, &s.terrain.crop_z, &s.terrain.crop_w, &s.terrain.crop_h};
        for (int a = 0; a < 4; ++a) {
          if (!c[a].is_number_integer() || c[a].get<long>() < 0 || c[a].get<long>() > 1000000)
            t.fail("terrain.crop[" + std::to_string(a) + "]", "a whole number of pixels ≥ 0", c[a]);
          *dst[a] = c[a].get<int>();
        }
      }
      if (t.has("raw_size")) {
        const json& c = t.raw("raw_size");
        if (!c.is_array() || c.size() != 2 || !c[0].is_number_integer() || !c[1].is_number_integer() ||
            c[0].get<long>() < 2 || c[1].get<long>() < 2 || c[0].get<long>() > 1000000 ||
            c[1].get<long>() > 1000000)
          t.fail("terrain.raw_size", "[width, height] in pixels, each ≥ 2", c);
        s.terrain.raw_width = c[0].get<int>();
        s.terrain.raw_height = c[1].get<int>();
      }
    }
    t.finish();
  }
  if (top.has("domain")) {
    Fields d(top.raw("domain"), "domain", file);
    s.domain.walls = d.boolean("walls", s.domain.walls);
    d.finish();
  }
  if (top.has("effects")) {
    const json& e = top.raw("effects");
    if (!e.is_array()) top.fail("effects", "an array of effect names", e);
    s.effects = Effects{};
    for (const auto& [name, member] : effectTable()) s.effects.*member = false;
    std::vector<std::string> names;
    for (const auto& [name, member] : effectTable()) names.push_back(name);
    for (size_t k = 0; k < e.size(); ++k) {
      const std::string at = "effects[" + std::to_string(k) + "]";
      if (!e[k].is_string()) top.fail(at, "an effect name", e[k]);
      const std::string name = e[k].get<std::string>();
      bool found = false;
      for (const auto& [n, member] : effectTable())
        if (n == name) s.effects.*member = true, found = true;
      if (!found)
        throw SceneError(file + ": " + at + ": unknown effect '" + name + "' (did you mean '" +
                         nearestName(name, names) + "'?)");
    }
  }
  if (top.has("water")) {
    Fields w(top.raw("water"), "water", file);
    const json& blocks = w.array("blocks");
    for (size_t k = 0; k < blocks.size(); ++k) {
      Fields b(blocks[k], "water.blocks[" + std::to_string(k) + "]", file);
      WaterBlock wb;
      wb.min = b.vec3("min");
      wb.max = b.vec3("max");
      wb.above_terrain = b.boolean("above_terrain", wb.above_terrain);
      if (b.has("flood_from")) {
        const auto seed = b.vec2("flood_from");
        wb.flood = true;
        wb.flood_from = {seed[0], seed[1]};
      }
      b.finish();
      for (int a = 0; a < 3; ++a)
        if (!(wb.max[a] > wb.min[a]))
          throw SceneError(file + ": water.blocks[" + std::to_string(k) +
                           "]: max must exceed min on every axis");
      s.blocks.push_back(wb);
    }
    const json& marks = w.array("sediment");
    for (size_t k = 0; k < marks.size(); ++k) {
      Fields m(marks[k], "water.sediment[" + std::to_string(k) + "]", file);
      SedimentMark sm{m.vec3("position"), m.number("c", 0, 0, s.params.c_max, true)};
      m.finish();
      s.sediment.push_back(sm);
    }
    w.finish();
  }
  const json& sources = top.array("sources");
  for (size_t k = 0; k < sources.size(); ++k) {
    Fields f(sources[k], "sources[" + std::to_string(k) + "]", file);
    Source src;
    src.center = f.vec3("position");
    src.direction = f.vec3("direction");
    if (src.direction.norm() == 0)
      throw SceneError(file + ": " + f.at("direction") + ": must not be the zero vector");
    readFields(f, src, sourceReals());
    if (f.has("stop") && !f.raw("stop").is_null())
      src.stop = f.number("stop", 0, src.start, 1e9);
    f.finish();
    s.sources.push_back(src);
  }
  const json& sinks = top.array("sinks");
  for (size_t k = 0; k < sinks.size(); ++k) {
    Fields f(sinks[k], "sinks[" + std::to_string(k) + "]", file);
    Sink sk{f.vec3("min"), f.vec3("max")};
    f.finish();
    if (!((sk.hi - sk.lo).minCoeff() > 0))
      throw SceneError(file + ": sinks[" + std::to_string(k) + "]: max must exceed min on every axis");
    s.sinks.push_back(sk);
  }
  const json& rain = top.array("rain");
  for (size_t k = 0; k < rain.size(); ++k) {
    Fields f(rain[k], "rain[" + std::to_string(k) + "]", file);
    Rain r;
    const auto lo = f.vec2("min"), hi = f.vec2("max");
    r.lo_x = lo[0], r.lo_z = lo[1], r.hi_x = hi[0], r.hi_z = hi[1];
    if (!(r.hi_x > r.lo_x && r.hi_z > r.lo_z))
      throw SceneError(file + ": " + f.at("max") + ": must exceed min on both axes (x, z)");
    readFields(f, r, rainReals());
    if (f.has("stop") && !f.raw("stop").is_null()) r.stop = f.number("stop", 0, r.start, 1e9);
    r.seed = uint64_t(f.integer("seed", (long long)r.seed, 0, 9007199254740991LL));
    f.finish();
    s.rain.push_back(r);
  }
  if (top.has("camera")) {
    Fields c(top.raw("camera"), "camera", file);
    s.has_camera = true;
    s.camera_eye = c.vec3("eye");
    s.camera_target = c.vec3("target");
    c.finish();
    if ((s.camera_eye - s.camera_target).norm() == 0)
      throw SceneError(file + ": camera.target: must differ from camera.eye");
  }
  if (top.has("scaling")) s.scaling = scalingFromJson(top.raw("scaling"), file);
  if (top.has("stress")) s.stress = stressFromJson(top.raw("stress"), file);
  if (top.has("built")) top.raw("built");  // written by sceneToJson for people; not read back
  top.finish();
  // What the scene asks of the machine, before anything is allocated (buildScene checks again,
  // after --set and --scale).
  try {
    checkFootprint(s);
  } catch (const SceneError& e) {
    throw SceneError(file + ": " + e.what());
  }
  return s;
}

std::string excerpt(const std::string& text, size_t limit) {
  return text.size() > limit ? text.substr(0, limit - 3) + "..." : text;
}

json parseJsonText(const std::string& text, const std::string& file) {
  // The reader's own stack of open arrays and objects: it bounds the depth before the parser
  // (and every recursive function after it) goes deeper, finds a key given twice, and says where
  // in the document an error lies.
  struct Open {
    bool object;
    std::vector<std::string> keys;
    size_t index = 0;
  };
  std::vector<Open> open;
  auto where = [&] {
    std::string path;
    for (const Open& o : open) {
      if (o.object && !o.keys.empty()) path += (path.empty() ? "" : ".") + o.keys.back();
      if (!o.object) path += "[" + std::to_string(o.index) + "]";
    }
    return path.empty() ? std::string("(top level)") : excerpt(path, 120);
  };
  auto done = [&] {
    if (!open.empty() && !open.back().object) ++open.back().index;
  };
  auto callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (open.size() >= size_t(kMaxJsonDepth))
          throw SceneError(file + ": " + where() + ": nested deeper than " +
                           std::to_string(kMaxJsonDepth) + " levels of arrays and objects");
        open.push_back({event == json::parse_event_t::object_start, {}, 0});
        break;
      case json::parse_event_t::key: {
        const std::string key = parsed.get<std::string>();
        auto& keys = open.back().keys;
        if (std::find(keys.begin(), keys.end(), key) != keys.end()) {
          keys.push_back(key);
          throw SceneError(file + ": " + where() + ": key given twice in one object");
        }
        keys.push_back(key);
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        open.pop_back();
        done();
        break;
      case json::parse_event_t::value: done(); break;
    }
    return true;
  };
  try {
    return json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::out_of_range& e) {
    // The lexer refuses a number beyond double range (1e999) before any value event: the path
    // is where it stood.
    std::string what = e.what();
    const size_t quote = what.find('\'');
    throw SceneError(file + ": " + where() + ": number beyond the range of a double" +
                     (quote != std::string::npos ? " (" + excerpt(what.substr(quote), 40) + ")" : ""));
  } catch (const json::exception& e) {
    // "…; last read: '<token>'" can quote megabytes: keep its start.
    std::string what = e.what();
    const size_t last = what.find("last read: '");
    if (last != std::string::npos) what = what.substr(0, last + 11) + excerpt(what.substr(last + 11), 40);
    throw SceneError(file + ": not valid JSON: " + excerpt(what, 240));
  }
}

SceneSpec loadSceneFile(const std::string& path) {
  std::string text;
  try {
    text = readInputFile(path, "scene file", kMaxSceneFileBytes);
  } catch (const InputFileError& e) {
    throw SceneError(e.what());
  }
  return specFromJson(parseJsonText(text, path), path);
}

}  // namespace scour
