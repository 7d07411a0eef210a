#include "engine/sediment.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <omp.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "engine/parallel.h"

namespace scour {

SedimentConstants::SedimentConstants(const SimParams& p)
    : volume(p.particleVolume()),
      per_area(1.0 / (p.spacing * p.spacing)),
      c_max(p.c_max),
      rz(p.rz_exponent),
      vs0(p.settlingSpeed()),
      diffusion(p.diffusion),
      k_eps(p.k_eps),
      tau_c(p.tau_c),
      shear_k(p.shear_k),
      shear_n(p.shear_n),
      rho_s(p.sediment_density),
      mass(p.particleMass()),
      advection(p.advection),
      diffusion_form(p.diffusion_form),
      min_distance(0.1 * p.support()),
      spline(p.support()) {
  hindranceTable.resize(4097);
  for (size_t t = 0; t < hindranceTable.size(); ++t)
    hindranceTable[t] = float(hindrance(c_max * double(t) / 4096.0));
}

float SedimentConstants::hindranceFast(double c) const {
  const double u = std::max(c, 0.0) / c_max * 4096.0;
  if (u >= 4096.0) return 0.0f;
  const size_t i = size_t(u);
  const float w = float(u - double(i));
  return hindranceTable[i] + w * (hindranceTable[i + 1] - hindranceTable[i]);
}

double SedimentConstants::hindrance(double c) const {
  if (c >= c_max) return 0.0;
  return 1.0 - std::pow(std::max(c, 0.0) / c_max, rz);
}

namespace {

// The geometry of a pair, computed once per pair and pass from operands both particles see
// identically (|dy| and r), so the two sides of a pair agree to the bit. Float: the fluxes need
// no more, and the budget stays exact because both sides use the same float values (the sums are
// double).
struct PairGeometry {
  float settle = 0;   // 2 V² |v_s| (|dy|/r) |F(r)|: eq. (16) doubled, without C and f(C)
  float diffuse = 0;  // 2 D V² |F(r)| / r: model.md's eq. (19), without the C difference
};

struct PairFlux {
  float kSettle, kDiffuse, kPrinted, invHm, fCoef;
  PairFlux(const SedimentConstants& k, bool settle, bool diffuse, bool printed)
      : kSettle(settle ? float(2.0 * k.volume * k.volume * std::abs(k.vs0)) : 0.0f),
        kDiffuse(diffuse ? float(2.0 * k.diffusion * k.volume * k.volume) : 0.0f),
        kPrinted(printed ? float(k.volume * k.mass * k.diffusion) : 0.0f),
        invHm(float(1.0 / k.spline.hm)),
        fCoef(float(k.spline.sigma / k.spline.hm)) {}
  // |F(r)| of the cubic spline (support 2 h_M = h).
  float absF(float r) const {
    const float q = r * invHm;
    if (q >= 2.0f) return 0.0f;
    if (q < 1.0f) return fCoef * (3.0f * q - 2.25f * q * q);
    const float t = 2.0f - q;
    return fCoef * 0.75f * t * t;
  }
  /// |F(r)| / r, 0 for coincident particles: absF(r) / r to the bit, every piece of the spline
  /// computed and one chosen (no branch to mispredict).
  float ratio(float r) const {
    const float q = r * invHm, t = 2.0f - q;
    const float inner = fCoef * (3.0f * q - 2.25f * q * q), outer = fCoef * 0.75f * t * t;
    const float f = q < 1.0f ? inner : (q < 2.0f ? outer : 0.0f);
    return r > 0.0f ? f / (r > 0.0f ? r : 1.0f) : 0.0f;
  }
  PairGeometry geometry(float absDy, float fr) const { return {kSettle * absDy * fr, kDiffuse * fr}; }
  // Eq. (19) as printed, as a volume flux: V m/(ρ_i ρ_j) D |F(r)| (symmetric in i and j, so both
  // sides of a pair compute the same bits).
  float printedDiffusion(float r, float rhoI, float rhoJ) const {
    return kPrinted * absF(r) / (rhoI * rhoJ);
  }
  // Volume flux [m³/s] from donor d to acceptor a; `below` says a lies below d (dy > 0), fa is
  // the acceptor's hindrance f(C_a) (eq. 17: C taken at the acceptor).
  static double flux(const PairGeometry& g, float cd, float ca, float fa, bool below) {
    float v = below ? g.settle * cd * fa : 0.0f;
    if (cd > ca) v += g.diffuse * (cd - ca);
    return double(v);
  }
};

// The fluid–fluid exchange of particle i for the default forms (donor–acceptor settling and
// the consistent diffusion): the general loop's arithmetic, operand for operand, so the same bits,
// with its data-dependent choices made by selects (which way the pair settles, whether C falls
// across it, which piece of the spline) rather than branches, which mispredicted on about half the
// pairs. A pair with no sediment on either side adds exact zeros.
template <bool Scaled>
void exchangePlain(const PairFlux& pair, const NeighborLists& nbrs, const std::vector<Vec3f>& x,
                   const std::vector<float>& conc, const std::vector<float>& hind,
                   const std::vector<SedimentWorkspace::Scales>& scale, bool rising, double dt,
                   size_t i, double& d, double& in, double& out, uint32_t first = 0) {
  const uint32_t* js = nbrs.begin(i);
  const uint32_t count = nbrs.count(i);
  const Vec3f xi = x[i];
  const float ci = conc[i], hi = hind[i];
  // dy > 0: i above j. Settling goes down (up when rising): the acceptor is the lower one.
  const float down = rising ? -1.0f : 1.0f;
  // The sums in registers (through the references, each pair's adds waited on a store), added to
  // the callers' in the same order.
  double dSum = d, inSum = in, outSum = out;
  for (uint32_t c = first; c < count; ++c) {
    const uint32_t j = js[c];
    const float cj = conc[j];
    const Vec3f xij = xi - x[j];
    const float dy = xij.y();
    const float fr = pair.ratio(xij.norm());
    const PairGeometry g = pair.geometry(std::abs(dy), fr);
    // Which side settles, as 0 or 1 (times a finite non-negative rate: the select's bits), and the
    // fall of C across the pair as max(·, 0).
    const float iDownstream = float(down * dy < 0.0f), jDownstream = float(down * dy > 0.0f);
    const float gainRate = g.settle * cj * hi * iDownstream + g.diffuse * std::max(cj - ci, 0.0f);
    const float lossRate = g.settle * ci * hind[j] * jDownstream + g.diffuse * std::max(ci - cj, 0.0f);
    const double gain = double(gainRate) * dt, loss = double(lossRate) * dt;
    if constexpr (Scaled) {
      dSum += gain * std::min(scale[j].out, scale[i].in);
      dSum -= loss * std::min(scale[i].out, scale[j].in);
    } else {
      dSum += gain;
      dSum -= loss;
    }
    inSum += gain;
    outSum += loss;
  }
  d = dSum, in = inSum, out = outSum;
}

#if defined(__SSE2__)
// exchangePlain<false> four pairs at a time: the same float operations, operand for operand and
// in the same order, on four lanes (SSE's arithmetic is IEEE's, lane by lane, and no FMA is
// contracted at this target), then each pair's double adds in list order, so the same bits as the
// scalar loop, which takes the last count % 4 pairs.
void exchangePlainSse(const PairFlux& pair, const NeighborLists& nbrs, const std::vector<Vec3f>& x,
                      const std::vector<float>& conc, const std::vector<float>& hind, bool rising,
                      double dt, size_t i, double& d, double& in, double& out) {
  const uint32_t* js = nbrs.begin(i);
  const uint32_t count = nbrs.count(i);
  const Vec3f xi = x[i];
  const float ci = conc[i], hi = hind[i];
  const __m128 xix = _mm_set1_ps(xi.x()), xiy = _mm_set1_ps(xi.y()), xiz = _mm_set1_ps(xi.z());
  const __m128 cI = _mm_set1_ps(ci), hI = _mm_set1_ps(hi), down = _mm_set1_ps(rising ? -1.0f : 1.0f);
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), two = _mm_set1_ps(2.0f);
  const __m128 invHm = _mm_set1_ps(pair.invHm), fCoef = _mm_set1_ps(pair.fCoef);
  const __m128 fOuter = _mm_set1_ps(pair.fCoef * 0.75f);
  const __m128 three = _mm_set1_ps(3.0f), quad = _mm_set1_ps(2.25f);
  const __m128 kSettle = _mm_set1_ps(pair.kSettle), kDiffuse = _mm_set1_ps(pair.kDiffuse);
  const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128d dtv = _mm_set1_pd(dt);
  double dSum = d, inSum = in, outSum = out;
  uint32_t c = 0;
  for (; c + 4 <= count; c += 4) {
    const Vec3f &x0 = x[js[c]], &x1 = x[js[c + 1]], &x2 = x[js[c + 2]], &x3 = x[js[c + 3]];
    const __m128 dx = _mm_sub_ps(xix, _mm_setr_ps(x0.x(), x1.x(), x2.x(), x3.x()));
    const __m128 dy = _mm_sub_ps(xiy, _mm_setr_ps(x0.y(), x1.y(), x2.y(), x3.y()));
    const __m128 dz = _mm_sub_ps(xiz, _mm_setr_ps(x0.z(), x1.z(), x2.z(), x3.z()));
    const __m128 cJ = _mm_setr_ps(conc[js[c]], conc[js[c + 1]], conc[js[c + 2]], conc[js[c + 3]]);
    const __m128 hJ = _mm_setr_ps(hind[js[c]], hind[js[c + 1]], hind[js[c + 2]], hind[js[c + 3]]);
    // r as Eigen's norm: sqrt(x² + (y² + z²)).
    const __m128 r = _mm_sqrt_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_add_ps(_mm_mul_ps(dy, dy), _mm_mul_ps(dz, dz))));
    // PairFlux::ratio.
    const __m128 q = _mm_mul_ps(r, invHm), t = _mm_sub_ps(two, q);
    const __m128 inner = _mm_mul_ps(fCoef, _mm_sub_ps(_mm_mul_ps(three, q), _mm_mul_ps(_mm_mul_ps(quad, q), q)));
    const __m128 outer = _mm_mul_ps(_mm_mul_ps(fOuter, t), t);
    const __m128 isInner = _mm_cmplt_ps(q, one), isOuter = _mm_andnot_ps(isInner, _mm_cmplt_ps(q, two));
    const __m128 f = _mm_or_ps(_mm_and_ps(isInner, inner), _mm_and_ps(isOuter, outer));
    const __m128 apart = _mm_cmpgt_ps(r, zero);
    const __m128 denom = _mm_or_ps(_mm_and_ps(apart, r), _mm_andnot_ps(apart, one));
    const __m128 fr = _mm_and_ps(apart, _mm_div_ps(f, denom));
    // PairFlux::geometry, then exchangePlain's rates.
    const __m128 settle = _mm_mul_ps(_mm_mul_ps(kSettle, _mm_and_ps(dy, absMask)), fr);
    const __m128 diffuse = _mm_mul_ps(kDiffuse, fr);
    const __m128 along = _mm_mul_ps(down, dy);
    const __m128 iDown = _mm_and_ps(_mm_cmplt_ps(along, zero), one);
    const __m128 jDown = _mm_and_ps(_mm_cmpgt_ps(along, zero), one);
    const __m128 gainRate = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_mul_ps(settle, cJ), hI), iDown),
                                       _mm_mul_ps(diffuse, _mm_max_ps(zero, _mm_sub_ps(cJ, cI))));
    const __m128 lossRate = _mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_mul_ps(settle, cI), hJ), jDown),
                                       _mm_mul_ps(diffuse, _mm_max_ps(zero, _mm_sub_ps(cI, cJ))));
    alignas(16) double gain[4], loss[4];
    _mm_store_pd(gain, _mm_mul_pd(_mm_cvtps_pd(gainRate), dtv));
    _mm_store_pd(gain + 2, _mm_mul_pd(_mm_cvtps_pd(_mm_movehl_ps(gainRate, gainRate)), dtv));
    _mm_store_pd(loss, _mm_mul_pd(_mm_cvtps_pd(lossRate), dtv));
    _mm_store_pd(loss + 2, _mm_mul_pd(_mm_cvtps_pd(_mm_movehl_ps(lossRate, lossRate)), dtv));
    for (int l = 0; l < 4; ++l) {
      dSum += gain[l];
      dSum -= loss[l];
      inSum += gain[l];
      outSum += loss[l];
    }
  }
  d = dSum, in = inSum, out = outSum;
  if (c < count) exchangePlain<false>(pair, nbrs, x, conc, hind, {}, rising, dt, i, d, in, out, c);
}
#endif

// Eq. (20) with the doubled eq. (16) flux over one fluid particle's boundary pairs: a donor fluid
// particle above a boundary particle (which holds no sediment, f = 1) gives it
// 2 V² C_d v_s (dy/r) |F(r)| Δt · L_b²/Δs², passed to `add(bj, v)` in list order for v > 0 only.
// Two pairs at a time (SSE2's double arithmetic is IEEE's, lane by lane), the rest one by one
// with the same operations in the same order, so the result does not depend on where a pair sits.
struct Deposition {
  double twoVV, vs0, hm, inner, outer, dt, perArea;
  Deposition(const SedimentConstants& k, double dt)
      : twoVV(2.0 * k.volume * k.volume),
        vs0(k.vs0),
        hm(k.spline.hm),
        inner(k.spline.sigma / k.spline.hm),
        outer(-k.spline.sigma / k.spline.hm * 0.75),
        dt(dt),
        perArea(k.per_area) {}
  template <class Add>
  void pairs(const NeighborLists& bnbrs, const Vec3f& xi, const BoundaryParticles& b, size_t i, double cd,
             Add&& add) const {
    // Grains lighter than water rise (v_s < 0): they never reach the bed below.
    if (cd <= 0.0 || vs0 <= 0.0) return;
    const uint32_t* js = bnbrs.begin(i);
    const uint32_t count = bnbrs.count(i);
    const double P = twoVV * cd * vs0;
    uint32_t c = 0;
#if defined(__SSE2__)
    const __m128d vP = _mm_set1_pd(P), vHm = _mm_set1_pd(hm), vInner = _mm_set1_pd(inner);
    const __m128d vOuter = _mm_set1_pd(outer), vDt = _mm_set1_pd(dt), vPerArea = _mm_set1_pd(perArea);
    const __m128d zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0), two = _mm_set1_pd(2.0);
    const __m128d minusThree = _mm_set1_pd(-3.0), quad = _mm_set1_pd(2.25), sign = _mm_set1_pd(-0.0);
    for (; c + 2 <= count; c += 2) {
      const uint32_t j0 = js[c], j1 = js[c + 1];
      const Vec3f x0 = xi - b.x[j0], x1 = xi - b.x[j1];
      const __m128d r = _mm_setr_pd(double(x0.norm()), double(x1.norm()));
      const __m128d dy = _mm_setr_pd(double(x0.y()), double(x1.y()));
      const __m128d q = _mm_div_pd(r, vHm), t = _mm_sub_pd(two, q);
      const __m128d in = _mm_mul_pd(vInner, _mm_add_pd(_mm_mul_pd(minusThree, q), _mm_mul_pd(_mm_mul_pd(quad, q), q)));
      const __m128d out = _mm_mul_pd(_mm_mul_pd(vOuter, t), t);
      const __m128d isInner = _mm_cmplt_pd(q, one), isOuter = _mm_andnot_pd(isInner, _mm_cmplt_pd(q, two));
      const __m128d F = _mm_or_pd(_mm_and_pd(isInner, in), _mm_and_pd(isOuter, out));
      const __m128d flux = _mm_mul_pd(_mm_mul_pd(vP, _mm_div_pd(dy, r)), _mm_xor_pd(F, sign));
      const __m128d area = _mm_mul_pd(_mm_setr_pd(b.area[j0], b.area[j1]), vPerArea);
      const __m128d valid = _mm_and_pd(_mm_cmpgt_pd(r, zero), _mm_cmpgt_pd(dy, zero));
      alignas(16) double v[2];
      _mm_store_pd(v, _mm_and_pd(valid, _mm_mul_pd(_mm_mul_pd(flux, vDt), area)));
      if (v[0] > 0.0) add(j0, v[0]);
      if (v[1] > 0.0) add(j1, v[1]);
    }
#endif
    for (; c < count; ++c) {
      const uint32_t j = js[c];
      const Vec3f xib = xi - b.x[j];
      const double r = double(xib.norm()), dy = double(xib.y());
      if (r <= 0.0 || dy <= 0.0) continue;
      const double q = r / hm;
      const double F = q >= 2.0 ? 0.0 : (q < 1.0 ? inner * (-3.0 * q + 2.25 * q * q) : outer * (2.0 - q) * (2.0 - q));
      const double v = P * (dy / r) * (-F) * dt * (b.area[j] * perArea);
      if (v > 0.0) add(j, v);
    }
  }
};

// Per-thread lists of (boundary particle, volume) for contiguous particle blocks; replayed in
// thread order they are in particle order, whatever the thread count. Each volume goes to its
// boundary particle's sum, which the terrain pass spreads over the triangles it stands for.
using BoundaryVolumes = std::vector<std::vector<std::pair<uint32_t, double>>>;

void replay(const BoundaryVolumes& lists, const BoundaryParticles& b, TerrainAccumulator& acc) {
  if (acc.particle.size() < b.size()) acc.particle.resize(b.size(), 0.0), acc.particleListed.resize(b.size(), 0);
  for (const auto& l : lists)
    for (auto [j, v] : l) acc.addParticle(j, v);
}

}  // namespace

void transferSediment(const SedimentConstants& k, const SedimentEffects& fx,
                      const NeighborLists& nbrs, const NeighborLists& bnbrs,
                      const BoundaryParticles& b, double dt, Fluid& f, TerrainAccumulator& acc,
                      SedimentWorkspace& ws) {
  const size_t n = f.size();
  const double V = k.volume, room = k.c_max * V;
  const bool naive = fx.settling && k.advection == SettlingAdvection::kNaiveGradient;
  const bool printed = fx.diffusion && k.diffusion_form == DiffusionForm::kPrinted;
  // v_s < 0 (ρs < ρ0): the donor–acceptor flux runs upwards at |v_s| (model.md).
  const bool rising = k.vs0 < 0.0;
  const PairFlux pair(k, fx.settling && !naive, fx.diffusion && !printed, printed);
  // Neither study option: the fluid pairs go through exchangePlain.
  const bool plain = !naive && !printed;
  // Naive advection: ds_i = V Δt v_s0 f(C_i) ∂C/∂y, ∂C/∂y = Σ_j V (C_j − C_i) F dy/r (F = −|F|).
  const double naiveCoef = naive ? V * V * k.vs0 : 0.0;
  const bool deposit = fx.deposition && bnbrs.size() == n;
  const Deposition depositing(k, dt);
  std::vector<float>& conc = ws.conc;
  std::vector<float>& hind = ws.hind;
  std::vector<SedimentWorkspace::Scales>& scale = ws.scale;
  std::vector<double>& delta = ws.delta;
  resizeForParticles(conc, n);
  resizeForParticles(hind, n);
  resizeForParticles(scale, n);
  resizeForParticles(delta, n);
  // (delta needs no clearing: the exchange writes every particle's.)
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) {
    conc[i] = float(f.sed[i] / V);
    hind[i] = k.hindranceFast(f.sed[i] / V);
    scale[i] = SedimentWorkspace::Scales{};
  }

  // One exchange pass over all pairs. Unscaled (every factor 1), it also sums each particle's
  // outflow and inflow over Δt; those give the factors that keep every donor from giving more
  // than it holds and every acceptor from passing C_max. Only when some factor is below 1 (rare:
  // a nearly empty donor or a nearly saturated acceptor) does the scaled pass run again; the
  // unscaled pass then equals it to the bit, so the result does not depend on which ran.
  BoundaryVolumes& deposits = ws.exchanges;
  bool limited = false;
  auto exchange = [&](bool scaled) {
#pragma omp parallel reduction(|| : limited)
    {
      const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
      deposits.resize(size_t(threads));
      // The thread's list kept on its own stack while it fills it: the lists' headers share a cache
      // line, and each thread writing its own end pointer there bounced the line between cores.
      auto mine = std::move(deposits[size_t(t)]);
      mine.clear();
      const size_t lo = blockBegin(n, size_t(threads), size_t(t));
      const size_t hi = blockBegin(n, size_t(threads), size_t(t) + 1);
      for (size_t i = lo; i < hi; ++i) {
        const float ci = conc[i];
        double d = 0.0, out = 0.0, in = 0.0, grad = 0.0;
        const uint32_t* js = nbrs.begin(i);
        if (plain && scaled)
          exchangePlain<true>(pair, nbrs, f.x, conc, hind, scale, rising, dt, i, d, in, out);
        else if (plain)
#if defined(__SSE2__)
          exchangePlainSse(pair, nbrs, f.x, conc, hind, rising, dt, i, d, in, out);
#else
          exchangePlain<false>(pair, nbrs, f.x, conc, hind, scale, rising, dt, i, d, in, out);
#endif
        else
          for (uint32_t c = 0; c < nbrs.count(i); ++c) {
            const uint32_t j = js[c];
            const float cj = conc[j];
            if (ci == 0.0f && cj == 0.0f) continue;
            const float dy = f.x[i].y() - f.x[j].y();
            // |F(r)|/r: the same bits in the unscaled and the scaled pass.
            const float fr = pair.ratio((f.x[i] - f.x[j]).norm());
            PairGeometry g = pair.geometry(std::abs(dy), fr);
            if (printed) g.diffuse = pair.printedDiffusion((f.x[i] - f.x[j]).norm(), f.rho[i], f.rho[j]);
            // The symmetric-difference gradient Σ_j V (C_j − C_i) ∇W_ij, y component over −V.
            if (naive) grad += double(cj - ci) * double(fr) * double(dy);
            // Settling carries sediment down the pair (up, for grains lighter than water).
            const bool iDownstream = rising ? dy > 0.0f : dy < 0.0f;
            const bool jDownstream = rising ? dy < 0.0f : dy > 0.0f;
            const double gain = PairFlux::flux(g, cj, ci, hind[i], iDownstream) * dt;
            const double loss = PairFlux::flux(g, ci, cj, hind[j], jDownstream) * dt;
            // Unscaled, the factors are being written by other threads: read none of them.
            d += scaled ? gain * std::min(scale[j].out, scale[i].in) : gain;
            d -= scaled ? loss * std::min(scale[i].out, scale[j].in) : loss;
            in += gain;
            out += loss;
          }
        // −v_s·∇C as a rate of C_i (the study's naive baseline): not a pairwise flux.
        if (naive) d -= naiveCoef * double(hind[i]) * grad * dt;
        if (deposit && ci > 0.0f) {
          // Weighed by L_b²/Δs² (model.md): deposition per area, however finely sampled.
          const double keep = scaled ? scale[i].out : 1.0;
          depositing.pairs(bnbrs, f.x[i], b, i, f.sed[i] / V, [&](uint32_t bj, double v) {
            const double given = scaled ? v * keep : v;
            d -= given;
            out += v;
            mine.emplace_back(bj, given);
          });
        }
        delta[i] = d;
        if (scaled) continue;
        if (out > f.sed[i]) scale[i].out = f.sed[i] / out, limited = true;
        const double space = std::max(room - f.sed[i], 0.0);
        if (in > space) scale[i].in = space / in, limited = true;
      }
      deposits[size_t(t)] = std::move(mine);
    }
  };
  exchange(false);
  if (limited) exchange(true);
  replay(deposits, b, acc);
  ws.defects = {};
  if (naive) {
    // The naive rate leaks: count what the step made (suspended change + deposits) and what the
    // clamp into [0, C_max] added, serially in particle order so the sums are thread-independent.
    SedimentDefects& def = ws.defects;
    def.c_min_raw = n ? (f.sed[0] + delta[0]) / V : 0.0;
    def.c_max_raw = def.c_min_raw;
    for (size_t i = 0; i < n; ++i) {
      const double raw = f.sed[i] + delta[i], now = std::clamp(raw, 0.0, room);
      def.c_min_raw = std::min(def.c_min_raw, raw / V);
      def.c_max_raw = std::max(def.c_max_raw, raw / V);
      def.clipped += now - raw;
      def.created += now - f.sed[i];
      f.sed[i] = now;
    }
    for (const auto& l : deposits)
      for (const auto& tv : l) def.created += tv.second;
    return;
  }
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (size_t i = 0; i < n; ++i) f.sed[i] = std::clamp(f.sed[i] + delta[i], 0.0, room);
}

namespace {
// Eq. (9): τ = K θⁿ, θ = v_rel / l, l clamped below at the constants' minimum distance [Pa].
double pairShear(const SedimentConstants& k, double speed, double l) {
  const double theta = speed / std::max(l, k.min_distance);
  return k.shear_k * (k.shear_n == 0.5 ? std::sqrt(theta) : std::pow(theta, k.shear_n));
}
}  // namespace

void bedShear(const SedimentConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
              const Fluid& f, std::vector<float>& tau) {
  const size_t n = f.size();
  resizeForParticles(tau, n);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) {
    double peak = -1.0;
    const double speed = double(f.v[i].norm());
    forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t, const Vec3f&, float r) {
      peak = std::max(peak, pairShear(k, speed, double(r)));
    });
    tau[i] = float(peak);
  }
}

void erode(const SedimentConstants& k, const NeighborLists& bnbrs, const BoundaryParticles& b,
           double dt, Fluid& f, TerrainAccumulator& acc, SedimentWorkspace& ws) {
  const size_t n = f.size();
  const double room = k.c_max * k.volume;
  BoundaryVolumes& eroded = ws.exchanges;
  resizeForParticles(ws.tau, n);
  // τ ≤ τ_c for l ≥ |v| K² / τ_c² (τ = K √(|v| / l)); l_c lies a millionth farther, far beyond
  // the rounding of either side (with τ_c = 0 every pair is looked at).
  const bool sqrtLaw = k.shear_n == 0.5;
  const double erodingBelow = k.tau_c > 0 ? k.shear_k * k.shear_k / (k.tau_c * k.tau_c) * (1.0 + 1e-6) : INFINITY;
#pragma omp parallel
  {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
    eroded.resize(size_t(threads));
    auto mine = std::move(eroded[size_t(t)]);  // on the thread's stack, as transferSediment's
    mine.clear();
    const size_t lo = blockBegin(n, size_t(threads), size_t(t));
    const size_t hi = blockBegin(n, size_t(threads), size_t(t) + 1);
    for (size_t i = lo; i < hi; ++i) {
      ws.tau[i] = -1.0f;
      if (bnbrs.count(i) == 0) continue;
      const double speed = double(f.v[i].norm());
      const size_t first = mine.size();
      double total = 0.0, peak = -1.0;
      // Eq. (10): ε = K_ε (τ − τ_c) for τ > τ_c; the pair's volume L_b² ε Δt / ρ_s.
      auto pair = [&](uint32_t bj, double tau) {
        if (tau <= k.tau_c) return;
        const double v = b.area[bj] * k.k_eps * (tau - k.tau_c) * dt / k.rho_s;
        if (v <= 0.0) return;
        mine.emplace_back(bj, -v);
        total += v;
      };
      if (sqrtLaw) {
        // τ = K √(|v| / l) falls as l grows, and each of its operations is correctly rounded, so
        // is monotone: the peak is the nearest pair's τ, and a pair farther than l_c (where τ is
        // surely below τ_c, with a margin far above rounding) erodes nothing. Only the nearer
        // pairs take the division and the root: the same bits as computing every pair's τ.
        const double lc = speed * erodingBelow;
        double nearest = INFINITY;
        forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t bj, const Vec3f&, float r) {
          const double l = std::max(double(r), k.min_distance);
          nearest = std::min(nearest, l);
          if (l < lc) pair(bj, pairShear(k, speed, l));
        });
        peak = pairShear(k, speed, nearest);
      } else {
        forEachNeighbor(bnbrs, f.x, b.x, i, [&](uint32_t bj, const Vec3f&, float r) {
          const double tau = pairShear(k, speed, double(r));
          peak = std::max(peak, tau);
          pair(bj, tau);
        });
      }
      ws.tau[i] = float(peak);
      if (total <= 0.0) continue;
      // Model.md: C_j ≤ C_max. The particle gains exactly the sum the terrain loses.
      const double space = std::max(room - f.sed[i], 0.0);
      const double scale = total > space ? space / total : 1.0;
      double gained = 0.0;
      for (size_t e = first; e < mine.size(); ++e) {
        mine[e].second *= scale;
        gained -= mine[e].second;
      }
      f.sed[i] += gained;
    }
    eroded[size_t(t)] = std::move(mine);
  }
  replay(eroded, b, acc);
}

void TerrainAccumulator::growParticles(uint32_t j) {
  particle.resize(size_t(j) + 1, 0.0), particleListed.resize(size_t(j) + 1, 0);
}

std::vector<double> vertexAreas(const Heightfield& hf) {
  std::vector<double> a(hf.heights().size(), 0.0);
  const double third = hf.dx() * hf.dz() / 2.0 / 3.0;
  for (int t = 0; t < hf.triangleCount(); ++t)
    for (size_t v : hf.triangleVertexIndices(t)) a[v] += third;
  return a;
}

TerrainChange measureTerrainChange(const std::vector<double>& dh, const std::vector<double>& areas) {
  TerrainChange c;
  for (size_t v = 0; v < dh.size(); ++v) {
    c.max_erosion = std::max(c.max_erosion, -dh[v]), c.max_deposition = std::max(c.max_deposition, dh[v]);
    (dh[v] < 0 ? c.eroded : c.deposited) += std::abs(dh[v]) * areas[v];
  }
  return c;
}

double terrainVolume(const Heightfield& hf, const std::vector<double>& areas, double reference) {
  double v = 0.0;
  const auto& h = hf.heights();
  for (size_t i = 0; i < h.size(); ++i) v += (h[i] - reference) * areas[i];
  return v;
}

namespace {

// depositOnTriangle on the corners idx.
void depositOnCorners(std::vector<double>& h, const std::vector<double>& areas, std::array<size_t, 3> idx,
                      double volume) {
  const double sign = volume > 0 ? 1.0 : -1.0;
  double left = std::abs(volume);
  // Order from the lowest (deposit) or highest (erosion) vertex; ties by index, deterministically.
  auto before = [&](size_t p, size_t q) {
    const double hp = sign * h[p], hq = sign * h[q];
    return hp < hq || (hp == hq && p < q);
  };
  if (before(idx[1], idx[0])) std::swap(idx[0], idx[1]);
  if (before(idx[2], idx[1])) std::swap(idx[1], idx[2]);
  if (before(idx[1], idx[0])) std::swap(idx[0], idx[1]);
  // Work in "sign-flipped" heights g = sign·h so both cases fill the lowest first.
  double areaSum = 0.0;
  for (int level = 0; level < 3; ++level) {
    areaSum += areas[idx[level]];
    const double g = sign * h[idx[level]];
    const double next = level < 2 ? sign * h[idx[level + 1]] : INFINITY;
    const double cost = (next - g) * areaSum;
    if (left <= cost || level == 2) {
      const double rise = left / areaSum;
      for (int a = 0; a <= level; ++a) h[idx[a]] = sign * (g + rise);
      return;
    }
    left -= cost;
    for (int a = 0; a <= level; ++a) h[idx[a]] = sign * next;
  }
}

}  // namespace

void depositOnTriangle(Heightfield& hf, const std::vector<double>& areas, int tri, double volume) {
  if (volume == 0.0) return;
  depositOnCorners(hf.heights(), areas, hf.triangleVertexIndices(tri), volume);
}

std::vector<int> applyTerrainChange(Heightfield& hf, const std::vector<double>& areas,
                                    TerrainAccumulator& acc, double threshold) {
  const int cells = hf.nx() - 1, rows = hf.nz() - 1;
  if (acc.vertexMark.size() != hf.heights().size()) acc.vertexMark.assign(hf.heights().size(), 0u), acc.epoch = 0;
  if (++acc.epoch == 0) std::fill(acc.vertexMark.begin(), acc.vertexMark.end(), 0u), acc.epoch = 1;
  const uint32_t epoch = acc.epoch;
  // A triangle is applied once its volume would move it by `threshold` on average; a block's
  // bank once it would move the block so: it is split into its triangles, which apply this call.
  const double least = threshold * 0.5 * hf.dx() * hf.dz();
  acc.cellsX = cells;
  for (size_t e = 0, listed = acc.touched.size(); e < listed; ++e) {
    const int t = acc.touched[e];
    const uint8_t c = acc.code[size_t(t)];
    if (!TerrainAccumulator::isHead(c)) continue;
    const double v = acc.volume[size_t(t)];
    if (v != 0.0 && std::abs(v) >= least * 2.0 * double(c & 15) * double(c >> 4)) acc.split(t, TerrainAccumulator::kApplyNow);
  }
  // The touched triangles by cell row (a counting sort; each row's then sorted ascending), and
  // where each row's changed vertices and waiting triangles go (at most 3 and 1 for each of its
  // triangles). The work follows the touched triangles, not the rows' width.
  const int perRow = 2 * cells;
  std::vector<int>& start = acc.rowStart;
  std::vector<int>& byRow = acc.byRow;
  std::vector<int>& next = acc.rowNext;
  start.assign(size_t(rows) + 1, 0);
  for (int t : acc.touched) ++start[size_t(t / perRow) + 1];
  std::vector<int> live;
  for (int k = 0; k < rows; ++k) {
    if (start[size_t(k) + 1] > 0) live.push_back(k);
    start[size_t(k) + 1] += start[size_t(k)];
  }
  next.assign(start.begin(), start.end() - 1);
  byRow.resize(acc.touched.size());
  for (int t : acc.touched) byRow[size_t(next[size_t(t / perRow)]++)] = t;
  std::vector<int>& changedAt = acc.changedAt;
  std::vector<int>& waiting = acc.waiting;
  changedAt.assign(3 * acc.touched.size(), -1);
  waiting.assign(acc.touched.size(), -1);
  // A row's triangles in ascending order.
  auto applyRow = [&](int k) {
    int* out = changedAt.data() + 3 * size_t(start[size_t(k)]);
    int* wait = waiting.data() + size_t(start[size_t(k)]);
    std::vector<double>& h = hf.heights();
    int* const first = byRow.data() + start[size_t(k)];
    int* const last = byRow.data() + start[size_t(k) + 1];
    std::sort(first, last);
    for (const int* at = first; at != last; ++at) {
      const int t = *at;
      const double v = acc.volume[size_t(t)];
      uint8_t& c = acc.code[size_t(t)];
      // A bank left whole waits; the sums of a split bank apply whatever their size.
      if (v == 0.0 || TerrainAccumulator::isHead(c) || (c != TerrainAccumulator::kApplyNow && std::abs(v) < least)) {
        if (v != 0.0) *wait++ = t;
        else c = TerrainAccumulator::kNone;
        continue;
      }
      acc.volume[size_t(t)] = 0.0;
      c = TerrainAccumulator::kNone;
      const std::array<size_t, 3> idx = hf.triangleVertexIndices(t);
      const std::array<double, 3> was = {h[idx[0]], h[idx[1]], h[idx[2]]};
      depositOnCorners(h, areas, idx, v);
      for (int a = 0; a < 3; ++a)
        if (h[idx[a]] != was[a] && acc.vertexMark[idx[a]] != epoch)
          acc.vertexMark[idx[a]] = epoch, *out++ = int(idx[a]);
    }
  };
  // Rows k and k + 2 share no vertex: each round's rows run in parallel, a row on one thread.
  // A round of fewer touched triangles than kParallelFrom runs on this thread.
  for (int parity = 0; parity < 2; ++parity) {
    std::vector<int> round;
    size_t triangles = 0;
    for (int k : live)
      if (k % 2 == parity) round.push_back(k), triangles += size_t(start[size_t(k) + 1] - start[size_t(k)]);
    const long nr = long(round.size());
#pragma omp parallel for schedule(dynamic, 1) if (triangles >= kParallelFrom)
    for (long r = 0; r < nr; ++r) applyRow(round[size_t(r)]);
  }
  std::vector<int> moved;
  for (int v : changedAt)
    if (v >= 0) moved.push_back(v);
  // What waits, row by row in ascending order: the front of the next step's list.
  acc.touched.clear();
  for (int t : waiting)
    if (t >= 0) acc.touched.push_back(t);
  return moved;
}

}  // namespace scour
