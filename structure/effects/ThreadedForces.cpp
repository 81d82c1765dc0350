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
    : effects_(std::move(effects)), scratch_(effects_) {
  // From each effect's connectivity alone: which split (a light one never decides the threading; a
  // scattered one splits only with enough items to decide it), which have a first pass, which run whole.
  int largest = -1, most = 0;
  for (std::size_t i = 0; i < effects_.size(); ++i) {
    const Connectivity c = effects_[i]->connectivity();
    if (c.items > 0 && !(c.scattered && c.items < kMinParallelItems)) {
      if (!c.light && c.items > most) most = c.items, largest = int(split_.size());
      split_.push_back({effects_[i], c, scratch_.of(i)});
      if (c.prepass) prepasses_ = std::max(prepasses_, c.prepasses);
    } else {
      whole_.push_back({effects_[i], c, scratch_.of(i)});
    }
  }
  if (threads <= 1 || !threadsAvailable() || most < kMinParallelItems) return;
  shares_.resize(std::size_t(threads));

  // Equal element counts, boundaries on whole batches; the last share takes the remainder.
  auto range = [&](const Connectivity& c, int s, int& begin, int& end) {
    const int n = c.items, a = c.batch;
    auto boundary = [&](int b) {
      if (b == 0 || b == threads) return b == 0 ? 0 : n;
      return std::max(std::min(n, 1), int(long(n) * b / threads / a * a));
    };
    begin = boundary(s), end = boundary(s + 1);
  };
  // The bands start at the lowest node of each share's first element of the largest effect (sorted by
  // lowest node, so increasing; kept increasing whatever the order).
  std::vector<int> cut(std::size_t(threads) + 1, nodes);
  cut[0] = 0;
  std::vector<int> en;
  for (int s = 1; s < threads; ++s) {
    int b = 0, e = 0;
    const Connectivity& c = split_[std::size_t(largest)].items;
    range(c, s, b, e);
    int lo = cut[std::size_t(s) - 1];
    if (b < e) {
      en.clear();
      c.appendNodes(b, en);
      if (!en.empty()) lo = std::max(lo, *std::min_element(en.begin(), en.end()));
    }
    cut[std::size_t(s)] = std::min(lo, nodes);
  }

  for (int s = 0; s < threads; ++s) {
    Share& sh = shares_[std::size_t(s)];
    sh.nodeBegin = cut[std::size_t(s)];
    sh.nodeEnd = cut[std::size_t(s) + 1];
    std::vector<int> seamNodes;
    for (std::size_t i = 0; i < split_.size(); ++i) {
      const Connectivity& c = split_[i].items;
      int b = 0, end = 0;
      range(c, s, b, end);
      // Blocks of whole batches: a block writes directly when all its elements stay in the band.
      const int a = std::max(1, c.batch);
      for (int j = b; j < end;) {
        const int blockEnd = std::min(end, (j / a + 1) * a);
        en.clear();
        for (int k = j; k < blockEnd; ++k) c.appendNodes(k, en);
        const bool direct = std::all_of(en.begin(), en.end(),
                                        [&](int node) { return node >= sh.nodeBegin && node < sh.nodeEnd; });
        if (!direct) seamNodes.insert(seamNodes.end(), en.begin(), en.end());
        if (!sh.runs.empty() && sh.runs.back().effect == int(i) && sh.runs.back().direct == direct &&
            sh.runs.back().end == j)
          sh.runs.back().end = blockEnd;
        else
          sh.runs.push_back({int(i), j, blockEnd, direct});
        j = blockEnd;
      }
    }
    std::sort(seamNodes.begin(), seamNodes.end());
    seamNodes.erase(std::unique(seamNodes.begin(), seamNodes.end()), seamNodes.end());
    sh.touched = std::move(seamNodes);
    if (!sh.touched.empty()) {
      // Indexed by dof, as the node arrays: the kernels write through the same node numbers. Left
      // uninitialised: only the touched nodes' pages are ever written (and so mapped).
      const std::size_t size = 3 * std::size_t(sh.touched.back() + 1);
      sh.fint.reset(new double[size]);
      sh.fext.reset(new double[size]);
    }
  }
}

void ThreadedForces::evaluateShare(int s, const ForceContext& base) {
  Share& sh = shares_[std::size_t(s)];
  ForceContext ctx = base;
  ctx.minStableDt = std::numeric_limits<double>::infinity();
  ctx.strainEnergy = 0.0;
  std::fill(base.fint + 3 * long(sh.nodeBegin), base.fint + 3 * long(sh.nodeEnd), 0.0);
  std::fill(base.fext + 3 * long(sh.nodeBegin), base.fext + 3 * long(sh.nodeEnd), 0.0);
  for (int node : sh.touched)
    for (int k = 0; k < 3; ++k) sh.fint[3 * std::size_t(node) + k] = sh.fext[3 * std::size_t(node) + k] = 0.0;
  for (const Run& r : sh.runs) {
    ctx.fint = r.direct ? base.fint : sh.fint.get();
    ctx.fext = r.direct ? base.fext : sh.fext.get();
    const Part& p = split_[std::size_t(r.effect)];
    ctx.scratch = p.scratch;
    p.effect->addRange(ctx, r.begin, r.end);
  }
  sh.dt = ctx.minStableDt;
  sh.energy = ctx.strainEnergy;
}

void ThreadedForces::evaluateWhole(const ForceContext& base) {
  ForceContext ctx = base;
  ctx.minStableDt = std::numeric_limits<double>::infinity();
  ctx.strainEnergy = 0.0;
  for (const Part& p : whole_) {
    ctx.scratch = p.scratch;
    p.effect->addForces(ctx);
  }
  wholeDt_ = ctx.minStableDt;
  wholeEnergy_ = ctx.strainEnergy;
}

void ThreadedForces::evaluateShares(int t, int nt, const ForceContext& base) {
  const int shares = this->shares();
  for (int pass = 0; pass < prepasses_; ++pass) {
    ForceContext ctx = base;
    ctx.pass = pass;
    for (int s = t; s < shares; s += nt)
      for (const Part& p : split_) {
        if (!p.items.prepass || pass >= p.items.prepasses) continue;
        // Ranges on whole batches too (a batched first pass writes its batches whole); the last takes the
        // rest.
        const long n = p.items.items, a = std::max(1, p.items.batch);
        const auto cut = [&](long b) { return b >= shares ? n : n * b / shares / a * a; };
        ctx.scratch = p.scratch;
        p.effect->prepareRange(ctx, int(cut(s)), int(cut(s + 1)));
      }
#ifdef FSI_HAVE_OPENMP
#pragma omp barrier
#endif
  }
  for (int s = t; s < shares; s += nt) evaluateShare(s, base);
  if (whole_.empty()) return;
#ifdef FSI_HAVE_OPENMP
#pragma omp barrier
#endif
  if (t == 0) evaluateWhole(base);
}

void ThreadedForces::gather(int s, double* fint, double* fext) const {
  const Share& own = shares_[std::size_t(s)];
  for (const Share& sh : shares_) {
    const auto first = std::lower_bound(sh.touched.begin(), sh.touched.end(), own.nodeBegin);
    const auto last = std::lower_bound(first, sh.touched.end(), own.nodeEnd);
    const double* __restrict bi = sh.fint.get();
    const double* __restrict be = sh.fext.get();
    for (auto it = first; it != last; ++it)
      for (std::size_t d = 3 * std::size_t(*it), dEnd = d + 3; d < dEnd; ++d) {
        fint[d] += bi[d];
        fext[d] += be[d];
      }
  }
}

double ThreadedForces::minStableDt() const {
  double dt = whole_.empty() ? std::numeric_limits<double>::infinity() : wholeDt_;
  for (const Share& sh : shares_) dt = std::min(dt, sh.dt);
  return dt;
}

double ThreadedForces::strainEnergy() const {
  double e = 0.0;
  for (const Share& sh : shares_) e += sh.energy;
  return whole_.empty() ? e : e + wholeEnergy_;
}

long ThreadedForces::seamElements() const {
  long n = 0;
  for (const Share& sh : shares_)
    for (const Run& r : sh.runs) n += r.direct ? 0 : r.end - r.begin;
  return n;
}

long ThreadedForces::splitElements() const {
  long n = 0;
  for (const Part& p : split_) n += p.items.items;
  return n;
}

ForceContext ThreadedForces::evaluate(Nodes& nodes, double time, double loadFactor, bool wantEnergy) {
  if (serial()) return evaluateEffects(nodes, effects_, scratch_, time, loadFactor, wantEnergy);
  ForceContext ctx = forceContextFor(nodes, time, loadFactor, wantEnergy);
#ifdef FSI_HAVE_OPENMP
  const int shares = this->shares();
#pragma omp parallel num_threads(shares)
  {
    // The runtime may give fewer threads than asked (nested regions, OMP_THREAD_LIMIT): a thread then takes
    // several shares.
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    evaluateShares(t, nt, ctx);
#pragma omp barrier
    for (int s = t; s < shares; s += nt) gather(s, ctx.fint, ctx.fext);
  }
#endif
  ctx.minStableDt = minStableDt();
  ctx.strainEnergy = strainEnergy();
  return ctx;
}

}  // namespace fsi::structure
