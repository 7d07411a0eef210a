// The World's state as bytes: the hash the golden and determinism tests compare, saveState and
// loadState (checkpoints, the window's snapshots), and the memory it holds.
#include "engine/world.h"
#include "engine/world_parts.h"

#include <algorithm>
#include <cstring>
#include <istream>
#include <ostream>
#include <type_traits>

namespace scour {

using detail::wallSurfaceFor;

uint64_t World::stateHash() const {
  uint64_t h = 1469598103934665603ULL;
  auto mix = [&](const void* data, size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (size_t k = 0; k < bytes; ++k) h = (h ^ c[k]) * 1099511628211ULL;
  };
  uint64_t n = fluid_.size();
  mix(&n, sizeof n);
  mix(fluid_.x.data(), n * sizeof(Vec3f));
  mix(fluid_.v.data(), n * sizeof(Vec3f));
  mix(fluid_.sed.data(), n * sizeof(double));
  mix(terrain_.heights().data(), terrain_.heights().size() * sizeof(double));
  mix(&time_, sizeof time_);
  // The soil waiting for its triangle (sediment.h), in the state's order, and the bed's clock.
  for (int t : accumulator_.touched) {
    mix(&t, sizeof t);
    mix(&accumulator_.volume[size_t(t)], sizeof(double));
    mix(&accumulator_.code[size_t(t)], 1);
  }
  mix(&morphTime_, sizeof morphTime_);
  mix(&factor_, sizeof factor_);
  return h;
}

namespace {

template <class T>
void put(std::ostream& o, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  o.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
void putVec(std::ostream& o, const std::vector<T>& v) {
  put(o, uint64_t(v.size()));
  o.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(T)));
}
template <class T>
void get(std::istream& in, T& v, const char* what) {
  in.read(reinterpret_cast<char*>(&v), sizeof v);
  if (!in) throw std::runtime_error(std::string("state ends early (in ") + what + ")");
}
template <class T>
void getVec(std::istream& in, std::vector<T>& v, const char* what, uint64_t expect = UINT64_MAX) {
  uint64_t n = 0;
  get(in, n, what);
  if (expect != UINT64_MAX && n != expect)
    throw std::runtime_error(std::string("state does not fit this scene (") + what + ": " +
                             std::to_string(n) + " entries, the scene has " +
                             std::to_string(expect) + ")");
  // Never more than the bytes that are left: a corrupt count cannot ask for memory.
  const std::streampos here = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff left = in.tellg() - here;
  in.seekg(here);
  if (!in || left < 0 || n > uint64_t(left) / sizeof(T))
    throw std::runtime_error(std::string("state is corrupt (") + what + ": " + std::to_string(n) +
                             " entries, more than the state holds)");
  v.resize(n);
  in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(T)));
  if (!in) throw std::runtime_error(std::string("state ends early (in ") + what + ")");
}

constexpr uint32_t kStateTag = 0x444C5257;  // "WRLD"
// Version 2 adds the sediment defects (naive advection), version 3 the last density rate (the
// next Δt's bound), version 4 the count of terrain contacts, version 5 the blocks of cells the
// boundary particles stand for; older states load with none (each particle stands for part of
// its triangle, as those builds sampled). Version 6 adds the geologic clock (the bed's time, the
// factor in effect and the one asked for, what the factor added to the soil budget, the bed
// guard's record) and the volumes waiting in the terrain accumulator (below
// kTerrainApplyOverSpacing); older states load at the scene's factor with the bed's time equal to
// the water's, and wait for none. Version 7 adds the flow record (flow_record.h: the bed time it
// covers, its tiles and their values); older states load with an empty one, recording from then.
// Version 8 has the flow record in tiles of 8 × 8 vertices (version 7's of 16 are cut into them).
// Version 9 adds what each waiting volume is (TerrainAccumulator::code: a triangle's own sum, or
// the bank of a block of cells whose first triangle it is); in older states each is a triangle's.
constexpr uint32_t kStateVersion = 9;

}  // namespace

void Ledger::save(std::ostream& o) const {
  put(o, removedBySinks), put(o, removedByOutflow), put(o, emitted), put(o, removedSediment);
  put(o, painted);
  put(o, invariants);
  put(o, defects);
  put(o, terrainContacts);
  put(o, morphological), put(o, guard);
}

void Ledger::load(std::istream& in, uint32_t version) {
  get(in, removedBySinks, "counters"), get(in, removedByOutflow, "counters");
  get(in, emitted, "counters"), get(in, removedSediment, "counters");
  get(in, painted, "counters");
  get(in, invariants, "invariants");
  defects = {};
  if (version >= 2) get(in, defects, "sediment defects");
  terrainContacts = 0;
  if (version >= 4) get(in, terrainContacts, "terrain contacts");
  morphological = 0, guard = {};
  if (version >= 6) get(in, morphological, "geologic clock"), get(in, guard, "geologic clock");
}

void Supply::saveProgress(std::ostream& o) const {
  put(o, uint64_t(emitters.size()));
  for (const Emitter& e : emitters) put(o, e.travelled), put(o, e.emitted), put(o, e.blocked);
  put(o, uint64_t(rain.size()));
  for (const RainState& r : rain) put(o, r.pending), put(o, r.drawn), put(o, r.emitted), put(o, r.blocked);
}

void Supply::loadProgress(std::istream& in) {
  std::vector<Emitter> emitters = this->emitters;
  std::vector<RainState> rain = this->rain;
  uint64_t count = 0;
  get(in, count, "sources");
  if (count != emitters.size())
    throw std::runtime_error("state does not fit this scene (" + std::to_string(count) +
                             " sources, the scene has " + std::to_string(emitters.size()) + ")");
  for (Emitter& e : emitters) get(in, e.travelled, "sources"), get(in, e.emitted, "sources"), get(in, e.blocked, "sources");
  get(in, count, "rain");
  if (count != rain.size())
    throw std::runtime_error("state does not fit this scene (" + std::to_string(count) +
                             " rain regions, the scene has " + std::to_string(rain.size()) + ")");
  for (RainState& r : rain)
    get(in, r.pending, "rain"), get(in, r.drawn, "rain"), get(in, r.emitted, "rain"), get(in, r.blocked, "rain");
  this->emitters = std::move(emitters);
  this->rain = std::move(rain);
}

void World::saveState(std::ostream& o) const {
  put(o, kStateTag);
  put(o, kStateVersion);
  fluid_.forEachArray([&](const char*, const auto& array) { putVec(o, array); });
  putVec(o, vhat_);
  putVec(o, terrain_.heights());
  putVec(o, boundary_.x), putVec(o, boundary_.triangle), putVec(o, boundary_.area), putVec(o, boundary_.bary);
  putVec(o, boundary_.patch), putVec(o, boundary_.extent);
  putVec(o, sampler_.activeTiles());
  supply_.saveProgress(o);
  put(o, time_), put(o, dt_), put(o, step_), put(o, supply_.nextId);
  ledger_.save(o);
  put(o, densityRate_);
  put(o, morphTime_), put(o, factor_), put(o, params_.morphological_factor);
  std::vector<double> waiting;
  for (int t : accumulator_.touched) waiting.push_back(accumulator_.volume[size_t(t)]);
  putVec(o, accumulator_.touched), putVec(o, waiting);
  put(o, flow_.time()), putVec(o, flow_.tiles()), putVec(o, flow_.values());
  std::vector<uint8_t> codes;
  for (int t : accumulator_.touched) codes.push_back(accumulator_.code[size_t(t)]);
  putVec(o, codes);
}

void World::loadState(std::istream& in) {
  uint32_t tag = 0, version = 0;
  get(in, tag, "header");
  get(in, version, "header");
  if (tag != kStateTag) throw std::runtime_error("not a Scour world state");
  if (version < 1 || version > kStateVersion)
    throw std::runtime_error("world state version " + std::to_string(version) +
                             ", this build reads versions 1 to " + std::to_string(kStateVersion));
  Fluid f;
  uint64_t n = UINT64_MAX;  // the first array's count, which every other one must have
  f.forEachArray([&](const char* name, auto& array) {
    getVec(in, array, name, n);
    n = array.size();
  });
  std::vector<Vec3f> vhat;
  getVec(in, vhat, "predicted velocities");  // empty while the fluid is frozen
  if (!vhat.empty() && vhat.size() != n) throw std::runtime_error("state is corrupt (predicted velocities)");
  for (size_t i = 0; i < n; ++i)
    if (!f.x[i].allFinite() || !f.v[i].allFinite() || !std::isfinite(f.rho[i]) || !(f.rho[i] > 0) ||
        !std::isfinite(f.sed[i]) || f.sed[i] < 0)
      throw std::runtime_error("state is corrupt (particle " + std::to_string(i) + " is not finite)");
  std::vector<double> heights;
  getVec(in, heights, "terrain heights", terrain_.heights().size());
  for (double h : heights)
    if (!std::isfinite(h)) throw std::runtime_error("state is corrupt (a terrain height is not finite)");
  BoundaryParticles b;
  getVec(in, b.x, "boundary particles");
  const uint64_t nb = b.x.size();
  getVec(in, b.triangle, "boundary triangles", nb), getVec(in, b.area, "boundary areas", nb);
  getVec(in, b.bary, "boundary coordinates", nb);
  for (int t : b.triangle)
    if (t < 0 || t >= terrain_.triangleCount()) throw std::runtime_error("state is corrupt (boundary triangle)");
  b.cellsX = terrain_.nx() - 1;
  if (version >= 5) {
    getVec(in, b.patch, "boundary blocks", nb), getVec(in, b.extent, "boundary blocks", nb);
    for (size_t j = 0; j < nb; ++j) {
      if (b.patch[j] < 0) continue;
      const int i0 = b.patch[j] % b.cellsX, k0 = b.patch[j] / b.cellsX;
      const int bx = b.extent[j] & 15, bz = b.extent[j] >> 4;
      if (bx < 1 || bz < 1 || i0 + bx > b.cellsX || k0 + bz > terrain_.nz() - 1)
        throw std::runtime_error("state is corrupt (boundary block)");
    }
  } else {
    b.patch.assign(nb, -1), b.extent.assign(nb, 0);
  }
  std::vector<int> tiles;
  getVec(in, tiles, "active tiles");
  for (int t : tiles)
    if (t < 0 || t >= sampler_.tileCount()) throw std::runtime_error("state is corrupt (tile)");
  // Everything is read into locals and checked before any of it replaces the world's own: a
  // state refused half-way leaves the world as it was.
  Supply supply = supply_;
  supply.loadProgress(in);
  double time = 0, dt = 0, densityRate = 0;
  long step = 0;
  get(in, time, "clock"), get(in, dt, "clock"), get(in, step, "clock"), get(in, supply.nextId, "clock");
  Ledger ledger;
  ledger.load(in, version);
  if (version >= 3) get(in, densityRate, "density rate");
  std::vector<int> waitingAt;
  std::vector<double> waiting;
  // Older states: the bed's clock is the water's, at the scene's factor.
  double morphTime = time, factor = params_.morphological_factor, requested = factor;
  if (version >= 6) {
    get(in, morphTime, "geologic clock"), get(in, factor, "geologic clock"), get(in, requested, "geologic clock");
    if (!std::isfinite(morphTime) || morphTime < 0 || !(factor >= 1 && factor <= 1e6) || !(requested >= factor && requested <= 1e6))
      throw std::runtime_error("state is corrupt (geologic clock)");
    getVec(in, waitingAt, "waiting terrain volumes"), getVec(in, waiting, "waiting terrain volumes", waitingAt.size());
    std::vector<uint8_t> seen(size_t(terrain_.triangleCount()), 0);
    for (size_t e = 0; e < waitingAt.size(); ++e) {
      const int t = waitingAt[e];
      if (t < 0 || t >= terrain_.triangleCount() || seen[size_t(t)] || !std::isfinite(waiting[e]))
        throw std::runtime_error("state is corrupt (waiting terrain volumes)");
      seen[size_t(t)] = 1;
    }
  }
  FlowRecord flow;
  flow.reset(terrain_.nx(), terrain_.nz());
  if (version >= 7) {
    double recorded = 0;
    std::vector<int> tiles;
    std::vector<double> values;
    get(in, recorded, "flow maps"), getVec(in, tiles, "flow maps"), getVec(in, values, "flow maps");
    flow.restore(terrain_.nx(), terrain_.nz(), recorded, std::move(tiles), std::move(values), version >= 8 ? FlowRecord::kTile : 16);
  }
  // What each waiting volume is: a triangle's own sum, or the bank of a block of cells (a tile's
  // at most) inside the terrain whose first triangle holds it.
  std::vector<uint8_t> codes(waitingAt.size(), TerrainAccumulator::kTriangle);
  if (version >= 9) {
    getVec(in, codes, "waiting terrain volumes", waitingAt.size());
    const int cellsX = terrain_.nx() - 1, rows = terrain_.nz() - 1;
    for (size_t e = 0; e < codes.size(); ++e) {
      const uint8_t c = codes[e];
      const int t = waitingAt[e], cell = t / 2, bx = c & 15, bz = c >> 4;
      const int most = BoundarySampler::kTileCells;
      const bool head = TerrainAccumulator::isHead(c) && bx >= 1 && bz >= 1 && bx <= most && bz <= most && t % 2 == 0 &&
                        cell % cellsX + bx <= cellsX && cell / cellsX + bz <= rows;
      if (c != TerrainAccumulator::kTriangle && !head) throw std::runtime_error("state is corrupt (waiting terrain volumes)");
    }
  }
  f.scratch.clear();
  flow_ = std::move(flow);
  supply_ = std::move(supply);
  time_ = time, dt_ = dt, step_ = step, densityRate_ = densityRate;
  fluid_ = std::move(f);
  vhat_ = std::move(vhat);
  terrain_.heights() = std::move(heights);
  wall_ = wallSurfaceFor(terrain_, params_);
  boundary_ = std::move(b);
  sampler_.setActiveTiles(std::move(tiles));
  accumulator_.resize(terrain_.triangleCount(), terrain_.heights().size(), terrain_.nx() - 1);
  for (size_t e = 0; e < waitingAt.size(); ++e) {
    const int t = waitingAt[e];
    accumulator_.touched.push_back(t), accumulator_.volume[size_t(t)] = waiting[e], accumulator_.code[size_t(t)] = codes[e];
  }
  // The factor the guard had lowered holds while the speed-up asked for is the one the state was
  // saved under; a world whose user has asked for another since (a snapshot restored after the
  // slider moved) runs at what they asked for.
  morphTime_ = morphTime, factor_ = requested == params_.morphological_factor ? factor : params_.morphological_factor;
  ledger.initialSoil = ledger_.initialSoil;
  ledger_ = ledger;
  ledger_.energy = mechanicalEnergy();
  // The neighbor lists of the last search: the particles have not moved since it (a step ends
  // with a kick), and the boundary lists are rebuilt on the boundary particles' places.
  buildFluidLists();
  if (needsBoundary()) buildBoundaryLists();
  // DFSPH's α and wall gradients follow from the positions (the density it recomputes is the one
  // saved, bit for bit: the same sums over the same lists).
  if (implicit() && effects_.fluid_motion)
    dfsphFactors(dfsphK_, neighbors_.fluid(), wall_.of(terrain_), domain_, fluid_, dfsph_);
}

size_t World::memoryBytes() const {
  // The fluid's arrays, the predicted velocities and the scratch array.
  const size_t per = Fluid::bytesPerParticle() + sizeof(Vec3f) + sizeof(float);
  return fluid_.x.capacity() * per + neighbors_.bytes() +
         boundary_.x.capacity() * (sizeof(Vec3f) + 2 * sizeof(int) + sizeof(double) + sizeof(Eigen::Vector2f) + 1) +
         (sedimentWork_.conc.capacity() + sedimentWork_.hind.capacity()) * sizeof(float) +
         sedimentWork_.scale.capacity() * sizeof(SedimentWorkspace::Scales) +
         sedimentWork_.delta.capacity() * sizeof(double) + sedimentWork_.tau.capacity() * sizeof(float) + flow_.bytes() +
         dfsph_.bytes();
}

}  // namespace scour
