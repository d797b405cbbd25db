#include "identification/identify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <ceres/ceres.h>

#include "studies/parallel.h"
#include "model/spec/constants.h"

namespace turbodyn::identification {
namespace {

// Maps scaled parameters x (what Ceres sees) to values in the parameters' units and back.
struct ParameterScaling {
  std::vector<double> offset, factor;  // v = offset + factor * x

  explicit ParameterScaling(const IdentifyStudy& s) {
    for (const ParameterSpec& p : s.parameters) {
      if (s.solver.scaling == identification::Scaling::Start) {
        offset.push_back(0.0);
        factor.push_back(p.start);
      } else {
        offset.push_back(p.lower);
        factor.push_back(p.upper - p.lower);
      }
    }
  }
  std::vector<double> values(const double* x) const {
    std::vector<double> v(offset.size());
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = offset[i] + factor[i] * x[i];
    return v;
  }
  double scaled(std::size_t i, double v) const { return (v - offset[i]) / factor[i]; }
};

// Everything the cost function needs; model runs are cached by their exact scaled parameter vector.
class Problem {
 public:
  Problem(const IdentifyStudy& s, const Evaluator& ev, const Residuals& res, const ParameterScaling& sc, int threads,
          const std::atomic<bool>* cancel)
      : study_(s), evaluator_(ev), residuals_(res), scaling_(sc), threads_(threads), cancel_(cancel) {}

  // Residuals at every point (nullopt where the model run failed); runs the points not cached yet in parallel.
  std::vector<std::optional<std::vector<double>>> residuals(const std::vector<std::vector<double>>& points) {
    std::vector<std::optional<std::vector<double>>> out(points.size());
    std::vector<std::size_t> todo;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (std::size_t i = 0; i < points.size(); ++i) {
        const auto it = cache_.find(points[i]);
        if (it != cache_.end()) out[i] = it->second;
        else if (std::find_if(todo.begin(), todo.end(), [&](std::size_t j) { return points[j] == points[i]; }) == todo.end())
          todo.push_back(i);
      }
    }
    std::vector<std::optional<std::vector<double>>> fresh(todo.size());
    std::vector<std::string> errors(todo.size());
    studies::parallel_runs(todo.size(), threads_, [&](std::size_t k) {
      const Evaluation ev = evaluator_.evaluate(scaling_.values(points[todo[k]].data()), false, cancel_);
      if (!ev.ok) {
        errors[k] = ev.error;
        return;
      }
      std::vector<double> r(residuals_.size());
      if (residuals_.evaluate(ev.features, r.data())) fresh[k] = std::move(r);
      else errors[k] = "a model feature is undefined (NaN) at one of the compared speeds";
    });
    std::lock_guard<std::mutex> lock(mutex_);
    const bool cancelled = cancel_ && cancel_->load();
    for (std::size_t k = 0; k < todo.size(); ++k) {
      if (!fresh[k] && cancelled) continue;  // stopped by Ctrl-C: neither a result nor a finished run
      if (!fresh[k]) last_error_ = errors[k];
      cache_[points[todo[k]]] = fresh[k];
      ++runs_;
    }
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!out[i]) {
        const auto it = cache_.find(points[i]);
        if (it != cache_.end()) out[i] = it->second;
      }
    return out;
  }

  std::size_t runs() const { return runs_; }
  const std::string& last_error() const { return last_error_; }
  int threads() const { return threads_; }

 private:
  const IdentifyStudy& study_;
  const Evaluator& evaluator_;
  const Residuals& residuals_;
  const ParameterScaling& scaling_;
  int threads_;
  const std::atomic<bool>* cancel_;
  std::mutex mutex_;
  std::map<std::vector<double>, std::optional<std::vector<double>>> cache_;
  std::size_t runs_ = 0;
  std::string last_error_;
};

// The whole residual vector as one Ceres cost function of one parameter block; the Jacobian by our own finite
// differences, whose model runs go in parallel.
class FiniteDifferenceCost final : public ceres::CostFunction {
 public:
  FiniteDifferenceCost(Problem& p, std::size_t n, std::size_t m, double step, bool central,
                       std::vector<double> upper)
      : problem_(p), n_(n), step_(step), central_(central), upper_(std::move(upper)) {
    set_num_residuals(static_cast<int>(m));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(n));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const std::vector<double> x(parameters[0], parameters[0] + n_);
    const bool jac = jacobians && jacobians[0];
    std::vector<std::vector<double>> points{x};
    std::vector<double> h(n_, step_);
    if (jac) {
      for (std::size_t i = 0; i < n_; ++i) {
        // Forward step, or backward where the forward one would leave the upper bound.
        if (!central_ && x[i] + step_ > upper_[i]) h[i] = -step_;
        std::vector<double> xp = x;
        xp[i] += h[i];
        points.push_back(xp);
        if (central_) {
          std::vector<double> xm = x;
          xm[i] -= h[i];
          points.push_back(xm);
        }
      }
    }
    const auto r = problem_.residuals(points);
    if (!r[0]) return false;
    const std::vector<double>& r0 = *r[0];
    std::copy(r0.begin(), r0.end(), residuals);
    if (!jac) return true;
    const std::size_t m = r0.size();
    for (std::size_t i = 0; i < n_; ++i) {
      const std::size_t a = central_ ? 1 + 2 * i : 1 + i;
      if (!r[a] || (central_ && !r[a + 1])) return false;
      for (std::size_t k = 0; k < m; ++k) {
        const double d = central_ ? ((*r[a])[k] - (*r[a + 1])[k]) / (2.0 * h[i]) : ((*r[a])[k] - r0[k]) / h[i];
        jacobians[0][k * n_ + i] = d;
      }
    }
    return true;
  }

 private:
  Problem& problem_;
  std::size_t n_;
  double step_;
  bool central_;
  std::vector<double> upper_;
};

class Progress final : public ceres::IterationCallback {
 public:
  Progress(const IdentifyOptions& o, const ParameterScaling& s, const IdentifyStudy& st, const double* x, const Problem& p)
      : options_(o), scaling_(s), study_(st), x_(x), problem_(p) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& it) override {
    last_values_ = scaling_.values(x_);  // the state after this iteration (update_state_every_iteration)
    if (options_.progress) {
      std::ostringstream os;
      os << "iteration " << std::setw(3) << it.iteration << "  cost " << std::scientific << std::setprecision(4)
         << it.cost << "  |gradient| " << it.gradient_max_norm << "  model runs " << problem_.runs() << " ";
      const std::vector<double>& v = last_values_;
      os << std::defaultfloat << std::setprecision(6);
      for (std::size_t i = 0; i < v.size(); ++i)
        os << " " << study_.parameters[i].name << " = " << v[i]
           << (study_.parameters[i].unit.empty() ? "" : " " + study_.parameters[i].unit);
      options_.progress(os.str());
    }
    if (options_.cancel && options_.cancel->load()) return ceres::SOLVER_ABORT;
    return ceres::SOLVER_CONTINUE;
  }
  /// The parameter values after the last finished iteration (empty before the first).
  const std::vector<double>& last_values() const { return last_values_; }

 private:
  const IdentifyOptions& options_;
  const ParameterScaling& scaling_;
  const IdentifyStudy& study_;
  const double* x_;
  const Problem& problem_;
  std::vector<double> last_values_;
};

double resolution_of(const IdentifyStudy& s, const MeasuredData& m) {
  if (m.format == MeasurementFormat::TimeSeries) return m.record.sample_rate / static_cast<double>(s.processing.segment);
  std::vector<double> d;
  for (const auto& f : m.spectra.frequency_hz)
    for (std::size_t k = 1; k < f.size(); ++k) d.push_back(f[k] - f[k - 1]);
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

}  // namespace

std::vector<Override> measured_speed_table(const Record& record, std::size_t max_points) {
  const std::size_t n = record.time.size();
  if (n < 2 || record.speed_hz.size() != n)
    throw ModelError("identify.speed = \"measured\": the measured record has no speed history");
  const std::size_t points = std::max<std::size_t>(2, std::min(max_points, n));
  const std::size_t half = (n / points) / 2;  // half-width of the block each point's speed is averaged over
  std::string times = "[", speeds = "[";
  for (std::size_t k = 0; k < points; ++k) {
    // Point k: the first and last samples exactly in time; the speed a mean over the block around the point (tacho
    // speeds jitter from pulse to pulse), clamped at zero.
    const std::size_t i = k * (n - 1) / (points - 1);
    const std::size_t a = i > half ? i - half : 0, b = std::min(n - 1, i + half);
    double mean = 0.0;
    for (std::size_t j = a; j <= b; ++j) mean += record.speed_hz[j];
    mean /= static_cast<double>(b - a + 1);
    times += (k ? ", " : "") + format_value(record.time[i] - record.time.front(), "");
    speeds += (k ? ", " : "") + format_value(2.0 * M_PI * std::max(0.0, mean), "");
  }
  // The whole [speed] table is replaced (a ramp's start, end and duration do not belong in a table profile).
  return {{"speed", "{profile = \"table\", times = " + times + "], speeds = " + speeds + "]}"}};
}

IdentifyResult identify(const IdentifyStudy& study, const IdentifyOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  IdentifyResult out;
  const std::size_t n = study.parameters.size();

  // Measurement and its features.
  out.measured = read_measurement(study.measurement);
  if (out.measured.resampled)
    out.warnings.push_back("the measured time steps are uneven: resampled linearly at the mean rate");
  try {
    if (out.measured.format == MeasurementFormat::TimeSeries)
      out.measured_features = features_from_record(study.features, study.processing, out.measured.record,
                                                   study.measurement.has_phase_reference());
    else
      out.measured_features = features_from_spectra(study.features, out.measured.spectra);
  } catch (const std::invalid_argument& e) {
    throw ModelError(study.measurement.file.string() + ": cannot extract the features: " + e.what());
  }
  for (std::size_t f = 0; f < study.features.size(); ++f) {
    // Speeds without a measured value: beyond the speeds the record's analysis windows (each wholly inside the
    // record) or the measured spectra cover. Named, so a user sees which end of the speed range to move.
    const FeatureTrack& t = out.measured_features[f];
    std::size_t missing = 0;
    std::string which;
    for (std::size_t k = 0; k < t.amplitude.size(); ++k) {
      if (std::isfinite(t.amplitude[k])) continue;
      if (missing++ < 4) which += (which.empty() ? "" : ", ") + std::to_string(std::lround(t.speed_hz[k] * 60.0));
    }
    if (missing > 4) which += ", ...";
    if (missing)
      out.warnings.push_back("feature '" + study.features[f].name + "': " + std::to_string(missing) + " of its " +
                             std::to_string(t.amplitude.size()) + " speeds (" + which +
                             " rpm) have no measured value (beyond the speeds the measured record's analysis "
                             "windows or spectra cover) and are not compared");
  }
  const Residuals residuals(study.features, out.measured_features, resolution_of(study, out.measured));
  out.rows = residuals.rows();
  out.amplitude_scales = residuals.amplitude_scales();
  out.n_residuals = residuals.size();
  if (residuals.size() < n)
    throw ModelError(study.source.string() + ": " + std::to_string(residuals.size()) + " residuals for " +
                     std::to_string(n) + " parameters; compare more speeds or features");

  // With identify.speed = "measured", every run-up follows the measured speed: the study as run carries it.
  IdentifyStudy run_study = study;
  if (study.speed_from_measurement) {
    out.added_fixed = measured_speed_table(out.measured.record);
    run_study.fixed.insert(run_study.fixed.end(), out.added_fixed.begin(), out.added_fixed.end());
  }
  const Evaluator evaluator(run_study);
  const ParameterScaling scaling(study);
  const int threads = studies::run_threads(options.threads, study.threads);
  out.threads = threads;
  Problem problem(study, evaluator, residuals, scaling, threads, options.cancel);

  std::vector<double> x(n), lower(n), upper(n);
  for (std::size_t i = 0; i < n; ++i) {
    const ParameterSpec& p = study.parameters[i];
    out.start.push_back(p.start);
    x[i] = scaling.scaled(i, p.start);
    lower[i] = scaling.scaled(i, p.lower);
    upper[i] = scaling.scaled(i, p.upper);
  }
  {  // The start point must evaluate: a clear error now beats a Ceres failure later.
    const auto r = problem.residuals({x});
    if (!r[0])
      throw ModelError(study.source.string() + ": the model cannot be evaluated at the start values: " +
                       problem.last_error());
  }

  ceres::Problem::Options po;
  ceres::Problem cp(po);
  ceres::LossFunction* loss = nullptr;
  switch (study.solver.loss) {
    case Loss::None: break;
    case Loss::Huber: loss = new ceres::HuberLoss(study.solver.loss_scale); break;
    case Loss::Cauchy: loss = new ceres::CauchyLoss(study.solver.loss_scale); break;
    case Loss::SoftLOne: loss = new ceres::SoftLOneLoss(study.solver.loss_scale); break;
  }
  cp.AddResidualBlock(new FiniteDifferenceCost(problem, n, residuals.size(), study.solver.step, study.solver.central, upper),
                      loss, x.data());
  for (std::size_t i = 0; i < n; ++i) {
    cp.SetParameterLowerBound(x.data(), static_cast<int>(i), lower[i]);
    cp.SetParameterUpperBound(x.data(), static_cast<int>(i), upper[i]);
  }
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = study.solver.max_iterations;
  so.function_tolerance = study.solver.function_tolerance;
  so.parameter_tolerance = study.solver.parameter_tolerance;
  so.gradient_tolerance = study.solver.gradient_tolerance;
  so.num_threads = 1;  // one residual block: the parallelism is in the model runs
  so.logging_type = ceres::SILENT;
  so.update_state_every_iteration = true;  // so the progress line shows the current estimate
  Progress progress(options, scaling, study, x.data(), problem);
  so.callbacks.push_back(&progress);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &cp, &summary);
  out.cancelled = options.cancel && options.cancel->load();

  out.full_report = summary.FullReport();
  out.brief_report = summary.BriefReport();
  out.termination = summary.message;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  // An aborted solve (Ctrl-C) leaves the parameter blocks as Ceres chooses: report the last finished iteration.
  out.estimate = out.cancelled && !progress.last_values().empty() ? progress.last_values() : scaling.values(x.data());
  if (!summary.IsSolutionUsable())
    out.warnings.push_back("Ceres found no usable solution: " + summary.message +
                           (problem.last_error().empty() ? "" : " (last model failure: " + problem.last_error() + ")"));

  // Covariance at the estimate, scaled by the residual variance, in parameter units.
  const std::size_t m = residuals.size();
  out.residual_variance = m > n ? 2.0 * summary.final_cost / static_cast<double>(m - n) : kNaN;
  out.std_dev.assign(n, kNaN);
  if (!out.cancelled && summary.IsSolutionUsable()) {
    ceres::Covariance::Options co;
    co.algorithm_type = ceres::DENSE_SVD;
    co.num_threads = 1;
    ceres::Covariance cov(co);
    const std::vector<std::pair<const double*, const double*>> blocks{{x.data(), x.data()}};
    if (m > n && cov.Compute(blocks, &cp)) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(n, n);
      cov.GetCovarianceBlock(x.data(), x.data(), c.data());
      out.covariance.resize(n, n);
      out.correlation.resize(n, n);
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          out.covariance(i, j) = c(i, j) * out.residual_variance * scaling.factor[i] * scaling.factor[j];
      for (std::size_t i = 0; i < n; ++i) out.std_dev[i] = std::sqrt(out.covariance(i, i));
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j)
          out.correlation(i, j) = out.covariance(i, j) / (out.std_dev[i] * out.std_dev[j]);
      out.covariance_ok = true;
    } else {
      out.covariance_message = m <= n ? "no more residuals than parameters"
                                      : "the Jacobian at the estimate is rank deficient (a parameter does not change "
                                        "the compared features, or two change them alike): no covariance";
      out.warnings.push_back(out.covariance_message);
    }
  }

  // Initial and fitted model, once more with their signals kept (for the pictures); in parallel.
  Evaluation initial, fitted;
  studies::parallel_runs(2, std::min(threads, 2), [&](std::size_t k) {
    if (k == 0) initial = evaluator.evaluate(out.start, true);
    else fitted = evaluator.evaluate(out.estimate, true);
  });
  if (!fitted.ok) throw ModelError("the model fails at the estimate: " + fitted.error);
  out.initial_features = initial.ok ? initial.features : std::vector<FeatureTrack>{};
  out.fitted_features = fitted.features;
  out.initial_record = std::move(initial.record);
  out.fitted_record = std::move(fitted.record);
  out.fitted_residuals.assign(m, kNaN);
  residuals.evaluate(out.fitted_features, out.fitted_residuals.data());
  out.model_runs = problem.runs() + 2;
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace turbodyn::identification
