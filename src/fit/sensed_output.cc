#include "fit/sensed_output.h"

namespace beamid::fit {

std::optional<std::string> sensed_validation_error(const signal::SensorFilter& sensor,
                                                   const simulation::Experiment& experiment) {
  if (auto error = signal::validation_error(sensor, experiment.dt_s)) return error;
  if (sensor.cutoff_hz > 0 && experiment.excitation == simulation::kFreeDecay)
    return "sensor filter in the model: a free decay's amplitudes are solved against the data from an unknown state, "
           "which the filter's transient would not match (give a pulse, pluck or sampled force)";
  return std::nullopt;
}

simulation::Experiment simulated_experiment(const simulation::Experiment& record, const signal::SensorFilter& sensor) {
  return sensor.cutoff_hz > 0 ? simulation::finer(record, sensor.oversampling) : record;
}

void sense_output(const signal::SensorFilter& sensor, double dt_s, std::vector<double>& y) {
  if (sensor.cutoff_hz > 0) y = signal::sense(sensor, y, dt_s);
}

void sense_columns(const signal::SensorFilter& sensor, double dt_s, Eigen::MatrixXd& columns) {
  if (!(sensor.cutoff_hz > 0)) return;
  const Eigen::Index fine = columns.rows();
  Eigen::MatrixXd sensed(fine / sensor.oversampling, columns.cols());
  std::vector<double> column(static_cast<std::size_t>(fine));
  for (Eigen::Index k = 0; k < columns.cols(); ++k) {
    Eigen::VectorXd::Map(column.data(), fine) = columns.col(k);
    const std::vector<double> out = signal::sense(sensor, column, dt_s);
    sensed.col(k) = Eigen::VectorXd::Map(out.data(), static_cast<Eigen::Index>(out.size()));
  }
  columns = std::move(sensed);
}

}  // namespace beamid::fit
