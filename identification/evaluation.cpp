#include "identification/evaluation.h"

#include <chrono>
#include <cmath>
#include <complex>

#include "model/rotor/response.h"
#include "model/rotor/rotor.h"
#include "model/engine/integrator.h"
#include "studies/channels.h"
#include "studies/run_evaluation.h"
#include "studies/table.h"
#include "model/spec/constants.h"

namespace turbodyn::identification {
namespace {

// Steady-state response method: where a probe sits in the rotor's DOFs or bearing forces.
struct ResponseProbe {
  int dof = -1;       // rotor DOF (disk x/y)
  int bearing = -1;   // bearing index (fx/fy)
  bool y = false;
};

ResponseProbe response_probe(const Rotor& rotor, const std::string& probe) {
  ResponseProbe p;
  for (const RigidDisk& d : rotor.disks) {
    if (probe == "disk." + d.name + ".x") p.dof = rotor.dof(d.node, kX);
    if (probe == "disk." + d.name + ".y") p.dof = rotor.dof(d.node, kY);
  }
  for (std::size_t b = 0; b < rotor.bearings.size(); ++b) {
    if (probe == "bearing." + rotor.bearings[b].name + ".fx") p.bearing = static_cast<int>(b);
    if (probe == "bearing." + rotor.bearings[b].name + ".fy") {
      p.bearing = static_cast<int>(b);
      p.y = true;
    }
  }
  return p;
}

std::vector<std::string> response_probe_names(const Rotor& rotor) {
  std::vector<std::string> names;
  for (const RigidDisk& d : rotor.disks) names.insert(names.end(), {"disk." + d.name + ".x", "disk." + d.name + ".y"});
  for (const LinearBearing& b : rotor.bearings)
    names.insert(names.end(), {"bearing." + b.name + ".fx", "bearing." + b.name + ".fy"});
  return names;
}

void check_probe(const IdentifyStudy& s, std::size_t i, bool found, const std::vector<std::string>& names) {
  if (found) return;
  throw ModelError(s.source.string() + ": measurement.sensors[" + std::to_string(i) + "].probe: " +
                   studies::unknown_probe(s.measurement.sensors[i].probe, names));
}

// Second derivative by central differences (one-sided at the ends): acceleration from displacement.
std::vector<double> second_difference(const std::vector<double>& x, double fs) {
  const std::size_t n = x.size();
  std::vector<double> a(n, 0.0);
  if (n < 3) return a;
  for (std::size_t i = 1; i + 1 < n; ++i) a[i] = (x[i + 1] - 2.0 * x[i] + x[i - 1]) * fs * fs;
  a[0] = a[1];
  a[n - 1] = a[n - 2];
  return a;
}

}  // namespace

std::string format_value(double value, const std::string& unit) { return studies::value_text(value, unit); }

Evaluator::Evaluator(const IdentifyStudy& study) : study_(study) {
  with_phase_ = false;
  for (const FeatureSpec& f : study.features) with_phase_ = with_phase_ || f.phase;
  std::vector<double> start;
  for (const ParameterSpec& p : study.parameters) start.push_back(p.start);
  // The start values and both bounds must be accepted by the model loader (units, ranges).
  MachineSpec spec;
  try {
    spec = studies::load_base_model(study, overrides(start));
    std::vector<double> lo, hi;
    for (const ParameterSpec& p : study.parameters) {
      lo.push_back(p.lower);
      hi.push_back(p.upper);
    }
    (void)studies::load_base_model(study, overrides(lo));
    (void)studies::load_base_model(study, overrides(hi));
  } catch (const ModelError& e) {
    throw ModelError(study.source.string() + ": the parameters do not apply to the model: " + e.what());
  }
  std::vector<std::pair<std::string, std::string>> paths;
  for (std::size_t i = 0; i < study.parameters.size(); ++i)
    for (const std::string& p : study.parameters[i].paths)
      paths.emplace_back("parameters[" + std::to_string(i) + "].path", p);
  studies::check_varied_paths(study, overrides(start), paths);
  if (study.method == Method::Response) {
    for (const BearingSpec& b : spec.bearings)
      if (b.type != BearingType::Linear || b.pedestal_mass > 0.0 || b.damper.enabled)
        throw ModelError(study.source.string() + ": identify.method = \"response\" needs linear bearings without "
                         "pedestals or dampers; bearing '" + b.name + "' is " + to_string(b.type) + " (use method = \"runup\")");
    const Rotor rotor = build_rotor(spec);
    const std::vector<std::string> names = response_probe_names(rotor);
    for (std::size_t i = 0; i < study.measurement.sensors.size(); ++i) {
      const ResponseProbe p = response_probe(rotor, study.measurement.sensors[i].probe);
      check_probe(study, i, p.dof >= 0 || p.bearing >= 0, names);
    }
  } else {
    const auto model = make_runup_model(spec);
    const std::vector<std::string> names = studies::channel_names(model->channels());
    for (std::size_t i = 0; i < study.measurement.sensors.size(); ++i)
      check_probe(study, i, studies::find_channel(model->channels(), study.measurement.sensors[i].probe) >= 0, names);
  }
}

std::vector<Override> Evaluator::overrides(const std::vector<double>& values) const {
  std::vector<Override> o = study_.fixed;
  for (std::size_t p = 0; p < study_.parameters.size(); ++p)
    for (const std::string& path : study_.parameters[p].paths)
      o.push_back({path, format_value(values[p], study_.parameters[p].unit)});
  return o;
}

Evaluation Evaluator::evaluate(const std::vector<double>& values, bool keep_record,
                               const std::atomic<bool>* cancel) const {
  const auto t0 = std::chrono::steady_clock::now();
  Evaluation ev;
  try {
    const std::vector<SensorSpec>& sensors = study_.measurement.sensors;
    if (study_.method == Method::Response) {
      const Rotor rotor = build_rotor(studies::load_base_model(study_, overrides(values)));
      std::vector<ResponseProbe> probes;
      for (const SensorSpec& s : sensors) probes.push_back(response_probe(rotor, s.probe));
      auto response = [&](double speed_hz) {
        const double w = kTwoPi * speed_hz;
        const SteadyResponse r = unbalance_response(rotor, w);
        std::vector<std::complex<double>> z(sensors.size());
        for (std::size_t i = 0; i < sensors.size(); ++i) {
          const ResponseProbe& p = probes[i];
          z[i] = p.dof >= 0 ? r.q(p.dof) : p.y ? r.bearing_fy[p.bearing] : r.bearing_fx[p.bearing];
          if (sensors[i].quantity == Quantity::Acceleration) z[i] *= -w * w;
        }
        return z;
      };
      ev.features = features_from_response(study_.features, response, with_phase_);
    } else {
      studies::RunupRun run = studies::run_runup(study_, overrides(values), cancel);
      RunupResult& r = run.result;
      if (!r.complete) {
        ev.error = r.message.empty() ? "the run-up stopped early" : r.message;
        ev.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return ev;
      }
      Record rec;
      rec.sample_rate = run.options.sample_rate;
      rec.time = std::move(r.time);
      rec.speed_hz = r.columns[studies::kind_channel(r.channels, ProbeChannel::Kind::Speed)];
      rec.angle = r.columns[studies::kind_channel(r.channels, ProbeChannel::Kind::Angle)];
      for (const SensorSpec& s : sensors) {
        std::vector<double> x = r.columns[studies::find_channel(r.channels, s.probe)];
        if (s.quantity == Quantity::Acceleration) x = second_difference(x, rec.sample_rate);
        rec.channels.push_back(std::move(x));
      }
      if (study_.measurement.format == MeasurementFormat::Spectra)
        ev.features = features_from_spectra(study_.features, spectra_from_record(rec, study_.processing));
      else
        ev.features = features_from_record(study_.features, study_.processing, rec, with_phase_);
      if (keep_record) ev.record = std::move(rec);
    }
    ev.ok = true;
  } catch (const std::exception& e) {
    ev.error = e.what();
  }
  ev.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return ev;
}

}  // namespace turbodyn::identification
