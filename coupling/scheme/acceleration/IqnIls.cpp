#include "coupling/scheme/acceleration/IqnIls.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "structure/model/Error.hpp"

namespace fsi::coupling {

IqnIls::IqnIls(IqnIlsOptions options) : opt_(options) {
  if (!(opt_.initialOmega > 0.0 && opt_.initialOmega <= 1.0))
    throw std::invalid_argument(
        fmt::format("IqnIls: initialOmega = {:g}, valid: 0 < initialOmega <= 1", opt_.initialOmega));
  if (opt_.reuseSteps < 0)
    throw std::invalid_argument(fmt::format("IqnIls: reuseSteps = {}, valid: >= 0", opt_.reuseSteps));
  if (opt_.maxColumns < 1)
    throw std::invalid_argument(fmt::format("IqnIls: maxColumns = {}, valid: >= 1", opt_.maxColumns));
  if (!(opt_.filterTolerance >= 0)) throw std::invalid_argument("IqnIls: filterTolerance must be >= 0");
  if (!(opt_.maxStepRatio >= 1)) throw std::invalid_argument("IqnIls: maxStepRatio must be >= 1");
}

std::string IqnIls::name() const {
  return opt_.reuseSteps > 0 ? "iqn-ils(q=" + std::to_string(opt_.reuseSteps) + ")" : "iqn-ils";
}

Eigen::VectorXd IqnIls::relax(const Eigen::VectorXd& d, const Eigen::VectorXd& r) const {
  return d + opt_.initialOmega * r;
}

Eigen::VectorXd IqnIls::compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) {
  Eigen::VectorXd r = dTilde - d;
  if (iteration_ > 0) {
    current_.v.push_front(r - previousResidual_);
    current_.w.push_front(dTilde - previousOutput_);
    if (int(current_.v.size()) > opt_.maxColumns) {
      current_.v.pop_back();
      current_.w.pop_back();
    }
  }
  previousResidual_ = r;
  previousOutput_ = dTilde;
  const bool first = iteration_ == 0;
  ++iteration_;
  lastColumnsUsed_ = lastColumnsFiltered_ = 0;
  if (first && (opt_.relaxFirstIteration || past_.empty())) return relax(d, r);

  Eigen::VectorXd next = quasiNewtonStep(r, dTilde, true);
  if (next.size() == 0) return relax(d, r);
  // This window's own columns are trusted whatever the step's length (a slow mode, |J| near 1, legitimately
  // asks for steps many residuals long); the reused ones only while the step stays within maxStepRatio |r|.
  const bool finite = next.allFinite();
  if (finite && (past_.empty() || (next - d).norm() <= opt_.maxStepRatio * r.norm())) return next;
  past_.clear();
  next = quasiNewtonStep(r, dTilde, false);
  return next.size() != 0 && next.allFinite() ? next : relax(d, r);
}

Eigen::VectorXd IqnIls::quasiNewtonStep(const Eigen::VectorXd& r, const Eigen::VectorXd& dTilde,
                                        bool withReused) {
  const Eigen::Index n = r.size();
  lastColumnsUsed_ = lastColumnsFiltered_ = 0;
  // Candidate columns newest first: this window, then the reused windows from the newest.
  std::vector<const Eigen::VectorXd*> cv, cw;
  auto take = [&](const Columns& c) {
    for (std::size_t i = 0; i < c.v.size() && int(cv.size()) < opt_.maxColumns; ++i) {
      if (c.v[i].size() != n) continue;  // the interface changed size: old columns are meaningless
      cv.push_back(&c.v[i]);
      cw.push_back(&c.w[i]);
    }
  };
  take(current_);
  if (withReused)
    for (const Columns& c : past_) take(c);

  // Filter by modified Gram-Schmidt: an older column that adds (almost) nothing to the span of the newer
  // ones would make R ill-conditioned and the coefficients c meaningless.
  std::vector<Eigen::VectorXd> q;
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < cv.size(); ++i) {
    const double norm0 = cv[i]->norm();
    if (!(norm0 > 0.0)) continue;
    Eigen::VectorXd v = *cv[i];
    for (const Eigen::VectorXd& qj : q) v -= qj.dot(v) * qj;
    const double norm1 = v.norm();
    if (norm1 <= opt_.filterTolerance * norm0) continue;
    q.push_back(v / norm1);
    kept.push_back(i);
  }
  lastColumnsFiltered_ = int(cv.size() - kept.size());
  if (kept.empty()) return {};

  Eigen::MatrixXd V(n, Eigen::Index(kept.size())), W(n, Eigen::Index(kept.size()));
  for (std::size_t j = 0; j < kept.size(); ++j) {
    V.col(Eigen::Index(j)) = *cv[kept[j]];
    W.col(Eigen::Index(j)) = *cw[kept[j]];
  }
  lastColumnsUsed_ = int(kept.size());
  const Eigen::VectorXd c = V.householderQr().solve(-r);
  return dTilde + W * c;
}

void IqnIls::onTimeWindowComplete(bool converged) {
  if (!converged)
    past_.clear();  // neither this window's columns nor the older ones describe where the next one starts
  else if (opt_.reuseSteps > 0) {
    past_.push_front(std::move(current_));
    while (int(past_.size()) > opt_.reuseSteps) past_.pop_back();
  }
  current_ = Columns{};
  iteration_ = 0;
}

Acceleration::State IqnIls::state() const {
  State s;
  std::vector<double>& counts = s["past_columns"];
  std::vector<double>& v = s["past_v"];
  std::vector<double>& w = s["past_w"];
  for (const Columns& c : past_) {
    counts.push_back(double(c.v.size()));
    for (std::size_t i = 0; i < c.v.size(); ++i) {
      v.insert(v.end(), c.v[i].data(), c.v[i].data() + c.v[i].size());
      w.insert(w.end(), c.w[i].data(), c.w[i].data() + c.w[i].size());
    }
  }
  return s;
}

void IqnIls::restore(const State& state) {
  auto array = [&](const char* name) -> const std::vector<double>& {
    const auto it = state.find(name);
    if (it == state.end()) throw InputError(fmt::format("IQN-ILS state: the array {} is missing", name));
    for (std::size_t i = 0; i < it->second.size(); ++i)
      if (!std::isfinite(it->second[i]))
        throw InputError(fmt::format("IQN-ILS state: {}[{}] is not finite ({})", name, i, it->second[i]));
    return it->second;
  };
  const std::vector<double>& counts = array("past_columns");
  const std::vector<double>& v = array("past_v");
  const std::vector<double>& w = array("past_w");
  std::size_t columns = 0;
  for (double c : counts) {
    if (!(c >= 0 && c <= opt_.maxColumns && c == std::floor(c)))
      throw InputError(
          fmt::format("IQN-ILS state: past_columns holds {}, not a column count 0..{}", c, opt_.maxColumns));
    columns += std::size_t(c);
  }
  if (v.size() != w.size() || (columns == 0 ? !v.empty() : v.size() % columns != 0))
    throw InputError(
        fmt::format("IQN-ILS state: past_v ({} values) and past_w ({}) do not hold {} columns of "
                    "one length",
                    v.size(), w.size(), columns));
  const std::size_t n = columns == 0 ? 0 : v.size() / columns;
  past_.clear();
  std::size_t at = 0;
  // Only as many windows as this run reuses (a run restarted with a smaller `reuse` keeps the newest).
  for (std::size_t k = 0; k < counts.size() && int(k) < opt_.reuseSteps; ++k) {
    Columns c;
    for (std::size_t i = 0; i < std::size_t(counts[k]); ++i, at += n) {
      c.v.emplace_back(Eigen::Map<const Eigen::VectorXd>(v.data() + at, Eigen::Index(n)));
      c.w.emplace_back(Eigen::Map<const Eigen::VectorXd>(w.data() + at, Eigen::Index(n)));
    }
    past_.push_back(std::move(c));
  }
  current_ = Columns{};
  iteration_ = 0;
}

AccelerationEntry iqnIlsEntry() {
  return {"IQN-ILS",
          "interface quasi-Newton, inverse Jacobian by least squares",
          {omegaOption("0.1", "relaxation factor of a window's first iteration"),
           integerOption("reuse", "0", Bound{0, true}, std::nullopt,
                         "also use the columns of this many past windows (8 suits a canopy)")},
          [](const OptionValues& v) -> std::unique_ptr<Acceleration> {
            IqnIlsOptions o;
            o.initialOmega = v.real("omega");
            o.reuseSteps = int(v.integer("reuse"));
            return std::make_unique<IqnIls>(o);
          }};
}

}  // namespace fsi::coupling
