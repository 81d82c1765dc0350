#include "structure/effects/ThreadedForces.hpp"

#include <algorithm>
#include <limits>

#ifdef FSI_HAVE_OPENMP
#include <omp.h>
#endif

#include "structure/effects/Threads.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

ThreadedForces::ThreadedForces(std::vector<const Effect*> effects, int threads, int nodes)
    : effects_(std::move(effects)), nodes_(nodes) {
  int largest = 0;
  for (const Effect* e : effects_) {
    (e->splitItems() > 0 ? split_ : whole_).push_back(e);
    largest = std::max(largest, e->splitItems());
  }
  if (threads <= 1 || !threadsAvailable() || largest < kMinParallelItems) return;
  shares_.resize(std::size_t(threads));
  for (int s = 0; s < threads; ++s) {
    Share& sh = shares_[std::size_t(s)];
    sh.nodeBegin = int(long(nodes) * s / threads);
    sh.nodeEnd = int(long(nodes) * (s + 1) / threads);
    int lo = std::numeric_limits<int>::max(), hi = 0;
    for (const Effect* e : split_) {
      // Equal element counts, boundaries on whole batches; the last share takes the remainder. Only share 0's
      // range starts at element 0 (Effect::addRange), even for fewer elements than shares.
      const int n = e->splitItems(), a = e->splitAlignment();
      auto boundary = [&](int b) {
        if (b == 0 || b == threads) return b == 0 ? 0 : n;
        return std::max(std::min(n, 1), int(long(n) * b / threads / a * a));
      };
      const Range r{boundary(s), boundary(s + 1)};
      sh.ranges.push_back(r);
      int l = 0, h = 0;
      e->splitNodeSpan(r.begin, r.end, l, h);
      if (l < h) lo = std::min(lo, l), hi = std::max(hi, h);
    }
    sh.lo = lo < hi ? 3 * lo : 0;
    sh.hi = lo < hi ? 3 * hi : 0;
    if (s > 0) sh.fint.assign(std::size_t(sh.hi), 0.0), sh.fext.assign(std::size_t(sh.hi), 0.0);
  }
}

void ThreadedForces::evaluateShare(int s, const ForceContext& base) {
  Share& sh = shares_[std::size_t(s)];
  ForceContext ctx = base;
  ctx.minStableDt = std::numeric_limits<double>::infinity();
  ctx.strainEnergy = 0.0;
  if (s == 0) {
    std::fill(base.fint, base.fint + 3 * long(nodes_), 0.0);
    std::fill(base.fext, base.fext + 3 * long(nodes_), 0.0);
  } else {
    std::fill(sh.fint.begin() + sh.lo, sh.fint.begin() + sh.hi, 0.0);
    std::fill(sh.fext.begin() + sh.lo, sh.fext.begin() + sh.hi, 0.0);
    ctx.fint = sh.fint.data();
    ctx.fext = sh.fext.data();
  }
  for (std::size_t i = 0; i < split_.size(); ++i)
    split_[i]->addRange(ctx, sh.ranges[i].begin, sh.ranges[i].end);
  if (s == 0)
    for (const Effect* e : whole_) e->addForces(ctx);
  sh.dt = ctx.minStableDt;
  sh.energy = ctx.strainEnergy;
}

void ThreadedForces::gather(int s, double* fint, double* fext) const {
  const Share& own = shares_[std::size_t(s)];
  const int begin = 3 * own.nodeBegin, end = 3 * own.nodeEnd;
  for (std::size_t t = 1; t < shares_.size(); ++t) {
    const Share& sh = shares_[t];
    const int lo = std::max(begin, sh.lo), hi = std::min(end, sh.hi);
    const double* __restrict bi = sh.fint.data();
    const double* __restrict be = sh.fext.data();
    for (int d = lo; d < hi; ++d) {
      fint[d] += bi[d];
      fext[d] += be[d];
    }
  }
}

double ThreadedForces::minStableDt() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const Share& sh : shares_) dt = std::min(dt, sh.dt);
  return dt;
}

double ThreadedForces::strainEnergy() const {
  double e = 0.0;
  for (const Share& sh : shares_) e += sh.energy;
  return e;
}

ForceContext ThreadedForces::evaluate(Nodes& nodes, double time, double loadFactor, bool wantEnergy) {
  if (serial()) return evaluateEffects(nodes, effects_, time, loadFactor, wantEnergy);
  ForceContext ctx = forceContextFor(nodes, time, loadFactor, wantEnergy);
#ifdef FSI_HAVE_OPENMP
  const int shares = this->shares();
#pragma omp parallel num_threads(shares)
  {
    // The runtime may give fewer threads than asked (nested regions, OMP_THREAD_LIMIT): a thread then takes
    // several shares.
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    for (int s = t; s < shares; s += nt) evaluateShare(s, ctx);
#pragma omp barrier
    for (int s = t; s < shares; s += nt) gather(s, ctx.fint, ctx.fext);
  }
#endif
  ctx.minStableDt = minStableDt();
  ctx.strainEnergy = strainEnergy();
  return ctx;
}

}  // namespace fsi::structure
