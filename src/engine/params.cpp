#include "engine/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <type_traits>
#include <utility>

#include "engine/kernels.h"

namespace scour {
namespace {

const char* const kEosChoices[] = {"tait", "ideal_gas", nullptr};
const char* const kDensityChoices[] = {"continuity", "summation", nullptr};
const char* const kNeighborChoices[] = {"grid", "kd_tree", nullptr};
const char* const kSamplingChoices[] = {"triangles", "spacing", nullptr};
const char* const kAdvectionChoices[] = {"donor_acceptor", "naive_gradient", nullptr};
const char* const kDiffusionFormChoices[] = {"consistent", "printed", nullptr};
const char* const kSolverChoices[] = {"wcsph", "dfsph", nullptr};

ParamInfo real(const char* key, const char* label, const char* symbol, const char* unit, double lo,
               double hi, const char* help, double SimParams::*m) {
  ParamInfo i{key, label, symbol, unit, lo, hi, help};
  i.dmember = m;
  return i;
}
ParamInfo integer(const char* key, const char* label, const char* symbol, const char* unit,
                  double lo, double hi, const char* help, int SimParams::*m) {
  ParamInfo i{key, label, symbol, unit, lo, hi, help};
  i.imember = m;
  return i;
}
// An enum field M, named by `choices` in enumerator order.
template <auto M>
ParamInfo choice(const char* key, const char* label, const char* help, const char* const* choices) {
  using E = std::remove_reference_t<decltype(std::declval<SimParams&>().*M)>;
  int count = 0;
  while (choices[count]) ++count;
  ParamInfo i{key, label, "", "-", 0.0, double(count - 1), help};
  i.choices = choices;
  i.getChoice = [](const SimParams& p) { return int(p.*M); };
  i.setChoice = [](SimParams& p, int v) { p.*M = E(v); };
  return i;
}

// The span of the window's slider, where the valid range is too wide for a hand (Kε's valid
// [0, 10⁴] on 300 pixels moved 0.1 to 7,000 in half a slider).
ParamInfo slider(ParamInfo i, double lo, double hi) {
  i.slider_min = lo, i.slider_max = hi;
  return i;
}

std::vector<ParamInfo> makeTable() {
  using P = SimParams;
  return {
      slider(real("fluid.spacing", "Particle spacing", "Δs", "m", 1e-4, 100.0,
                  "Distance between neighbouring fluid particles at rest.", &P::spacing),
             0.001, 1.0),
      real("fluid.support_over_spacing", "Support / spacing", "h/Δs", "-", 1.5, 3.0,
           "Kernel support radius in particle spacings (paper: h ≈ 2Δs).",
           &P::support_over_spacing),
      slider(real("fluid.rest_density", "Rest density", "ρ0", "kg/m³", 1.0, 1e5,
                  "Density of water at rest.", &P::rest_density),
             100.0, 1e4),
      slider(real("fluid.sound_speed", "Speed of sound", "c_s", "m/s", 0.1, 1e4,
                  "Numerical speed of sound of the weakly compressible fluid; ≥ 10·|v|max.",
                  &P::sound_speed),
             1.0, 1000.0),
      choice<&P::eos>("fluid.eos", "Equation of state",
                      "tait: p = B((ρ/ρ0)^7 − 1); ideal_gas: Müller's p = c_s²(ρ − ρ0).",
                      kEosChoices),
      choice<&P::density>(
          "fluid.density", "Density method",
          "continuity: dρ/dt from the velocity divergence (+ δ-SPH); summation: ρ = Σ m W.",
          kDensityChoices),
      real("fluid.density_diffusion", "Density diffusion", "δ", "-", 0.0, 1.0,
           "δ-SPH diffusion of the continuity density (Molteni & Colagrossi 2009).",
           &P::density_diffusion),
      slider(real("fluid.viscosity", "Viscosity", "ν", "m²/s", 0.0, 10.0,
                  "Artificial kinematic viscosity (viscosity-kernel Laplacian).", &P::viscosity),
             1e-06, 1.0),
      slider(real("fluid.surface_tension", "Surface tension", "κ", "m³/s²", 0.0, 1.0,
                  "Becker–Teschner cohesion strength.", &P::surface_tension),
             1e-05, 1.0),
      slider(real("fluid.gravity", "Gravity", "g", "m/s²", 0.0, 100.0,
                  "Gravitational acceleration, pointing along −y.", &P::gravity),
             0.0, 30.0),
      choice<&P::solver>(
          "fluid.solver", "Pressure solver",
          "wcsph: weakly compressible (Tait), Δt from the sound speed; dfsph: divergence-free "
          "SPH, an implicit pressure at the density error asked for, Δt from the velocity.",
          kSolverChoices),
      slider(real("fluid.max_density_error", "Density error (DFSPH)", "η", "-", 1e-5, 0.1,
                  "DFSPH: the mean compression (ρ − ρ0)/ρ0 the density solve leaves.",
                  &P::max_density_error),
             1e-4, 0.1),
      slider(real("fluid.max_divergence_error", "Divergence error (DFSPH)", "η_v", "-", 1e-5, 0.1,
                  "DFSPH: the mean compression rate × Δt, Δt (Dρ/Dt)/ρ0, the divergence solve "
                  "leaves.",
                  &P::max_divergence_error),
             1e-4, 0.1),
      slider(integer("fluid.max_iterations", "Solver iterations (DFSPH)", "", "-", 1.0, 10000.0,
                     "DFSPH: the most iterations of each solve in a step.", &P::max_iterations),
             1.0, 1000.0),
      real("time.max_dt", "Maximum time step", "Δt", "s", 1e-7, 0.01,
           "Upper bound on the adaptive time step (paper: 2 ms).", &P::max_dt),
      real("time.cfl", "CFL factor", "λ", "-", 0.01, 0.4,
           "Δt ≤ λ·h / max(c_s, |v|max). 0.4 is the stability limit (`scour stress`, cfl-limit).",
           &P::cfl),
      real("time.force_cfl", "Force factor", "λ_f", "-", 0.01, 0.25,
           "Δt ≤ λ_f·√(h / |a|max). 0.25 is the stability limit (`scour stress`, cfl-limit).",
           &P::force_cfl),
      real("time.density_cfl", "Density factor", "λ_ρ", "-", 0.001, 0.2,
           "Δt ≤ λ_ρ / max |dρ/dt|/ρ: the largest relative density change in a step. Keeps "
           "splashes that collide from a one-step pressure spike (`scour stress`).",
           &P::density_cfl),
      slider(real("time.fixed_dt", "Fixed time step", "Δt", "s", 0.0, 0.01,
                  "If > 0, use this fixed step instead of the adaptive one.", &P::fixed_dt),
             1e-06, 0.01),
      real("time.velocity_cfl", "Velocity CFL (DFSPH)", "λ_v", "-", 0.01, 1.0,
           "DFSPH: Δt ≤ λ_v·h / |v|max; a particle moves at most λ_v h in a step.",
           &P::velocity_cfl),
      real("time.implicit_max_dt", "Maximum time step (DFSPH)", "Δt", "s", 1e-7, 0.05,
           "DFSPH: upper bound on the adaptive time step (WCSPH's is time.max_dt).",
           &P::implicit_max_dt),
      slider(real("boundary.penalty_stiffness", "Penalty stiffness", "K_S", "1/s²", 0.0, 1e12,
                  "Eq. (6) spring constant per unit mass; 0 derives it from the water depth.",
                  &P::penalty_stiffness),
             1000.0, 1e9),
      slider(real("boundary.penalty_damping", "Penalty damping", "K_D", "1/s", 0.0, 1e8,
                  "Eq. (6) damping per unit mass; 0 = critical damping.", &P::penalty_damping),
             0.1, 100000),
      real("boundary.contact_over_spacing", "Contact distance / spacing", "", "-", 0.0, 2.0,
           "Distance from terrain and walls within which eq. (6) acts, in Δs.",
           &P::contact_over_spacing),
      slider(real("boundary.friction", "No-slip friction", "μ_b", "m³/s", 0.0, 1e3,
                  "Eq. (8) friction constant over boundary particles.", &P::boundary_friction),
             1e-06, 1.0),
      slider(real("erosion.k_eps", "Erosion strength", "Kε", "kg/(m²·s·Pa)", 0.0, 1e4,
                  "Partheniades erosion rate per unit excess shear stress.", &P::k_eps),
             0.0001, 10.0),
      slider(real("erosion.tau_c", "Critical shear stress", "τc", "Pa", 0.0, 1e6,
                  "Shear stress below which the soil does not erode.", &P::tau_c),
             0.0001, 100.0),
      slider(real("erosion.shear_k", "Shear constant", "K", "Pa·sⁿ", 0.0, 1e6,
                  "K in the power law τ = K θⁿ.", &P::shear_k),
             0.001, 1000.0),
      real("erosion.shear_n", "Flow behaviour index", "n", "-", 0.05, 2.0,
           "n in the power law τ = K θⁿ (paper: 0.5, shear thinning).", &P::shear_n),
      slider(real("sediment.diffusion", "Sediment diffusivity", "D", "m²/s", 0.0, 10.0,
                  "Kinematic diffusivity of suspended sediment (paper: 0.1).", &P::diffusion),
             1e-06, 1.0),
      slider(
          real("sediment.grain_radius", "Grain radius", "r_s", "m", 1e-6, 0.1,
               "Radius of a sediment grain in the settling velocity, eq. (17).", &P::grain_radius),
          1e-06, 0.01),
      slider(real("sediment.density", "Sediment density", "ρs", "kg/m³", 1.0, 1e5,
                  "Density of the soil and of suspended sediment.", &P::sediment_density),
             500.0, 1e4),
      slider(real("erosion.morphological_factor", "Geologic speed-up", "N", "-", 1.0, 1e6,
                  "The bed changes N times as fast as the water's exchange (morphological "
                  "acceleration, Delft3D's MorFac): bed time = N × water time.",
                  &P::morphological_factor),
             1.0, 1e4),
      slider(real("erosion.morphological_spinup", "Speed-up spin-up", "", "s", 0.0, 1e6,
                  "Water time before the geologic speed-up acts, while the flow settles.",
                  &P::morphological_spinup),
             0.0, 1.0),
      slider(real("erosion.max_bed_step", "Bed-change guard", "", "Δs", 1e-6, 1.0,
                  "The most the bed may move in one step; a faster bed halves the speed-up "
                  "until it holds.",
                  &P::max_bed_step),
             1e-4, 0.1),
      slider(integer("erosion.exchange_every", "Bed work every", "K", "steps", 1.0, 1000.0,
                     "The sediment exchange, erosion and the terrain's update run every K-th "
                     "step over the K steps' time: K times less bed work for a coarser clock "
                     "(1: every step).",
                     &P::exchange_every),
             1.0, 16.0),
      real("sediment.c_max", "Maximum concentration", "Cmax", "-", 0.01, 1.0,
           "Largest solid volume fraction a fluid particle can carry.", &P::c_max),
      real("sediment.rz_exponent", "Richardson–Zaki exponent", "e", "-", 1.0, 10.0,
           "Exponent of the hindered settling f(C) = 1 − (C/Cmax)^e (4 < e < 5.5).",
           &P::rz_exponent),
      slider(real("sediment.settling_viscosity", "Settling viscosity", "μ", "Pa·s", 1e-6, 1e3,
                  "μ of eq. (17); the default gives v_s ≈ 0.1 m/s for 1 mm grains.",
                  &P::settling_viscosity),
             1e-05, 10.0),
      choice<&P::advection>(
          "sediment.advection", "Settling advection",
          "donor_acceptor: eq. (16) as pairwise volume fluxes (conservative); naive_gradient: "
          "−v_s·∇C per particle with the symmetric SPH gradient (leaks; study baseline).",
          kAdvectionChoices),
      choice<&P::diffusion_form>(
          "sediment.diffusion_form", "Diffusion form",
          "consistent: Σ V 2D (C_i − C_j) F/|r| (model.md); printed: eq. (19) as printed, "
          "Σ m/(ρ_i ρ_j) D (C_i − C_j) F.",
          kDiffusionFormChoices),
      slider(integer("engine.reorder_every", "Reorder interval", "", "steps", 1.0, 1e6,
                     "Steps between Z-order reorders of the particle arrays.", &P::reorder_every),
             1.0, 1000.0),
      choice<&P::neighbor_search>(
          "engine.neighbor_search", "Neighbor search",
          "grid: uniform cells of edge h; kd_tree: nanoflann kd-tree rebuilt every step (the "
          "paper's). Same neighbor sets.",
          kNeighborChoices),
      choice<&P::boundary_sampling>(
          "engine.boundary_sampling", "Boundary sampling",
          "spacing (default): about one boundary particle per Δs² on a terrain finer than Δs, each for "
          "a block of cells (model.md); triangles: n² per terrain triangle, at least one.",
          kSamplingChoices),
      slider(real("engine.max_penetration_over_ds", "Penetration limit", "", "Δs", 0.0, 100.0,
                  "A particle deeper than this below the terrain stops the run.",
                  &P::max_penetration_over_ds),
             0.05, 10.0),
  };
}

std::string formatRange(const ParamInfo& i) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "[%g, %g]", i.min, i.max);
  return buf;
}

}  // namespace

size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

SliderSpan sliderSpan(const ParamInfo& i) {
  const bool own = i.slider_min < i.slider_max;
  const double lo = own ? i.slider_min : i.min, hi = own ? i.slider_max : i.max;
  return {lo, hi, lo > 0 && hi / lo >= 100};
}

std::string nearestName(std::string_view word, const std::vector<std::string>& names,
                        size_t maxDistance) {
  std::string best;
  size_t bestD = SIZE_MAX;
  for (const std::string& n : names)
    if (const size_t d = editDistance(word, n); d < bestD) bestD = d, best = n;
  return bestD <= maxDistance ? best : "";
}

const std::vector<ParamInfo>& paramTable() {
  static const std::vector<ParamInfo> table = makeTable();
  return table;
}

const ParamInfo* findParam(std::string_view key) {
  for (const auto& i : paramTable())
    if (key == i.key) return &i;
  return nullptr;
}

std::string nearestParamKey(std::string_view key) {
  std::string best;
  size_t bestD = SIZE_MAX;
  for (const auto& i : paramTable()) {
    // Compare against the full key and against its last component, so "k_eps" finds
    // "erosion.k_eps".
    std::string_view full = i.key;
    std::string_view tail = full.substr(full.find('.') + 1);
    size_t d = std::min(editDistance(key, full), editDistance(key, tail));
    if (d < bestD) bestD = d, best = i.key;
  }
  return best;
}

double SimParams::particleMass() const {
  const double h = support();
  const Poly6 w(h);
  const int K = int(std::ceil(h / spacing));
  double sum = 0;
  for (int c = -K; c <= K; ++c)
    for (int b = -K; b <= K; ++b)
      for (int a = -K; a <= K; ++a) sum += w(float(spacing * spacing * (a * a + b * b + c * c)));
  return rest_density / sum;
}

double SimParams::particleVolume() const {
  return particleMass() / rest_density;
}

double getParam(const SimParams& p, const ParamInfo& info) {
  if (info.getChoice) return double(info.getChoice(p));
  return info.dmember ? p.*info.dmember : double(p.*info.imember);
}

std::string setParam(SimParams& p, std::string_view key, std::string_view value) {
  const ParamInfo* info = findParam(key);
  if (!info) {
    return "unknown parameter '" + std::string(key) + "' (did you mean '" + nearestParamKey(key) +
           "'?)";
  }
  std::string text(value);
  double v = 0.0;
  bool parsed = false;
  if (info->choices) {
    for (int k = 0; info->choices[k]; ++k)
      if (text == info->choices[k]) v = k, parsed = true;
    if (!parsed) {
      std::string names;
      for (int k = 0; info->choices[k]; ++k)
        names += (k ? ", " : "") + std::string(info->choices[k]);
      return "parameter '" + std::string(key) + "': expected one of " + names + ", found '" + text +
             "'";
    }
  } else {
    char* end = nullptr;
    v = std::strtod(text.c_str(), &end);
    parsed = !text.empty() && end == text.c_str() + text.size();
    if (!parsed)
      return "parameter '" + std::string(key) + "': expected a number, found '" + text + "'";
  }
  if (!std::isfinite(v)) return "parameter '" + std::string(key) + "': value must be finite";
  if (v < info->min || v > info->max) {
    return "parameter '" + std::string(key) + "': " + text + " is outside the valid range " +
           formatRange(*info);
  }
  if (info->dmember) {
    p.*info->dmember = v;
  } else {
    if (v != std::floor(v)) return "parameter '" + std::string(key) + "': expected an integer";
    if (info->setChoice)
      info->setChoice(p, int(v));
    else
      p.*info->imember = int(v);
  }
  return {};
}

std::string validateParams(const SimParams& p) {
  for (const auto& i : paramTable()) {
    double v = getParam(p, i);
    if (!std::isfinite(v)) return "parameter '" + std::string(i.key) + "' is not finite";
    if (v < i.min || v > i.max) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%g", v);
      return "parameter '" + std::string(i.key) + "': " + buf + " is outside the valid range " +
             formatRange(i);
    }
  }
  return {};
}

}  // namespace scour
